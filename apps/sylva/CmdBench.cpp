#include "Bench.hpp"
#include "Commands.hpp"
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