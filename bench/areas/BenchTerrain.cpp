#include "Bench.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/gpu/TerrainPopping.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <numeric>
#include <unistd.h>

namespace sylva::bench {

namespace {

/** The paper's Table 8 rows: roots, LOD enabled, tessellation level (their 64-root category has a 4th test).
 */
struct Table8Row {
  int roots;
  bool lod;
  int tess;
};
constexpr Table8Row kTable8[] = {{4, false, 1},   {4, false, 32}, {4, true, 32},   {16, false, 1},
                                 {16, false, 32}, {16, true, 32}, {32, false, 1},  {32, false, 32},
                                 {32, true, 32},  {64, false, 1}, {64, false, 32}, {64, true, 1},
                                 {64, true, 32}};

/** What the terrain benches render: the scene from the terrain flags, and an orbit around the field's centre.
 */
struct TerrainRig {
  shader::Library library;
  render::RenderTarget target;
  std::unique_ptr<terrain::TerrainScene> scene;
  render::Camera base;
  glm::vec3 centre{0.0f};

  explicit TerrainRig(const BenchOptions& o)
      : target(o.width, o.height),
        scene(terrain::TerrainScene::fromSetup(library, o.terrain, o.terrainFieldName)),
        base(scene->defaultCamera()),
        centre(0.5f * scene->field().extentX(), base.target.y, 0.5f * scene->field().extentZ()) {}

  /** The default camera turned by `angle` radians about the vertical through the centre, looking at it. */
  render::Camera orbit(float angle) const {
    render::Camera camera = base;
    const glm::vec3 offset = base.position - centre;
    camera.position = centre + glm::vec3(std::cos(angle) * offset.x - std::sin(angle) * offset.z, offset.y,
                                         std::sin(angle) * offset.x + std::cos(angle) * offset.z);
    camera.target = centre;
    return camera;
  }
};

/**
 * Terrain LOD popping (the grass issue's measure, docs/grass.md "Popping"): a camera 40 m above the ground
 * walks across the field in 0.1 m steps, looking almost level; for the first 16 steps in which a patch
 * changes level (selections without culling differ), the fraction of pixels that change by more than 5 % in
 * a channel is measured with the selection re-made for the moved camera ("across" LOD boundaries) and with
 * the first camera's selection kept ("inside" one band: no patch changes level, parallax alone), geomorphing
 * off and on, for the quadtree `config`. Prints the figures and returns them (mean % pixels per step).
 */
nlohmann::json benchTerrainPopping(const terrain::QuadtreeConfig& config, TerrainRig& rig) {
  terrain::TerrainScene& scene = *rig.scene;
  const terrain::HeightField& field = scene.field();
  terrain::Quadtree quadtree(config, field);
  const glm::vec3 forward = glm::normalize(glm::vec3(0.8f, 0.0f, 0.6f));
  const glm::vec2 start(0.2f * field.extentX(), 0.2f * field.extentZ());
  const float span = std::hypot(field.extentX(), field.extentZ());
  const glm::vec4 clear(0.62f, 0.72f, 0.85f, 1.0f);
  terrain::CameraStepChange off;
  terrain::CameraStepChange on;
  int steps = 0;
  constexpr int kWanted = 16;
  constexpr float kStep = 0.1f;
  for (int i = 0; i < 100000 && steps < kWanted; ++i) {
    const glm::vec2 xz = start + glm::vec2(forward.x, forward.z) * (0.5f * static_cast<float>(i));
    if (xz.x > 0.9f * field.extentX() || xz.y > 0.9f * field.extentZ()) {
      break;
    }
    render::Camera from = rig.base;
    from.position = {xz.x, terrain::heightAt(field, xz.x, xz.y) + 40.0f, xz.y};
    from.target = from.position + glm::vec3(forward.x, -0.12f, forward.z);
    from.nearPlane = 0.5f;
    from.farPlane = span;
    render::Camera to = from;
    to.position += forward * kStep;
    to.target += forward * kStep;
    if (terrain::changedLeaves(quadtree.select(from.position, nullptr),
                               quadtree.select(to.position, nullptr)) == 0) {
      continue;
    }
    terrain::TerrainDrawOptions draw = scene.drawOptions(from);
    draw.geomorph = false;
    const terrain::CameraStepChange a =
        terrain::measureCameraStep(scene.renderer(), quadtree, rig.target, from, to, draw, clear);
    draw.geomorph = true;
    const terrain::CameraStepChange b =
        terrain::measureCameraStep(scene.renderer(), quadtree, rig.target, from, to, draw, clear);
    off.across += a.across;
    off.inside += a.inside;
    on.across += b.across;
    on.inside += b.inside;
    off.leavesChanged += a.leavesChanged;
    ++steps;
  }
  const double n = std::max(steps, 1);
  const double acrossOff = 100.0 * off.across / n;
  const double insideOff = 100.0 * off.inside / n;
  const double acrossOn = 100.0 * on.across / n;
  const double insideOn = 100.0 * on.inside / n;
  std::printf(
      "  popping at base level %d: %d steps of %.1f m with a level change (%d leaves changed), %% pixels "
      "changed > 5 %%\n",
      config.patchTessLevel, steps, kStep, off.leavesChanged);
  std::printf("    geomorph off: across LOD boundaries %.4f, inside one band %.4f\n", acrossOff, insideOff);
  std::printf("    geomorph on:  across LOD boundaries %.4f, inside one band %.4f\n", acrossOn, insideOn);
  return {{"tess", config.patchTessLevel},
          {"max_depth", config.maxDepth},
          {"steps", steps},
          {"step_m", kStep},
          {"leaves_changed", off.leavesChanged},
          {"unit", "% pixels changed by > 5 % in a channel, mean per step"},
          {"geomorph_off", {{"across", acrossOff}, {"inside", insideOff}}},
          {"geomorph_on", {{"across", acrossOn}, {"inside", insideOn}}}};
}

} // namespace

void benchTerrain(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  TerrainRig rig(o);
  render::RenderTarget& target = rig.target;
  const auto& scene = rig.scene;
  const terrain::HeightField& field = scene->field();
  report = header(o, "terrain", context);
  report["terrain"] = {{"samples", {field.width(), field.height()}},
                       {"extent_m", {field.extentX(), field.extentZ()}},
                       {"source", o.terrainSource}};
  nlohmann::json rows = nlohmann::json::array();
  std::printf("terrain (Table 8): %dx%d samples, %.0fx%.0f m, %d frames after %d warm-up, %dx%d, %s\n",
              field.width(), field.height(), field.extentX(), field.extentZ(), o.frames, o.warmup, o.width,
              o.height, gl::queryContextInfo().renderer.c_str());
  std::printf("  %5s %4s %4s %-6s %7s %11s %9s %9s %9s %9s %9s\n", "roots", "LOD", "tess", "method", "nodes",
              "vertices", "LOD ms", "pass ms", "GPU ms", "frame ms", "frames/s");
  // The Table 8 rows for both methods, then the configuration `sylva render`/`view` use (the demo).
  struct Entry {
    std::string roots;
    terrain::QuadtreeConfig config;
    bool geomorph = false;
  };
  std::vector<Entry> entries;
  for (const Table8Row& row : kTable8) {
    for (const terrain::CrackMethod method :
         {terrain::CrackMethod::PaperSearch, terrain::CrackMethod::RestrictedLevelMap}) {
      terrain::QuadtreeConfig config =
          terrain::QuadtreeConfig::forRootCount(row.roots, field.extentX(), field.extentZ());
      config.maxDepth = std::max(0, static_cast<int>(std::round(std::log2(config.rootSize / 16.0f))));
      config.lodDistanceFactor = o.terrain.quadtree.lodDistanceFactor;
      config.patchTessLevel = row.tess;
      config.lodEnabled = row.lod;
      config.method = method;
      entries.push_back({std::to_string(row.roots), config});
    }
  }
  for (const terrain::CrackMethod method :
       {terrain::CrackMethod::PaperSearch, terrain::CrackMethod::RestrictedLevelMap}) {
    terrain::QuadtreeConfig config = terrain::quadtreeFor(o.terrain, field, o.terrainFieldName);
    config.method = method;
    entries.push_back({"demo", config});
  }
  // The demo configuration once more with geomorphing (method "ours+m"): its cost.
  entries.push_back({"demo", terrain::quadtreeFor(o.terrain, field, o.terrainFieldName), true});
  for (const Entry& entry : entries) {
    {
      const terrain::QuadtreeConfig& config = entry.config;
      const std::string method =
          std::string(config.method == terrain::CrackMethod::PaperSearch ? "paper" : "ours") +
          (entry.geomorph ? "+m" : "");
      terrain::Quadtree quadtree(config, field);
      terrain::QuadtreeSelection selection;
      terrain::TerrainDrawOptions draw;
      draw.geomorph = entry.geomorph;
      draw.environment = scene->environment(rig.base);
      const Samples s = measure(o, [&](render::GpuTimers& timers, int i, Samples& out) {
        // A slow orbit around the centre: the selection changes every frame, as in a fly-through.
        const render::Camera camera = rig.orbit(0.02f * static_cast<float>(i));
        const Frustum frustum = camera.frustum(target.aspect());
        const auto start = std::chrono::steady_clock::now();
        quadtree.select(camera.position, &frustum, selection);
        out.extra["lod_ms"].push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        target.begin(glm::vec4(draw.environment.fogColor, 1.0f));
        scene->renderer().draw(selection, camera, o.width, o.height, 0.0, &timers, draw);
        out.extra["nodes"].push_back(static_cast<double>(selection.nodes.size()));
      });
      const render::Stats lod = render::Stats::of(s.extra.at("lod_ms"));
      const render::Stats gpu = render::Stats::of(s.gpu.at("terrain"));
      const render::Stats frame = render::Stats::of(s.frame);
      const render::Stats nodes = render::Stats::of(s.extra.at("nodes"));
      // Tessellation-evaluation runs of the terrain pass (its pipeline statistics): the vertices processed.
      std::vector<double> tes;
      for (const render::PassCounts& c : s.counts.at("terrain")) {
        tes.push_back(static_cast<double>(c.tessEvaluations));
      }
      const render::Stats vertices = render::Stats::of(tes);
      const render::Stats pass = render::Stats::of(s.wall.at("terrain"));
      std::printf("  %5s %4s %4d %-6s %7.0f %11.0f %9.4f %9.2f %9.3f %9.2f %9.1f\n", entry.roots.c_str(),
                  config.lodEnabled ? "on" : "off", config.patchTessLevel, method.c_str(), nodes.median,
                  vertices.median, lod.median, pass.median, gpu.median, frame.median, 1000.0 / frame.median);
      rows.push_back({{"roots", entry.roots},
                      {"roots_layout", {config.rootsX, config.rootsZ}},
                      {"lod", config.lodEnabled},
                      {"tess", config.patchTessLevel},
                      {"terrain_pass_wall_ms", pass.toJson()},
                      {"method", method},
                      {"geomorph", entry.geomorph},
                      {"max_depth", config.maxDepth},
                      {"nodes", nodes.toJson()},
                      {"processed_vertices", vertices.toJson()},
                      {"vertices_measured_on_gpu", true},
                      {"lod_update_ms", lod.toJson()},
                      {"gpu_terrain_ms", gpu.toJson()},
                      {"frame_ms", frame.toJson()}});
    }
  }
  report["rows"] = rows;
  // Popping with the demo configuration, and with base level 4 (coarser patches, so level changes show more).
  terrain::TerrainSetup coarse = o.terrain;
  coarse.quadtree.patchTessLevel = 4;
  report["popping"] = {benchTerrainPopping(terrain::quadtreeFor(o.terrain, field, o.terrainFieldName), rig),
                       benchTerrainPopping(terrain::quadtreeFor(coarse, field, o.terrainFieldName), rig)};
}

/**
 * `bench soak`: renders the terrain scene for warmup + frames frames while the camera orbits (the LOD
 * selection changes every frame), and reports resident memory after warm-up and at the end, GL errors
 * (glGetError and KHR_debug errors) and the drift of frame time (mean of the last 10 % of frames against the
 * first 10 %). Fails (exit 1) when memory grew more than `maxGrowthPercent` or any GL error occurred.
 */
void benchSoak(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  TerrainRig rig(o);
  render::RenderTarget& target = rig.target;
  const auto& scene = rig.scene;
  const terrain::HeightField& field = scene->field();
  terrain::Quadtree quadtree(terrain::quadtreeFor(o.terrain, field, o.terrainFieldName), field);
  terrain::QuadtreeSelection selection;
  terrain::TerrainDrawOptions draw;
  draw.environment = scene->environment(rig.base);
  gl::clearDebugErrors();
  std::size_t glErrors = 0;
  std::vector<std::string> firstErrors;
  std::vector<double> frameMs;
  std::vector<std::pair<int, std::uint64_t>> rssSeries;
  std::uint64_t rssAfterWarmup = 0;
  Progress progress("soak", static_cast<std::size_t>(o.warmup + o.frames));
  for (int i = 0; i < o.warmup + o.frames && !progress.cancelled(); ++i) {
    const auto start = std::chrono::steady_clock::now();
    const render::Camera camera = rig.orbit(0.01f * static_cast<float>(i));
    const Frustum frustum = camera.frustum(target.aspect());
    quadtree.select(camera.position, &frustum, selection);
    target.begin(glm::vec4(draw.environment.fogColor, 1.0f));
    scene->renderer().draw(selection, camera, o.width, o.height, 0.05 * i, nullptr, draw);
    gl::finish();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    for (const std::string& e : gl::drainGlErrors()) {
      ++glErrors;
      if (firstErrors.size() < 5) {
        firstErrors.push_back(fmt::format("frame {}: glGetError {}", i, e));
      }
    }
    for (const gl::DebugMessage& m : gl::debugErrors()) {
      ++glErrors;
      if (firstErrors.size() < 5) {
        firstErrors.push_back(fmt::format("frame {}: {}", i, m.text));
      }
    }
    gl::clearDebugErrors();
    if (i + 1 == o.warmup) {
      rssAfterWarmup = residentBytes();
    }
    if (i >= o.warmup) {
      frameMs.push_back(ms);
      const int measured = i - o.warmup + 1;
      if (measured % std::max(1, o.frames / 20) == 0 || measured == o.frames) {
        rssSeries.emplace_back(measured, residentBytes());
      }
    }
    progress.advance();
  }
  if (progress.cancelled()) {
    fail("soak cancelled after {} frames", frameMs.size());
  }
  if (o.warmup == 0) {
    rssAfterWarmup = rssSeries.empty() ? residentBytes() : rssSeries.front().second;
  }
  const std::uint64_t rssEnd = residentBytes();
  const double growth = 100.0 * (static_cast<double>(rssEnd) - static_cast<double>(rssAfterWarmup)) /
                        static_cast<double>(std::max<std::uint64_t>(rssAfterWarmup, 1));
  const std::size_t tenth = std::max<std::size_t>(1, frameMs.size() / 10);
  const auto mean = [](auto first, auto last) {
    return std::accumulate(first, last, 0.0) / static_cast<double>(std::distance(first, last));
  };
  const double early = mean(frameMs.begin(), frameMs.begin() + static_cast<std::ptrdiff_t>(tenth));
  const double late = mean(frameMs.end() - static_cast<std::ptrdiff_t>(tenth), frameMs.end());
  const double drift = 100.0 * (late - early) / early;
  const render::Stats f = render::Stats::of(frameMs);
  std::printf("soak: %d frames after %d warm-up, %dx%d, %s\n", o.frames, o.warmup, o.width, o.height,
              gl::queryContextInfo().renderer.c_str());
  std::printf("  resident memory: %.1f MiB after warm-up, %.1f MiB at the end (%+.3f %%, limit %.2f %%)\n",
              static_cast<double>(rssAfterWarmup) / 1048576.0, static_cast<double>(rssEnd) / 1048576.0,
              growth, o.maxGrowthPercent);
  std::printf("  GL errors: %zu\n", glErrors);
  std::printf("  frame time: median %.2f ms; first 10 %% %.2f ms, last 10 %% %.2f ms (drift %+.1f %%)\n",
              f.median, early, late, drift);
  report = header(o, "soak", context);
  report["terrain"] = {{"samples", {field.width(), field.height()}}, {"source", o.terrainSource}};
  report["rss_bytes_after_warmup"] = rssAfterWarmup;
  report["rss_bytes_end"] = rssEnd;
  report["rss_growth_percent"] = growth;
  report["rss_growth_limit_percent"] = o.maxGrowthPercent;
  nlohmann::json series = nlohmann::json::array();
  for (const auto& [frame, bytes] : rssSeries) {
    series.push_back({{"frame", frame}, {"rss_bytes", bytes}});
  }
  report["rss_series"] = series;
  report["gl_errors"] = glErrors;
  report["gl_error_samples"] = firstErrors;
  report["frame_ms"] = f.toJson();
  report["frame_ms_first_tenth"] = early;
  report["frame_ms_last_tenth"] = late;
  report["frame_time_drift_percent"] = drift;
  const bool ok = glErrors == 0 && growth < o.maxGrowthPercent;
  report["passed"] = ok;
  if (!ok) {
    std::fprintf(stderr, "sylva: soak failed: %s\n",
                 glErrors > 0 ? fmt::format("{} GL errors (first: {})", glErrors, firstErrors.front()).c_str()
                              : fmt::format("resident memory grew {:.3f} % (limit {:.2f} %)", growth,
                                            o.maxGrowthPercent)
                                    .c_str());
  }
}

} // namespace sylva::bench
