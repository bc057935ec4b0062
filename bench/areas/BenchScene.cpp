// `sylva bench scene [--scene FILE]`: a scene file's frames with every pass timed (docs/scenes.md
// "Performance").
#include "Bench.hpp"

#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/Quality.hpp>
#include <sylva/scene/SceneFile.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>

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

void benchScene(const std::string& file, int frames, int warmup, int width, int height,
                const std::string& quality, double targetFps, nlohmann::json& report) {
  const bool automatic = quality == "auto";
  if (automatic) {
    warmup = std::max(warmup, 20); // the governor settles
  }
  const auto buildStart = std::chrono::steady_clock::now();
  const std::uint64_t rssBefore = residentBytes();
  shader::Library library;
  scene::SceneWorld world(library, scene::loadScene(file));
  scene::SceneDrawOptions draw = world.drawOptions();
  draw.fullQuality = quality == "full";
  world.setDrawOptions(draw);
  const scene::SceneDesc& desc = world.desc();
  scene::GovernorSettings governorSettings;
  governorSettings.targetMs = 1000.0 / targetFps;
  scene::QualityGovernor governor(governorSettings);
  std::vector<int> stepFrames(scene::qualityLadder().size(), 0);
  std::optional<render::RenderTarget> target;
  target.emplace(width, height);
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
  // Auto quality runs the viewer's loop: scene time moves on by each frame's wall time (advanceTo: the
  // simulations step as many fixed steps as real time needs, the grass holds what the frame cannot draw);
  // otherwise the sequence's frames, frame-exact.
  double time = world.frameTime(desc.output.firstFrame);
  double lastMs = 0.0;
  for (int i = 0; i < warmup + frames; ++i) {
    const int frame = desc.output.firstFrame + i;
    const auto start = std::chrono::steady_clock::now();
    timers.beginFrame();
    timers.begin("simulation");
    if (automatic) {
      time += lastMs / 1000.0;
      world.advanceTo(time);
    } else {
      world.advanceToFrame(frame);
      time = world.frameTime(frame);
    }
    timers.end();
    const int stepIndex = governor.step(); // 0 (as described) unless automatic
    const scene::QualityStep& step = scene::qualityLadder()[static_cast<std::size_t>(stepIndex)];
    const glm::ivec2 drawn = scene::renderSize({width, height}, step.renderScale);
    if (automatic) {
      world.setQuality(step);
      if (target->width() != drawn.x || target->height() != drawn.y) {
        target.emplace(drawn.x, drawn.y);
      }
    }
    const render::Camera camera =
        world.camera(desc.output.camera, time, static_cast<float>(width) / static_cast<float>(height));
    target->begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    world.draw(camera, target->width(), target->height(), time, &target->depth(), &timers);
    timers.endFrame();
    gl::finish();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (automatic) {
      governor.update(ms);
      lastMs = ms;
    }
    if (i >= warmup) {
      ++stepFrames[static_cast<std::size_t>(stepIndex)];
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
  if (automatic) {
    // The viewer's case: the frames per second auto quality keeps to, and the steps it drew them at.
    rows.push_back({fmt::format("{} {}×{} with auto quality: frames per second (median frame)", desc.name,
                                width, height),
                    fps, "fps", targetFps, false, 0, "the viewer's target (--target-fps)"});
    rows.push_back({"frame time (median; wall, every pass finished)", frame.median, "ms", 1000.0 / targetFps,
                    true, 0, fmt::format("p10 {:.1f}, p90 {:.1f}", frame.p10, frame.p90)});
  } else {
    rows.push_back({fmt::format("{} {}×{}: frames per second (median frame)", desc.name, width, height), fps,
                    "fps", llvmpipe ? 5.0 : 120.0, false, 0,
                    llvmpipe ? "llvmpipe target (scene spec)" : "NVIDIA target is 120 fps at 1920×1080"});
    rows.push_back({"frame time (median; wall, every pass finished)", frame.median, "ms",
                    llvmpipe ? 200.0 : 8.33, true, 0,
                    fmt::format("p10 {:.1f}, p90 {:.1f}", frame.p10, frame.p90)});
  }
  nlohmann::json steps = nlohmann::json::array();
  for (std::size_t s = 0; s < stepFrames.size(); ++s) {
    if (stepFrames[s] == 0) {
      continue;
    }
    const scene::QualityStep& q = scene::qualityLadder()[s];
    const glm::ivec2 drawn = scene::renderSize({width, height}, q.renderScale);
    rows.push_back({fmt::format("quality step {} ({}, {}×{})", s, scene::describe(q), drawn.x, drawn.y),
                    100.0 * stepFrames[s] / std::max(frames, 1), "% of frames", std::nan(""), true, 0,
                    automatic ? "chosen by the governor" : "as described"});
    steps.push_back({{"step", s}, {"frames", stepFrames[s]}, {"describe", scene::describe(q)}});
  }
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
  report["quality"] = quality;
  report["quality_steps"] = steps;
  report["gpu_bytes"] = world.gpuBytes();
  report["resident_bytes"] = rss;
  report["rows"] = printBenchRows(rows);
}

} // namespace sylva::bench
