#include "BenchRows.hpp"
#include "Commands.hpp"
#include "GrassFlags.hpp"
#include "GrassSim.hpp"
#include "TerrainFlags.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/render/DemoScene.hpp>
#include <sylva/render/GpuTimers.hpp>
#include <sylva/render/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/gpu/TerrainPopping.hpp>

#ifdef SYLVA_HAVE_FOLDING
#include <folding/FoldingCase.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Session.hpp>
#ifdef SYLVA_HAVE_FOLDING_GPU
#include <sylva/folding/gpu/FoldRenderer.hpp>
#endif
#endif

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

namespace sylva::app {

namespace {

struct BenchOptions {
  ContextFlags context;
  TerrainFlags terrain;
  int frames = 60;
  int warmup = 5;
  int width = 1280;
  int height = 720;
  std::string out;
  std::string area = "demo";
  double maxGrowthPercent = 1.0;
  std::string sceneFile = "data/scenes/meadow.json";
};

/** Samples of one measured run: per-pass CPU/GPU milliseconds, wall time per frame, extra per-frame series.
 */
struct Samples {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> cpu;
  std::map<std::string, std::vector<double>> gpu;
  std::map<std::string, std::vector<double>> wall;
  std::vector<double> frame;
  std::map<std::string, std::vector<double>> extra;

  nlohmann::json passesJson() const {
    nlohmann::json passes = nlohmann::json::array();
    for (const std::string& pass : order) {
      passes.push_back({{"name", pass},
                        {"cpu_ms", render::Stats::of(cpu.at(pass)).toJson()},
                        {"gpu_ms", render::Stats::of(gpu.at(pass)).toJson()},
                        {"wall_ms", render::Stats::of(wall.at(pass)).toJson()}});
    }
    return passes;
  }
};

/** Runs `frame(timers, index)` warmup + frames times with synchronous GPU timers and collects samples. */
Samples measure(const BenchOptions& o, const std::function<void(render::GpuTimers&, int, Samples&)>& frame) {
  render::GpuTimers timers(1, true);
  Samples s;
  for (int i = 0; i < o.warmup + o.frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    timers.beginFrame();
    Samples scratch;
    frame(timers, i, scratch);
    timers.endFrame(); // synchronous: waits for this frame's GPU results
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (i < o.warmup) {
      continue;
    }
    s.frame.push_back(ms);
    for (const render::PassTiming& t : timers.lastFrame()) {
      if (s.cpu.find(t.name) == s.cpu.end()) {
        s.order.push_back(t.name);
      }
      s.cpu[t.name].push_back(t.cpuMs);
      s.gpu[t.name].push_back(t.gpuMs);
      s.wall[t.name].push_back(t.wallMs);
    }
    for (auto& [name, values] : scratch.extra) {
      s.extra[name].insert(s.extra[name].end(), values.begin(), values.end());
    }
  }
  return s;
}

nlohmann::json header(const BenchOptions& o, const std::string& name, const platform::GlContext& context) {
  const gl::ContextInfo info = gl::queryContextInfo();
  const MachineInfo machine = machineInfo();
  return {{"benchmark", name},
          {"machine", {{"host", machine.host}, {"cpu", machine.cpu}, {"cores", machine.cores}}},
          {"renderer", {{"vendor", info.vendor}, {"renderer", info.renderer}, {"version", info.version}}},
          {"context", context.description()},
          {"frames", o.frames},
          {"warmup", o.warmup},
          {"resolution", {o.width, o.height}}};
}

void benchDemo(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  shader::Library library;
  render::RenderTarget target(o.width, o.height);
  render::DemoScene scene(library);
  const render::Camera camera = scene.defaultCamera();
  const Samples s = measure(o, [&](render::GpuTimers& timers, int i, Samples&) {
    target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
    scene.render(camera, o.width, o.height, 1.0 + i / 60.0, &timers);
  });
  std::printf("demo: %d frames after %d warm-up, %dx%d, %s\n", o.frames, o.warmup, o.width, o.height,
              gl::queryContextInfo().renderer.c_str());
  // "wall" is each pass's time to completion; on llvmpipe it is the meaningful column (work deferred to the
  // rasteriser threads, a clear included, lands in the pass that waits for it).
  std::printf("  %-14s %12s %12s %12s %12s %12s\n", "pass", "cpu median", "gpu median", "gpu p10", "gpu p90",
              "wall median");
  for (const std::string& pass : s.order) {
    const render::Stats c = render::Stats::of(s.cpu.at(pass));
    const render::Stats g = render::Stats::of(s.gpu.at(pass));
    const render::Stats w = render::Stats::of(s.wall.at(pass));
    std::printf("  %-14s %9.3f ms %9.3f ms %9.3f ms %9.3f ms %9.3f ms\n", pass.c_str(), c.median, g.median,
                g.p10, g.p90, w.median);
  }
  const render::Stats f = render::Stats::of(s.frame);
  std::printf("  %-14s %9.3f ms (%.1f frames/s at the median)\n", "frame (wall)", f.median,
              1000.0 / f.median);
  report = header(o, "demo", context);
  report["frame_ms"] = f.toJson();
  report["passes"] = s.passesJson();
}

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
      : target(o.width, o.height), scene(o.terrain.build(library)), base(scene->defaultCamera()),
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

void benchTerrain(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  TerrainRig rig(o);
  render::RenderTarget& target = rig.target;
  const auto& scene = rig.scene;
  const terrain::HeightField& field = scene->field();
  report = header(o, "terrain", context);
  report["terrain"] = {{"samples", {field.width(), field.height()}},
                       {"extent_m", {field.extentX(), field.extentZ()}},
                       {"source", o.terrain.source.describe()}};
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
    for (const std::string method : {"paper", "ours"}) {
      terrain::QuadtreeConfig config =
          terrain::QuadtreeConfig::forRootCount(row.roots, field.extentX(), field.extentZ());
      config.maxDepth = std::max(0, static_cast<int>(std::round(std::log2(config.rootSize / 16.0f))));
      config.lodDistanceFactor = o.terrain.quadtree.lodDistanceFactor;
      config.patchTessLevel = row.tess;
      config.lodEnabled = row.lod;
      config.method = parseCrackMethod(method);
      entries.push_back({std::to_string(row.roots), config});
    }
  }
  for (const std::string method : {"paper", "ours"}) {
    terrain::QuadtreeConfig config = o.terrain.configFor(field);
    config.method = parseCrackMethod(method);
    entries.push_back({"demo", config});
  }
  // The demo configuration once more with geomorphing (method "ours+m"): its cost.
  entries.push_back({"demo", o.terrain.configFor(field), true});
  for (const Entry& entry : entries) {
    {
      const terrain::QuadtreeConfig& config = entry.config;
      const std::string method =
          std::string(config.method == terrain::CrackMethod::PaperSearch ? "paper" : "ours") +
          (entry.geomorph ? "+m" : "");
      terrain::Quadtree quadtree(config, field);
      terrain::QuadtreeSelection selection;
      terrain::TerrainDrawOptions draw;
      draw.countVertices = true;
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
        const std::int64_t measured = scene->renderer().lastVertexInvocations();
        out.extra["vertices"].push_back(measured >= 0
                                            ? static_cast<double>(measured)
                                            : static_cast<double>(selection.stats.processedVertices));
      });
      const render::Stats lod = render::Stats::of(s.extra.at("lod_ms"));
      const render::Stats gpu = render::Stats::of(s.gpu.at("terrain"));
      const render::Stats frame = render::Stats::of(s.frame);
      const render::Stats nodes = render::Stats::of(s.extra.at("nodes"));
      const render::Stats vertices = render::Stats::of(s.extra.at("vertices"));
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
                      {"vertices_measured_on_gpu", scene->renderer().lastVertexInvocations() >= 0},
                      {"lod_update_ms", lod.toJson()},
                      {"gpu_terrain_ms", gpu.toJson()},
                      {"frame_ms", frame.toJson()}});
    }
  }
  report["rows"] = rows;
  // Popping with the demo configuration, and with base level 4 (coarser patches, so level changes show more).
  TerrainFlags coarse = o.terrain;
  coarse.quadtree.patchTessLevel = 4;
  report["popping"] = {benchTerrainPopping(o.terrain.configFor(field), rig),
                       benchTerrainPopping(coarse.configFor(field), rig)};
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
  terrain::Quadtree quadtree(o.terrain.configFor(field), field);
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
  report["terrain"] = {{"samples", {field.width(), field.height()}}, {"source", o.terrain.source.describe()}};
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
    exitCode() = 1;
  }
}

#ifdef SYLVA_HAVE_FOLDING
/**
 * `bench fold`: the folding targets of docs/folding.md on the generated 1024x1024 case (FoldingCase.hpp):
 * synthesis per megapixel (modified Shepard with 100 and 1,000 anchors, Shepard IDW with 100; all worker
 * threads), thresholds of a 64-vertex polygon (all workers), re-synthesis of the region one moved anchor
 * affects, the CPU reference render on one thread, and the GL renderer's frame rate at 1 MP (skipped with the
 * reason when no GL context can be made), and the editor's drag latency (edit, region re-synthesis, upload
 * and one preview frame per step; the CPU part only without GL). Medians of 5 runs after 1 warm-up (render:
 * `frames` frames after `warmup`; drag: 30 steps). Prints measured against target per row.
 */
void benchFold(const BenchOptions& o, nlohmann::json& report) {
  using namespace folding;
  using namespace folding::bench;
  const MachineInfo machine = machineInfo();
  const ProjectImages images = benchImages();
  const double mp = static_cast<double>(kCaseSide) * kCaseSide / 1048576.0;
  constexpr int kRuns = 5;
  volatile int sink = 0; // results are used, so no call is optimised away
  std::atomic<std::size_t> hits{0};
  using Row = BenchRow;
  std::vector<Row> rows;
  const auto interp = [](Interpolation::Type type) {
    Interpolation i;
    i.type = type;
    i.radius = 64.0;
    return i;
  };
  const auto synthesisRow = [&](const std::string& name, int anchors, Interpolation::Type type,
                                double target) {
    const Project p = benchProject(anchors, interp(type));
    const render::Stats s =
        render::Stats::of(timeRuns(1, kRuns, [&] { sink = synthesize(p, images).width(); }));
    rows.push_back({name, s.median / mp, "s/MP", target, true, workerCount(), ""});
  };
  std::printf("fold: %dx%d generated case, %s, %u cores, %u worker threads\n", kCaseSide, kCaseSide,
              machine.cpu.c_str(), machine.cores, workerCount());
  synthesisRow("synthesis, modified Shepard, 100 anchors", 100, Interpolation::Type::ModifiedShepard, 0.25);
  synthesisRow("synthesis, modified Shepard, 1,000 anchors", 1000, Interpolation::Type::ModifiedShepard,
               0.25);
  synthesisRow("synthesis, Shepard IDW, 100 anchors", 100, Interpolation::Type::Shepard, 0.3);
  {
    const std::array<std::vector<Vec2>, 1> polygons{benchStar()};
    const render::Stats s = render::Stats::of(timeRuns(1, kRuns, [&] {
      parallelFor(kCaseSide, [&](std::size_t begin, std::size_t end) {
        std::size_t count = 0;
        for (std::size_t y = begin; y < end; ++y) {
          for (int x = 0; x < kCaseSide; ++x) {
            count += foldIntervals(polygons, Vec2(x + 0.5, static_cast<double>(y) + 0.5),
                                   benchJump(x, static_cast<int>(y)))
                         .size();
          }
        }
        hits += count;
      });
    }));
    rows.push_back({"thresholds, 64-vertex polygon", s.median / mp, "s/MP", 0.2, true, workerCount(), ""});
  }
  const Project p = benchProject(1000, interp(Interpolation::Type::ModifiedShepard));
  Textures textures = synthesize(p, images);
  {
    Rect region;
    const Project moved = movedAnchor(p, 500, Vec2(5.0, 3.0), textures.atlas, region);
    const render::Stats s =
        render::Stats::of(timeRuns(1, kRuns, [&] { resynthesize(moved, images, textures, region); }));
    rows.push_back({"re-synthesis after moving one anchor (R = 64 px)", 1000.0 * s.median, "ms", 50.0, true,
                    workerCount(), fmt::format("region {}x{} px", region.width(), region.height())});
    textures = synthesize(p, images);
  }
  {
    const double atlasMp = static_cast<double>(textures.width()) * textures.height() / 1048576.0;
    int frame = 0;
    const render::Stats s = render::Stats::of(timeRuns(o.warmup, std::max(3, o.frames / 6), [&] {
      sink = renderFrame(textures, p.profiles, p.jumpLayers, frame++ / 30.0, 1).width();
    }));
    rows.push_back({"CPU reference render, one thread", 1000.0 * s.median / atlasMp, "ms/MP per frame", 40.0,
                    true, 1, ""});
  }
  // Drag latency (the editor's target: a dragged anchor updates the preview within 50 ms at 1 MP). Each step
  // moves anchor kDragPair along a circle of kDragRadius px around where it was, as the editor does per mouse
  // event: the validated edit (movePointAnchor on the session's history), then Session::synthesize with the
  // region the move can change (anchorMoveAtlasRect), which re-synthesises it and, with a GL context,
  // `gpuStep`: upload of that region, one frame drawn and glFinish. Medians over kDragSteps steps after 2
  // warm-ups. The session is shared by the rows, so every step starts from the textures the previous one
  // left.
  constexpr int kDragPair = 500;
  constexpr int kDragSteps = 30;
  constexpr int kDragWarmup = 2;
  constexpr double kDragRadius = 6.0;
  // The editor's own path: a Session (edit, atlas-layout check, region re-synthesis) over the generated case.
  std::unique_ptr<Session> dragSession = Session::fromMemory(p, images, "bench-drag.json");
  dragSession->install(Textures(textures), p, images);
  const Vec2 dragCentre = std::get<PointsTool>(p.zones[0].tools[0]).pairs[kDragPair][1];
  Vec2 dragPosition = dragCentre;
  int dragStep = 0;
  const auto dragRow = [&](const std::string& metric, const std::function<void(Rect, double)>& gpuStep,
                           const std::string& why) {
    std::vector<double> total;
    std::vector<double> edit;
    std::vector<double> cpu;
    std::vector<double> gpu;
    Rect region;
    const auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
    for (int step = 0; step < kDragWarmup + kDragSteps; ++step) {
      const double angle = 2.0 * std::numbers::pi * ++dragStep / kDragSteps;
      const Vec2 next = dragCentre + kDragRadius * Vec2(std::cos(angle), std::sin(angle));
      const auto t0 = std::chrono::steady_clock::now();
      movePointAnchor(dragSession->history(), 0, 0, kDragPair, 1, next);
      const auto t1 = std::chrono::steady_clock::now();
      region = dragSession
                   ->synthesize(anchorMoveAtlasRect(dragSession->project(), dragSession->textures()->atlas, 0,
                                                    dragPosition, next))
                   .region;
      const auto t2 = std::chrono::steady_clock::now();
      if (gpuStep) {
        gpuStep(region, dragStep / 30.0);
      }
      const auto t3 = std::chrono::steady_clock::now();
      dragPosition = next;
      if (step >= kDragWarmup) {
        total.push_back(ms(t0, t3));
        edit.push_back(ms(t0, t1));
        cpu.push_back(ms(t1, t2));
        gpu.push_back(ms(t2, t3));
      }
    }
    const auto median = [](std::vector<double> v) { return render::Stats::of(std::move(v)).median; };
    std::string note =
        fmt::format("median of {} steps; edit {:.1f} + region re-synthesis {:.1f} ms ({}x{} px)", kDragSteps,
                    median(edit), median(cpu), region.width(), region.height());
    note += gpuStep ? fmt::format(" + upload, frame, glFinish {:.1f} ms", median(gpu))
                    : fmt::format("; CPU part only: {}", why);
    rows.push_back({metric, median(total), "ms", 50.0, true, workerCount(), note});
  };
  const std::string dragCpuOnly = "drag: edit + re-synthesis (CPU part only, 1 MP)";
  nlohmann::json gpuJson = nullptr;
#ifdef SYLVA_HAVE_FOLDING_GPU
  std::string gpuSkipped;
  try {
    auto context = platform::createHeadlessContext(o.context.options());
    const gl::ContextInfo info = gl::queryContextInfo();
    shader::Library library;
    folding::gpu::FoldRenderer renderer(library);
    renderer.upload(textures, p.profiles, p.jumpLayers);
    const folding::gpu::GpuBenchResult g = folding::gpu::benchmarkGpu(renderer, o.frames);
    rows.push_back(
        {"GPU preview at 1 MP", g.fps, "frames/s", 30.0, false, 0,
         fmt::format("{}x{}, {}, {:.2f} ms/frame", g.width, g.height, info.renderer, g.msPerFrame)});
    gpuJson = {{"vendor", info.vendor},
               {"renderer", info.renderer},
               {"version", info.version},
               {"context", context->description()}};
    // The whole atlas into the renderer's atlas-sized target, then the same atlas shown in a 512x512 preview
    // pane (what the editor's pane beside the canvas costs; the draw scales with the pane's pixels).
    const gl::Framebuffer& target = renderer.offscreenTarget();
    const auto dragGpu = [&](const gl::Framebuffer& fb, int w, int h) {
      return [&renderer, &dragSession, &fb, w, h](Rect region, double t) {
        renderer.updateRegion(*dragSession->textures(), region);
        fb.bindForDraw(w, h);
        renderer.draw(t);
        gl::finish();
      };
    };
    dragRow("drag: edit + re-synthesis + GPU upload + preview frame (1 MP)",
            dragGpu(target, renderer.width(), renderer.height()), "");
    constexpr int kPane = 512;
    gl::Texture paneColor = gl::Texture::create2D(GL_RGBA8, kPane, kPane);
    gl::Framebuffer pane;
    pane.attachColor(0, paneColor);
    pane.checkComplete();
    dragRow(fmt::format("drag as above, 1 MP image in a {}x{} preview pane", kPane, kPane),
            dragGpu(pane, kPane, kPane), "");
    gl::bindWindowFramebuffer();
  } catch (const Error& e) {
    if (gpuJson.is_null()) {
      rows.push_back({"GPU preview at 1 MP", std::nan(""), "frames/s", 30.0, false, 0,
                      std::string("skipped: ") + e.what()});
      gpuSkipped = std::string("no GL context (") + e.what() + ")";
    } else {
      rows.push_back({"drag: edit + re-synthesis + GPU upload + preview frame (1 MP)", std::nan(""), "ms",
                      50.0, true, workerCount(), std::string("failed: ") + e.what()});
    }
  }
  if (!gpuSkipped.empty()) {
    dragRow(dragCpuOnly, nullptr, gpuSkipped);
  }
#else
  rows.push_back({"GPU preview at 1 MP", std::nan(""), "frames/s", 30.0, false, 0,
                  "skipped: built without the folding GPU renderer"});
  dragRow(dragCpuOnly, nullptr, "built without the folding GPU renderer");
#endif
  const nlohmann::json rowsJson = printBenchRows(rows);
  report = {{"benchmark", "fold"},
            {"machine", {{"host", machine.host}, {"cpu", machine.cpu}, {"cores", machine.cores}}},
            {"worker_threads", workerCount()},
            {"renderer", gpuJson},
            {"case", {{"size", {kCaseSide, kCaseSide}}, {"radius_px", 64}, {"polygon_vertices", 64}}},
            {"runs", kRuns},
            {"rows", rowsJson}};
}
#endif

/** The paper's field: 16,384-blade patch, 64 blades per 2 m tile, full density everywhere. */
grass::FieldSettings paperFieldSettings() {
  grass::FieldSettings fs;
  fs.patch.blades = 16384;
  fs.bladesPerTile = 64;
  fs.density.noiseFrequency = 0.0f;
  fs.density.coverage = 1.0f;
  fs.density.maxSlopeDegrees = 90.0f;
  return fs;
}

/**
 * `bench grass`: the paper's field (14,926 tiles of 2 m, 64 blades each: 955,264 blades in one draw, seen
 * whole), the demo's ground view, memory against the paper's 24 MB patch, and LOD popping: pixels that change
 * when the LOD boundary moves past blades (camera still), with dithered cross-fades and with hard switches.
 */
void benchGrass(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  shader::Library library;
  render::RenderTarget target(o.width, o.height);
  const std::string rendererName = gl::queryContextInfo().renderer;
  std::vector<BenchRow> rows;
  report = header(o, "grass", context);

  // 1. The paper's field: 34 x 439 tiles = 14,926, full density (constant noise), every blade drawn.
  terrain::ProceduralSpec spec = terrain::TerrainSource::defaultProcedural();
  spec.heightScale = 6.0f;
  spec.frequency = 1.0f / 150.0f;
  terrain::QuadtreeConfig quadtree = terrain::TerrainSetup::defaultQuadtree();
  quadtree.rootSize = 128.0f;
  quadtree.maxDepth = 4;
  terrain::TerrainScene paperScene(library, terrain::generate(spec, 0.0, 0.0, 69, 879, 1.0f), quadtree);
  const grass::FieldSettings fs = paperFieldSettings();
  auto paperField =
      std::make_shared<grass::GrassField>(paperScene.field(), grass::proceduralBladeTypes(), fs);
  grass::CullSettings all;
  all.maxDistance = 5000.0f;
  all.orientationCos = 0.0f;
  grass::GrassRenderer paperGrass(library, paperField, all);
  const std::size_t fieldBlades = paperField->countBlades();
  const std::size_t tiles = static_cast<std::size_t>(paperField->layout().tilesX) *
                            static_cast<std::size_t>(paperField->layout().tilesZ);
  render::Camera camera =
      paperScene.frameCamera(render::ViewFrom::SouthWest, glm::radians(50.0f), target.aspect());
  grass::GrassDrawOptions grassOptions;
  grassOptions.wind.speed = 3.0f;
  grassOptions.countPrimitives = true;
  const Samples paper = measure(o, [&](render::GpuTimers& timers, int i, Samples&) {
    target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
    drawTerrainWithGrass(paperScene, &paperGrass, camera, o.width, o.height, 1.0 + i / 60.0,
                         paperScene.drawOptions(camera), grassOptions, &timers);
  });
  const gpu::GrassCounters counters = paperGrass.readCounters();
  const double drawnBlades = counters.blades.x;
  const auto wallOf = [](const Samples& s, const std::string& pass) {
    return s.wall.count(pass) != 0 ? render::Stats::of(s.wall.at(pass)).median : std::nan("");
  };
  const double cullMs = wallOf(paper, "grass cull");
  const double drawMs = wallOf(paper, "grass");
  const double frameMs = render::Stats::of(paper.frame).median;
  const std::int64_t triangles = paperGrass.lastPrimitivesSubmitted();
  std::printf("grass: the paper's field, %zu tiles, %zu blades, %dx%d, %s\n", tiles, fieldBlades, o.width,
              o.height, rendererName.c_str());
  const std::string paperNote = "paper: 20 ms on a Radeon R9 270";
  rows.push_back({"paper field: tiles", static_cast<double>(tiles), "tiles", 14926.0, false, 0, ""});
  rows.push_back({"paper field: blades drawn in one draw", drawnBlades, "blades", 955264.0, false, 0,
                  fmt::format("{} triangles", triangles)});
  rows.push_back({"paper field: grass cull + draw", cullMs + drawMs, "ms", 20.0, true, 0, paperNote});
  rows.push_back({"paper field: culling passes", cullMs, "ms", std::nan(""), true, 0, "3 compute passes"});
  rows.push_back(
      {"paper field: whole frame (terrain + grass, wall)", frameMs, "ms", std::nan(""), true, 0, ""});
  rows.push_back({"paper field: blades drawn per second", drawnBlades / ((cullMs + drawMs) * 1e-3) / 1e6,
                  "M blades/s", 955264.0 / 0.020 / 1e6, false, 0, "target: the paper's rate"});
  rows.push_back({"patch memory (16,384 blades + 3 types)",
                  static_cast<double>(grass::patchBytes(16384, 3)) / 1e6, "MB", 24.0, true, 0,
                  "paper: about 24 MB"});
  rows.push_back({"storing every blade of the paper field instead",
                  static_cast<double>(grass::perBladeFieldBytes(fieldBlades)) / 1e6, "MB", std::nan(""), true,
                  0, "16 knots + widths per blade"});
  rows.push_back({"grass GPU memory (paper field, all buffers)",
                  static_cast<double>(paperGrass.gpuBytes()) / 1e6, "MB", std::nan(""), true, 0,
                  "instance lists sized for the draw distance"});

  // 2. The demo's ground view: the terrain of the command line (default: the demo landscape), --grass
  // defaults.
  auto demo = o.terrain.build(library);
  GrassFlags grassFlags;
  auto demoField = grassFlags.buildField(*demo);
  grass::GrassRenderer demoGrass(library, demoField, grassFlags.cullSettings());
  const render::Camera ground = grassCamera(*demo, *demoField, glm::radians(50.0f), grassFlags.windDirection);
  grass::GrassDrawOptions demoOptions;
  demoOptions.wind = grassFlags.wind();
  const Samples demoSamples = measure(o, [&](render::GpuTimers& timers, int i, Samples&) {
    target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
    drawTerrainWithGrass(*demo, &demoGrass, ground, o.width, o.height, 1.0 + i / 60.0,
                         demo->drawOptions(ground), demoOptions, &timers);
  });
  const gpu::GrassCounters demoCounters = demoGrass.readCounters();
  rows.push_back({"demo ground view: blades drawn", static_cast<double>(demoCounters.blades.x), "blades",
                  std::nan(""), false, 0,
                  fmt::format("{} visible tiles of {} blades", demoCounters.dispatch.x,
                              demoField->layout().bladesPerTile)});
  rows.push_back({"demo ground view: grass cull + draw",
                  wallOf(demoSamples, "grass cull") + wallOf(demoSamples, "grass"), "ms", std::nan(""), true,
                  0, ""});
  rows.push_back({"demo ground view: whole frame (wall)", render::Stats::of(demoSamples.frame).median, "ms",
                  std::nan(""), true, 0, ""});

  // 3. Popping: the camera stays; the LOD boundaries move by 0.25 m (what a 0.25 m step of the camera does
  // to the blades near them, without the parallax). Pixels changing by more than 5 % in any channel.
  const auto still = [&](const grass::CullSettings& settings) {
    demoGrass.setCullSettings(settings);
    target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
    drawTerrainWithGrass(*demo, &demoGrass, ground, o.width, o.height, 1.0, demo->drawOptions(ground),
                         demoOptions);
    return target.readColor();
  };
  const grass::CullSettings base = grassFlags.cullSettings();
  const auto shifted = [](grass::CullSettings s, float by) {
    s.lodDistances = {s.lodDistances[0] - by, s.lodDistances[1] - by};
    return s;
  };
  grass::CullSettings hard = base;
  hard.lodFade = 0.0f;
  const double faded = terrain::changedPixelFraction(still(base), still(shifted(base, 0.25f)), 0.05f);
  const double popped = terrain::changedPixelFraction(still(hard), still(shifted(hard, 0.25f)), 0.05f);
  // The draw distance moved by 1 m: blades dissolving into the ground tint over the far fade, or cut.
  const auto nearer = [](grass::CullSettings s) {
    s.maxDistance -= 1.0f;
    return s;
  };
  grass::CullSettings cut = base;
  cut.farFade = 0.0f;
  const double farFaded = terrain::changedPixelFraction(still(base), still(nearer(base)), 0.05f);
  const double farCut = terrain::changedPixelFraction(still(cut), still(nearer(cut)), 0.05f);
  // The same 0.25 m step of the camera, across the boundaries and with one level everywhere (no boundary).
  const auto step = [&](const grass::CullSettings& settings) {
    demoGrass.setCullSettings(settings);
    render::Camera moved = ground;
    const glm::vec3 forward = glm::normalize(
        glm::vec3(ground.target.x - ground.position.x, 0.0f, ground.target.z - ground.position.z));
    moved.position += forward * 0.25f;
    moved.target += forward * 0.25f;
    target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
    drawTerrainWithGrass(*demo, &demoGrass, ground, o.width, o.height, 1.0, demo->drawOptions(ground),
                         demoOptions);
    const Image a = target.readColor();
    target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
    drawTerrainWithGrass(*demo, &demoGrass, moved, o.width, o.height, 1.0, demo->drawOptions(moved),
                         demoOptions);
    return terrain::changedPixelFraction(a, target.readColor(), 0.05f);
  };
  grass::CullSettings single = base;
  single.lodDistances = {base.maxDistance - base.farFade - 2.0f * base.lodFade,
                         base.maxDistance - base.farFade - base.lodFade};
  const double acrossFaded = step(base);
  const double acrossHard = step(hard);
  const double inside = step(single);
  demoGrass.setCullSettings(base);
  rows.push_back({"popping: boundary moved 0.25 m, dithered cross-fade", faded * 100.0, "% pixels",
                  std::nan(""), true, 0, "changed > 5 %, camera still"});
  rows.push_back({"popping: boundary moved 0.25 m, hard switch", popped * 100.0, "% pixels", std::nan(""),
                  true, 0, "the same without cross-fade"});
  rows.push_back({"draw distance moved 1 m, far fade into the ground tint", farFaded * 100.0, "% pixels",
                  std::nan(""), true, 0, "changed > 5 %, camera still"});
  rows.push_back(
      {"draw distance moved 1 m, hard cut", farCut * 100.0, "% pixels", std::nan(""), true, 0, ""});
  rows.push_back({"camera step 0.25 m across LOD boundaries (cross-fade)", acrossFaded * 100.0, "% pixels",
                  inside * 100.0 * 1.1, true, 0, "target: within 10 % of the same step inside one band"});
  rows.push_back({"camera step 0.25 m across LOD boundaries (hard switch)", acrossHard * 100.0, "% pixels",
                  std::nan(""), true, 0, ""});
  rows.push_back({"camera step 0.25 m inside one LOD band", inside * 100.0, "% pixels", std::nan(""), true, 0,
                  "parallax alone"});
  report["rows"] = printBenchRows(rows);
  report["paper_field"] = {
      {"tiles", tiles}, {"blades", fieldBlades}, {"triangles", triangles}, {"passes", paper.passesJson()}};
  report["demo_passes"] = demoSamples.passesJson();
}

/**
 * `bench grass-sim`: the paper's Table 1 workloads (6/14/150/709 simulated tiles of 64 blades with
 * 1/2/20/128 bodies) stepped by the CPU reference (all cores) and the compute shader, and the GPU target
 * workload (500,000 blades, 1,024 bodies). Solver steps only (rest poses, constraints, collisions), medians.
 */
void benchGrassSim(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  shader::Library library;
  const std::string rendererName = gl::queryContextInfo().renderer;
  report = header(o, "grass-sim", context);
  terrain::ProceduralSpec spec = terrain::TerrainSource::defaultProcedural();
  spec.heightScale = 4.0f;
  spec.frequency = 1.0f / 120.0f;
  const grass::FieldSettings fs = paperFieldSettings();
  // 96 x 96 tiles of 2 m: room for the 7,813 tiles of the GPU workload.
  auto field = std::make_shared<grass::GrassField>(terrain::generate(spec, 0.0, 0.0, 193, 193, 1.0f),
                                                   grass::proceduralBladeTypes(), fs);
  grass::GrassRenderer renderer(library, field);
  wind::WindSettings wind;
  wind.speed = 4.0f;
  const float top = field->bladeTop();
  struct Workload {
    int tiles;
    int bodies;
    double paperMs;
  };
  const Workload table1[] = {{6, 1, 0.176}, {14, 2, 0.183}, {150, 20, 0.952}, {709, 128, 4.67}};
  // Tiles in a square block around the field's centre; bodies spread over them, each a 0.4 m ball resting on
  // the grass at the centre of its share of the tiles. Each tile gets the bodies whose inflated box touches
  // it.
  const auto setUp = [&](grass::TileSimulation& sim, int tiles, int bodies,
                         std::vector<std::vector<grass::BladeCollider>>& colliders) {
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles))));
    const glm::ivec2 first(48 - side / 2, 48 - side / 2);
    std::vector<glm::ivec2> chosen;
    for (int i = 0; i < tiles; ++i) {
      chosen.push_back(first + glm::ivec2(i % side, i / side));
      sim.activateTile(chosen.back(), wind);
    }
    std::vector<grass::BladeCollider> balls;
    for (int b = 0; b < bodies; ++b) {
      const glm::ivec2 t = chosen[static_cast<std::size_t>((static_cast<double>(b) + 0.5) * tiles / bodies)];
      const glm::vec2 xz = (glm::vec2(t) + 0.5f) * field->layout().tileSize;
      const float y = terrain::heightAt(field->terrain(), xz.x, xz.y) + 0.3f;
      balls.push_back({glm::vec3(xz.x, y, xz.y), glm::vec3(xz.x, y, xz.y), 0.4f, 30.0f});
    }
    colliders.assign(sim.slots().size(), {});
    for (std::size_t s = 0; s < sim.slots().size(); ++s) {
      if (!sim.slots()[s].used) {
        continue;
      }
      const glm::vec2 lo = glm::vec2(sim.slots()[s].tile) * field->layout().tileSize - top;
      const glm::vec2 hi = lo + field->layout().tileSize + 2.0f * top;
      for (const grass::BladeCollider& c : balls) {
        if (c.a.x + c.radius >= lo.x && c.a.x - c.radius <= hi.x && c.a.z + c.radius >= lo.y &&
            c.a.z - c.radius <= hi.y) {
          colliders[s].push_back(c);
        }
      }
    }
  };
  constexpr int kRuns = 15;
  constexpr int kWarmup = 3;
  const auto cpuMs = [&](int tiles, int bodies, std::size_t& blades) {
    grass::PoolSettings pool;
    pool.tiles = tiles;
    grass::TileSimulation sim(field, pool, grass::SolverSettings{});
    std::vector<std::vector<grass::BladeCollider>> colliders;
    setUp(sim, tiles, bodies, colliders);
    blades = 0;
    for (std::size_t i = 0; i < sim.blades().count(); ++i) {
      blades += sim.bladeInUse(i) ? 1 : 0;
    }
    return render::Stats::of(timeRuns(kWarmup, kRuns, [&] { sim.stepSolver(colliders, wind); })).median * 1e3;
  };
  const auto gpuMs = [&](int tiles, int bodies) {
    grass::PoolSettings pool;
    pool.tiles = tiles;
    grass::TileSimulation sim(field, pool, grass::SolverSettings{});
    grass::GrassSimulator gpu(library, renderer, sim);
    sim.setBackend(&gpu);
    std::vector<std::vector<grass::BladeCollider>> colliders;
    setUp(sim, tiles, bodies, colliders);
    gl::finish();
    return render::Stats::of(timeRuns(kWarmup, kRuns,
                                      [&] {
                                        sim.stepSolver(colliders, wind);
                                        gl::finish();
                                      }))
               .median *
           1e3;
  };
  const MachineInfo machine = machineInfo();
  std::printf(
      "grass-sim: solver steps (16 knots, 2 local and 2 length passes), CPU %s (%u threads), GPU %s\n",
      machine.cpu.c_str(), workerCount(), rendererName.c_str());
  std::vector<BenchRow> rows;
  nlohmann::json table = nlohmann::json::array();
  for (const Workload& w : table1) {
    std::size_t blades = 0;
    const double cpu = cpuMs(w.tiles, w.bodies, blades);
    const double gpu = gpuMs(w.tiles, w.bodies);
    const bool largest = w.tiles == 709;
    const std::string what =
        fmt::format("Table 1: {} tiles, {} bodies, {} blades", w.tiles, w.bodies, blades);
    rows.push_back({what + ", CPU", cpu, "ms/step", largest ? 10.0 : std::nan(""), true, workerCount(),
                    fmt::format("paper (GPU): {} ms; {:.0f} ns/blade", w.paperMs, cpu * 1e6 / blades)});
    rows.push_back({what + ", GPU", gpu, "ms/step", std::nan(""), true, 0,
                    fmt::format("{}; {:.0f} ns/blade", rendererName.substr(0, 24), gpu * 1e6 / blades)});
    table.push_back({{"tiles", w.tiles},
                     {"bodies", w.bodies},
                     {"blades", blades},
                     {"cpu_ms", cpu},
                     {"gpu_ms", gpu},
                     {"paper_ms", w.paperMs}});
  }
  // The GPU target: 500,000 simulated blades (7,813 tiles of 64) with 1,024 bodies in 3 ms.
  const double big = gpuMs(7813, 1024);
  rows.push_back({"500,000 blades, 1,024 bodies, GPU", big, "ms/step", 3.0, true, 0,
                  fmt::format("{}; target for an NVIDIA GPU", rendererName.substr(0, 24))});
  report["rows"] = printBenchRows(rows);
  report["table1"] = table;
}

} // namespace

void registerBench(CLI::App& app) {
  auto* command = app.add_subcommand(
      "bench", "Measure CPU and GPU time per pass over N frames; prints a table and writes JSON");
  auto o = std::make_shared<BenchOptions>();
  command
      ->add_option(
          "area", o->area,
          "demo (pipeline scene), terrain (the paper's Table 8, both crack methods) or soak (long "
          "run of the terrain scene: memory growth, GL errors, frame-time drift; exit 1 on failure) "
          "or fold (folding-texture targets on a generated 1 MP case) or capture (grass capture: "
          "extraction latency per 640x480 frame, refining) or grass (the paper's 955,264-blade field "
          "in one draw, patch memory, culling, LOD popping) or grass-sim (the paper's Table 1 workloads "
          "on the CPU and GPU solvers, and 500,000 blades with 1,024 bodies) or trees (the paper's Fig. 16 "
          "workloads instanced and per piece, tessellation cost, foliage, 1,000 animated + 100,000 impostor "
          "trees, generation, wind on joints, bark tile sets) or scene (a scene file's frames, --scene: "
          "per-pass CPU, GPU and wall times, frames per second, memory)")
      ->check(CLI::IsMember(
          {"demo", "terrain", "soak", "fold", "capture", "grass", "grass-sim", "trees", "scene"}))
      ->capture_default_str();
  o->context.add(*command);
  o->terrain.add(*command);
  command->add_option("--frames", o->frames, "Measured frames (per configuration)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--warmup", o->warmup, "Frames run before measuring")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  command->add_option("--width", o->width, "Target width in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  command->add_option("--height", o->height, "Target height in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "JSON report path (default: out/bench-<area>.json)");
  command->add_option("--scene", o->sceneFile, "scene: the scene file to measure")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  command
      ->add_option("--max-growth", o->maxGrowthPercent,
                   "soak: largest allowed growth of resident memory after warm-up, in percent")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  command->callback([o] {
    nlohmann::json report;
    if (o->area == "capture") {
#ifdef SYLVA_HAVE_CAPTURE
      benchCapture(report);
#else
      fail("bench capture: this sylva was built without the capture module");
#endif
      const std::string out = o->out.empty() ? "out/bench-capture.json" : o->out;
      saveJsonFile(out, report);
      std::printf("%s\n", out.c_str());
      return;
    }
    if (o->area == "fold") {
#ifdef SYLVA_HAVE_FOLDING
      // CPU rows need no GL; the GPU row makes its own context (and says why when it cannot).
      benchFold(*o, report);
#else
      fail("bench fold: this sylva was built without the folding module");
#endif
      const std::string out = o->out.empty() ? "out/bench-fold.json" : o->out;
      saveJsonFile(out, report);
      std::printf("%s\n", out.c_str());
      return;
    }
    auto context = platform::createHeadlessContext(o->context.options());
    if (o->area == "terrain") {
      benchTerrain(*o, *context, report);
    } else if (o->area == "grass") {
      benchGrass(*o, *context, report);
    } else if (o->area == "grass-sim") {
      benchGrassSim(*o, *context, report);
    } else if (o->area == "trees") {
      report = header(*o, "trees", *context);
      benchTrees(o->frames, o->width, o->height, report);
    } else if (o->area == "scene") {
#ifdef SYLVA_HAVE_SCENE
      report = header(*o, "scene", *context);
      benchScene(o->sceneFile, o->frames, o->warmup, o->width, o->height, report);
#else
      fail("bench scene: this sylva was built without the scene module");
#endif
    } else if (o->area == "soak") {
      benchSoak(*o, *context, report);
    } else {
      benchDemo(*o, *context, report);
    }
    const std::string out = o->out.empty() ? "out/bench-" + o->area + ".json" : o->out;
    saveJsonFile(out, report);
    std::printf("%s\n", out.c_str());
  });
}

} // namespace sylva::app
