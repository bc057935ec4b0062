// `sylva bench scene [--scene FILE]`: a scene file's frames with every pass timed (docs/scenes.md
// "Performance").
#include "Bench.hpp"

#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/SceneFile.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <map>

namespace sylva::bench {

namespace {

/** 1234567 → "1.23M". */
std::string compact(std::int64_t n) {
  const double v = static_cast<double>(n);
  if (v >= 1e9) {
    return fmt::format("{:.3g}G", v / 1e9);
  }
  if (v >= 1e6) {
    return fmt::format("{:.3g}M", v / 1e6);
  }
  if (v >= 1e3) {
    return fmt::format("{:.3g}k", v / 1e3);
  }
  return fmt::format("{}", n);
}

} // namespace

void benchScene(const std::string& file, int frames, int warmup, int width, int height, bool fullQuality,
                nlohmann::json& report) {
  const auto buildStart = std::chrono::steady_clock::now();
  const std::uint64_t rssBefore = residentBytes();
  shader::Library library;
  scene::SceneWorld world(library, scene::loadScene(file));
  scene::SceneDrawOptions draw = world.drawOptions();
  draw.fullQuality = fullQuality;
  world.setDrawOptions(draw);
  const scene::SceneDesc& desc = world.desc();
  render::RenderTarget target(width, height);
  gl::finish();
  const double buildS = std::chrono::duration<double>(std::chrono::steady_clock::now() - buildStart).count();
  // Synchronous: every pass finished before its end, wall times recorded; each pass's work counted too.
  render::GpuTimers timers(3, true, true);
  std::map<std::string, std::vector<double>> cpu;
  std::map<std::string, std::vector<double>> gpu;
  std::map<std::string, std::vector<double>> wall;
  std::map<std::string, std::vector<render::PassCounts>> counts;
  std::vector<std::string> order;
  std::vector<double> frameMs;
  Progress progress(fmt::format("bench scene {}", desc.name), static_cast<std::size_t>(warmup + frames));
  for (int i = 0; i < warmup + frames; ++i) {
    const int frame = desc.output.firstFrame + i;
    const auto start = std::chrono::steady_clock::now();
    timers.beginFrame();
    timers.begin("simulation");
    world.advanceToFrame(frame);
    timers.end();
    const double time = world.frameTime(frame);
    const render::Camera camera = world.camera(desc.output.camera, time, target.aspect());
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    world.draw(camera, width, height, time, &target.depth(), &timers);
    timers.endFrame();
    gl::finish();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (i >= warmup) {
      frameMs.push_back(ms);
      for (const render::PassTiming& t : timers.lastFrame()) {
        if (!cpu.contains(t.name)) {
          order.push_back(t.name);
        }
        cpu[t.name].push_back(t.cpuMs);
        gpu[t.name].push_back(t.gpuMs);
        wall[t.name].push_back(t.wallMs);
        counts[t.name].push_back(t.counts);
      }
    }
    progress.advance(1);
  }
  const std::uint64_t rss = residentBytes();
  const render::Stats frame = render::Stats::of(frameMs);
  const double fps = 1000.0 / frame.median;
  const gl::ContextInfo info = gl::queryContextInfo();
  const bool llvmpipe = info.renderer.find("llvmpipe") != std::string::npos;
  std::vector<BenchRow> rows;
  rows.push_back({fmt::format("{} {}×{}: frames per second (median frame)", desc.name, width, height), fps,
                  "fps", llvmpipe ? 5.0 : 120.0, false, 0,
                  llvmpipe ? "llvmpipe target (scene spec)" : "NVIDIA target is 120 fps at 1920×1080"});
  rows.push_back({"frame time (median; wall, every pass finished)", frame.median, "ms",
                  llvmpipe ? 200.0 : 8.33, true, 0,
                  fmt::format("p10 {:.1f}, p90 {:.1f}", frame.p10, frame.p90)});
  nlohmann::json passes = nlohmann::json::array();
  for (const std::string& name : order) {
    const render::Stats w = render::Stats::of(wall[name]);
    const render::Stats c = render::Stats::of(cpu[name]);
    const render::Stats g = render::Stats::of(gpu[name]);
    const render::PassCounts n = render::medianCounts(counts[name]);
    rows.push_back({"pass " + name + " (wall)", w.median, "ms", std::nan(""), true, 0,
                    fmt::format("cpu {:.2f} ms, gpu timestamps {:.2f} ms", c.median, g.median)});
    // Work, which carries to any GPU: fragments per target pixel (overdraw; shadow passes rasterise into
    // their cascades, so theirs is relative to the view), then the other counters.
    rows.push_back(
        {"pass " + name + " fragments per pixel",
         static_cast<double>(n.fragmentInvocations) / (static_cast<double>(width) * height), "", std::nan(""),
         true, 0,
         fmt::format("{}vertices {}, primitives {}, VS {}, TES {}, rasterised {}, FS {}, CS {}",
                     name == "shadows" ? fmt::format("{:.2f} per cascade texel; ",
                                                     static_cast<double>(n.fragmentInvocations) /
                                                         (static_cast<double>(desc.shadows.size) *
                                                          desc.shadows.size * desc.shadows.cascades))
                                       : std::string(),
                     compact(n.verticesSubmitted), compact(n.primitivesSubmitted),
                     compact(n.vertexInvocations), compact(n.tessEvaluations), compact(n.clippedPrimitives),
                     compact(n.fragmentInvocations), compact(n.computeInvocations))});
    passes.push_back({{"pass", name},
                      {"wall_ms", w.toJson()},
                      {"cpu_ms", c.toJson()},
                      {"gpu_ms", g.toJson()},
                      {"counts", n.toJson()}});
  }
  rows.push_back({"GPU memory the subsystems report", static_cast<double>(world.gpuBytes()) / 1e6, "MB",
                  std::nan(""), true, 0, "shadow maps, trees (pieces, bark, foliage, impostors)"});
  rows.push_back({"process resident memory after the run", static_cast<double>(rss) / 1e6, "MB", std::nan(""),
                  true, 0,
                  fmt::format("{:.0f} MB before building the scene; llvmpipe keeps GPU memory here too",
                              static_cast<double>(rssBefore) / 1e6)});
  rows.push_back({"scene build (load, synthesis, uploads)", buildS, "s", std::nan(""), true, 0,
                  fmt::format("{} trees, {} bodies", world.treeCount(), world.bodies())});
  report["scene"] = file;
  report["passes"] = passes;
  report["frame_ms"] = frame.toJson();
  report["fps"] = fps;
  report["gpu_bytes"] = world.gpuBytes();
  report["resident_bytes"] = rss;
  report["rows"] = printBenchRows(rows);
}

} // namespace sylva::bench
