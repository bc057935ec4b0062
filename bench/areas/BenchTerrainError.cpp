// `sylva bench terrain-error` (docs/terrain-lod.md, "Screen-space error"): distance LOD (the paper's rule)
// against screen-space-error LOD at the same measured worst error, on three fields.
#include "Bench.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/gpu/TerrainError.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

namespace sylva::bench {

namespace {

/** One field of the comparison: a name and how to get its heights. */
struct ErrorField {
  std::string name;
  std::function<terrain::HeightField()> heights;
};

/** Camera pose `index` over `field`: 10 m to 2 % of the span above the ground, looking slightly down. */
render::Camera errorBenchPose(const terrain::HeightField& field, int index) {
  Rng rng(0xE5B0ULL + static_cast<std::uint64_t>(index));
  const float span = std::max(field.extentX(), field.extentZ());
  const float x = rng.uniform(0.05f, 0.95f) * field.extentX();
  const float z = rng.uniform(0.05f, 0.95f) * field.extentZ();
  const float above = 10.0f * std::pow(std::max(1.0f, 0.02f * span / 10.0f), rng.uniform());
  render::Camera camera;
  camera.position = {x, terrain::heightAt(field, x, z) + above, z};
  const float yaw = rng.uniform(0.0f, 6.2831853f);
  const float pitch = rng.uniform(-0.5f, -0.05f);
  camera.target = camera.position + glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                              std::cos(pitch) * std::cos(yaw));
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = std::max(0.5f, 0.05f * above);
  camera.farPlane = 1.5f * span;
  return camera;
}

/** The layout both methods share: tessellation 16, finest vertices at the sample spacing, ~4 roots across. */
terrain::QuadtreeConfig sharedLayout(const terrain::HeightField& field) {
  terrain::QuadtreeConfig c;
  c.patchTessLevel = 16;
  const float spacing = std::min(field.spacingX(), field.spacingZ());
  const float extent = std::max(field.extentX(), field.extentZ());
  const float leaf = spacing * static_cast<float>(c.patchTessLevel);
  c.maxDepth = std::clamp(static_cast<int>(std::ceil(std::log2(0.25f * extent / leaf))), 0, 12);
  c.rootSize = std::ldexp(leaf, c.maxDepth);
  return c;
}

/** What one method's configuration gave over all poses. */
struct MethodRun {
  double worstPx = 0.0;
  double p999Px = 0.0; // largest per-pose 99.9th percentile
  bool failed = false; // stopped at the first pose over the target
};

/** The full-resolution reference of every pose: the view drawn with every patch at the deepest level. */
std::vector<Image> referenceViews(terrain::TerrainScene& scene, terrain::PositionTarget& target,
                                  const terrain::QuadtreeConfig& layout, int poses) {
  terrain::Quadtree full(layout.fullDepth(), scene.field());
  std::vector<Image> views;
  Progress progress("full-resolution reference views", static_cast<std::size_t>(poses));
  for (int i = 0; i < poses; ++i) {
    const render::Camera camera = errorBenchPose(scene.field(), i);
    const Frustum frustum = camera.frustum(target.aspect());
    views.push_back(target.draw(scene.renderer(), full.select(camera.position, &frustum), camera));
    progress.advance();
  }
  return views;
}

/** Measures the error of `config` over the poses; stops early once a pose exceeds `stopAbove` (> 0). */
MethodRun runErrors(terrain::TerrainScene& scene, terrain::PositionTarget& target,
                    const std::vector<Image>& references, const terrain::QuadtreeConfig& config,
                    double stopAbove) {
  terrain::Quadtree quadtree(config, scene.field());
  terrain::QuadtreeSelection selection;
  MethodRun run;
  const int poses = static_cast<int>(references.size());
  for (int i = 0; i < poses; ++i) {
    const render::Camera camera = errorBenchPose(scene.field(), i);
    const Frustum frustum = camera.frustum(target.aspect());
    quadtree.select(camera.position, &frustum, selection);
    const terrain::ScreenErrorStats e = target.measure(scene.renderer(), scene.field(), selection,
                                                       references[static_cast<std::size_t>(i)], camera);
    run.worstPx = std::max(run.worstPx, e.worstPx);
    run.p999Px = std::max(run.p999Px, e.p999Px);
    if (stopAbove > 0.0 && e.worstPx > stopAbove) {
      run.failed = true;
      break;
    }
  }
  return run;
}

/** The cheapest ladder entry whose worst error is ≤ target (binary search; errors fall along the ladder). */
struct Tuned {
  int index = -1; // -1: not even the last entry meets the target
  MethodRun run;
  int probes = 0;
};

Tuned tune(const std::vector<float>& ladder, const std::function<terrain::QuadtreeConfig(float)>& make,
           terrain::TerrainScene& scene, terrain::PositionTarget& target,
           const std::vector<Image>& references, double goal) {
  Tuned t;
  int lo = 0;
  int hi = static_cast<int>(ladder.size()) - 1;
  MethodRun best;
  bool found = false;
  while (lo <= hi) {
    const int mid = (lo + hi) / 2;
    const MethodRun r =
        runErrors(scene, target, references, make(ladder[static_cast<std::size_t>(mid)]), goal);
    ++t.probes;
    if (!r.failed && r.worstPx <= goal) {
      best = r;
      found = true;
      t.index = mid;
      hi = mid - 1;
    } else {
      lo = mid + 1;
    }
  }
  if (!found) {
    t.run = runErrors(scene, target, references, make(ladder.back()), 0.0);
  } else {
    t.run = best;
  }
  return t;
}

/** Cost of a configuration over the poses: leaves, tessellated vertices and triangles, LOD and frame time. */
struct MethodCost {
  double leaves = 0.0;
  double vertices = 0.0;
  double triangles = 0.0;
  std::vector<double> lodMs;
  std::vector<double> frameMs;
};

MethodCost runCost(terrain::TerrainScene& scene, render::RenderTarget& target,
                   const terrain::QuadtreeConfig& config, int poses) {
  terrain::Quadtree quadtree(config, scene.field());
  terrain::QuadtreeSelection selection;
  MethodCost cost;
  for (int i = -1; i < poses; ++i) { // pose -1: warm-up (shader compilation), not counted
    const render::Camera camera = errorBenchPose(scene.field(), std::max(i, 0));
    const Frustum frustum = camera.frustum(target.aspect());
    gl::finish();
    const auto start = std::chrono::steady_clock::now();
    quadtree.select(camera.position, &frustum, selection);
    const auto selected = std::chrono::steady_clock::now();
    terrain::TerrainDrawOptions draw = scene.drawOptions(camera);
    draw.countVertices = true;
    target.begin(glm::vec4(draw.environment.fogColor, 1.0f));
    scene.renderer().draw(selection, camera, target.width(), target.height(), 0.0, nullptr, draw);
    gl::finish();
    const auto end = std::chrono::steady_clock::now();
    if (i < 0) {
      continue;
    }
    cost.lodMs.push_back(std::chrono::duration<double, std::milli>(selected - start).count());
    cost.frameMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    cost.leaves += static_cast<double>(selection.nodes.size()) / poses;
    cost.vertices += static_cast<double>(scene.renderer().lastVertexInvocations()) / poses;
    std::uint64_t triangles = 0;
    for (const terrain::SelectedNode& n : selection.nodes) {
      triangles += terrain::patchTriangles(n);
    }
    cost.triangles += static_cast<double>(triangles) / poses;
  }
  return cost;
}

std::vector<ErrorField> errorFields(int proceduralSize) {
  const std::filesystem::path jacksboro = dataPath("external/jacksboro_fault_dem.npz");
  const std::filesystem::path elev = dataPath("external/elev.tif");
  for (const auto& file : {jacksboro, elev}) {
    if (!std::filesystem::exists(file)) {
      fail("bench terrain-error: {} is missing; run scripts/fetch-sample-data.sh", file.string());
    }
  }
  terrain::ProceduralSpec ridged;
  ridged.type = terrain::ProceduralSpec::Type::Ridged;
  ridged.seed = 11;
  ridged.octaves = 10;
  ridged.frequency = 1.0f / 3000.0f;
  ridged.heightScale = 1500.0f;
  const auto ridgedField = [ridged, proceduralSize] {
    terrain::TerrainSource source;
    source.procedural = ridged;
    source.proceduralSize = proceduralSize;
    source.proceduralSpacing = 2.0f;
    return terrain::loadTerrainSource(source);
  };
  std::vector<ErrorField> fields;
  fields.push_back(
      {"Jacksboro fault (NPZ, 403x344, ~75 m)", [jacksboro] { return terrain::loadHeightField(jacksboro); }});
  fields.push_back(
      {"elev.tif (GeoTIFF, 95x90, ~600x900 m)", [elev] { return terrain::loadHeightField(elev); }});
  fields.push_back({fmt::format("ridged ({0}x{0}, 2 m)", proceduralSize), ridgedField});
  // The same ridges where a low-frequency mask rises, gentle plains elsewhere: terrain whose roughness
  // varies, as real landscapes do (valleys, plateaus, ranges).
  fields.push_back(
      {fmt::format("ridged ranges and plains ({0}x{0}, 2 m)", proceduralSize), [ridgedField, proceduralSize] {
         terrain::HeightField field = ridgedField();
         terrain::ProceduralSpec mask;
         mask.seed = 12;
         mask.octaves = 3;
         mask.frequency = 1.0f / 12000.0f;
         mask.heightScale = 1.0f;
         const terrain::HeightField m =
             terrain::generate(mask, 0.0, 0.0, proceduralSize, proceduralSize, 2.0f);
         std::vector<float>& h = field.samples();
         const std::vector<float>& w = m.samples();
         for (std::size_t i = 0; i < h.size(); ++i) {
           const float t = std::clamp((w[i] - 0.45f) / 0.2f, 0.0f, 1.0f);
           h[i] = 40.0f * w[i] + h[i] * t * t * (3.0f - 2.0f * t);
         }
         return field;
       }});
  return fields;
}

} // namespace

void benchTerrainError(const BenchOptions& o, const platform::GlContext& context, int proceduralSize,
                       nlohmann::json& report) {
  constexpr double goalPx = 1.0; // the equal-error point: at most 1 px anywhere
  shader::Library library;
  if (proceduralSize < 17 || proceduralSize > 16384) {
    fail("--field-size: {} is not in [17, 16384]", proceduralSize);
  }
  const std::vector<ErrorField> fields = errorFields(proceduralSize);
  const int poses = o.frames;
  report = header(o, "terrain-error", context);
  report["poses_per_field"] = poses;
  report["goal_px"] = goalPx;
  std::printf(
      "terrain-error: distance LOD vs screen-space-error LOD at a worst error of %.2f px over %d poses, "
      "%dx%d, %s\n",
      goalPx, poses, o.width, o.height, gl::queryContextInfo().renderer.c_str());
  // Geometric ladders in steps of 10 %: distance factors from the restriction's minimum up to 64, error
  // thresholds from 8 px down to 0.2 px, both in order of rising cost.
  std::vector<float> factors;
  for (float f = terrain::kMinRestrictedLodFactor; f <= 64.0f; f *= 1.1f) {
    factors.push_back(f);
  }
  std::vector<float> thresholds;
  for (float t = 8.0f; t >= 0.2f; t /= 1.1f) {
    thresholds.push_back(t);
  }
  nlohmann::json rows = nlohmann::json::array();
  for (const ErrorField& field : fields) {
    const auto built = std::chrono::steady_clock::now();
    terrain::HeightField loaded = field.heights();
    const terrain::QuadtreeConfig layout = sharedLayout(loaded);
    auto scene = std::make_unique<terrain::TerrainScene>(library, std::move(loaded), layout,
                                                         terrain::TerrainSceneOptions{});
    const terrain::HeightField& heights = scene->field();
    const float ppr =
        terrain::QuadtreeConfig::pixelsPerRadianFor(static_cast<float>(o.height), glm::radians(50.0f));
    const auto distanceConfig = [&](float factor) {
      terrain::QuadtreeConfig c = layout;
      c.lodDistanceFactor = factor;
      return c;
    };
    const auto errorConfig = [&](float tau) {
      terrain::QuadtreeConfig c = layout;
      c.lodErrorPixels = tau;
      c.pixelsPerRadian = ppr;
      return c;
    };
    // Node errors once for the field (the error configs share them through the layout).
    const auto errorsStart = std::chrono::steady_clock::now();
    const terrain::Quadtree withErrors(errorConfig(1.0f), heights);
    const double errorsSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - errorsStart).count();
    std::printf("  %s: %dx%d samples, %.0fx%.0f m; roots %dx%d of %.0f m, depth %d, finest vertices %.2f m; "
                "node errors %.2f s (%.1f MB); built in %.1f s\n",
                field.name.c_str(), heights.width(), heights.height(), heights.extentX(), heights.extentZ(),
                withErrors.config().rootsX, withErrors.config().rootsZ, layout.rootSize, layout.maxDepth,
                layout.finestVertexSpacing(), errorsSeconds,
                static_cast<double>(withErrors.memoryBytes()) / 1e6,
                std::chrono::duration<double>(errorsStart - built).count());
    terrain::PositionTarget positions(o.width, o.height);
    render::RenderTarget colour(o.width, o.height);
    const std::vector<Image> references = referenceViews(*scene, positions, layout, poses);
    const Tuned d = tune(factors, distanceConfig, *scene, positions, references, goalPx);
    const Tuned e = tune(thresholds, errorConfig, *scene, positions, references, goalPx);
    const float factor = factors[static_cast<std::size_t>(d.index < 0 ? factors.size() - 1 : d.index)];
    const float tau = thresholds[static_cast<std::size_t>(e.index < 0 ? thresholds.size() - 1 : e.index)];
    const MethodCost dc = runCost(*scene, colour, distanceConfig(factor), poses);
    const MethodCost ec = runCost(*scene, colour, errorConfig(tau), poses);
    const double dFrame = render::Stats::of(dc.frameMs).median;
    const double eFrame = render::Stats::of(ec.frameMs).median;
    std::printf("    %-22s %9s %9s %9s %8s %11s %11s %8s %9s\n", "method", "parameter", "worst px",
                "p99.9 px", "leaves", "vertices", "triangles", "LOD ms", "frame ms");
    std::printf("    %-22s %9s %9.3f %9.3f %8.0f %11.0f %11.0f %8.3f %9.2f%s\n", "distance (paper)",
                fmt::format("F={:.3g}", factor).c_str(), d.run.worstPx, d.run.p999Px, dc.leaves, dc.vertices,
                dc.triangles, render::Stats::of(dc.lodMs).median, dFrame,
                d.index < 0 ? "  (goal not reached by the ladder)" : "");
    std::printf("    %-22s %9s %9.3f %9.3f %8.0f %11.0f %11.0f %8.3f %9.2f%s\n", "screen-space error",
                fmt::format("tau={:.3g}", tau).c_str(), e.run.worstPx, e.run.p999Px, ec.leaves, ec.vertices,
                ec.triangles, render::Stats::of(ec.lodMs).median, eFrame,
                e.index < 0 ? "  (goal not reached by the ladder)" : "");
    const double vertexRatio = dc.vertices / std::max(ec.vertices, 1.0);
    std::printf(
        "    distance / error: %.2fx vertices, %.2fx triangles, %.2fx frame time (target >= 4x vertices)\n",
        vertexRatio, dc.triangles / std::max(ec.triangles, 1.0), dFrame / std::max(eFrame, 1e-9));
    const auto method = [&](const Tuned& t, const MethodCost& c, const char* parameter, float value) {
      return nlohmann::json{{"parameter", parameter},
                            {"value", value},
                            {"goal_reached", t.index >= 0},
                            {"probes", t.probes},
                            {"worst_px", t.run.worstPx},
                            {"p999_px", t.run.p999Px},
                            {"leaves_mean", c.leaves},
                            {"vertices_mean", c.vertices},
                            {"vertices_measured_on_gpu", true},
                            {"triangles_mean", c.triangles},
                            {"lod_ms", render::Stats::of(c.lodMs).toJson()},
                            {"frame_ms", render::Stats::of(c.frameMs).toJson()}};
    };
    rows.push_back({{"field", field.name},
                    {"samples", {heights.width(), heights.height()}},
                    {"extent_m", {heights.extentX(), heights.extentZ()}},
                    {"root_size_m", layout.rootSize},
                    {"max_depth", layout.maxDepth},
                    {"tess", layout.patchTessLevel},
                    {"finest_vertex_spacing_m", layout.finestVertexSpacing()},
                    {"node_errors_s", errorsSeconds},
                    {"quadtree_bytes", withErrors.memoryBytes()},
                    {"distance", method(d, dc, "lod_factor", factor)},
                    {"error", method(e, ec, "lod_error_px", tau)},
                    {"vertex_ratio", vertexRatio},
                    {"frame_time_ratio", dFrame / std::max(eFrame, 1e-9)}});
  }
  report["fields"] = rows;
}

} // namespace sylva::bench
