#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/render/DemoScene.hpp>
#include <sylva/render/GpuTimers.hpp>
#include <sylva/render/RenderTarget.hpp>

#include <chrono>
#include <cstdio>
#include <map>

namespace sylva::app {

namespace {

struct BenchOptions {
  ContextFlags context;
  int frames = 120;
  int warmup = 10;
  int width = 1280;
  int height = 720;
  std::string out = "out/bench-demo.json";
  std::string area = "demo";
};

/** Runs `frame` warmup + frames times with synchronous GPU timers; returns the report JSON and prints a
 * table. */
nlohmann::json runFrames(const BenchOptions& o, const std::string& name,
                         const std::function<void(render::GpuTimers&, double time)>& frame) {
  render::GpuTimers timers(1, true);
  std::map<std::string, std::vector<double>> cpu;
  std::map<std::string, std::vector<double>> gpu;
  std::vector<double> total;
  std::vector<std::string> order;
  for (int i = 0; i < o.warmup + o.frames; ++i) {
    const auto start = std::chrono::steady_clock::now();
    timers.beginFrame();
    frame(timers, 1.0 + i / 60.0);
    timers.endFrame(); // synchronous: waits for this frame's GPU results
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (i < o.warmup) {
      continue;
    }
    total.push_back(ms);
    for (const render::PassTiming& t : timers.lastFrame()) {
      if (cpu.find(t.name) == cpu.end()) {
        order.push_back(t.name);
      }
      cpu[t.name].push_back(t.cpuMs);
      gpu[t.name].push_back(t.gpuMs);
    }
  }
  const gl::ContextInfo info = gl::queryContextInfo();
  const MachineInfo machine = machineInfo();
  nlohmann::json passes = nlohmann::json::array();
  std::printf("%s: %d frames after %d warm-up, %dx%d, %s\n", name.c_str(), o.frames, o.warmup, o.width,
              o.height, info.renderer.c_str());
  std::printf("  %-20s %12s %12s %12s %12s\n", "pass", "cpu median", "gpu median", "gpu p10", "gpu p90");
  for (const std::string& pass : order) {
    const render::Stats c = render::Stats::of(cpu[pass]);
    const render::Stats g = render::Stats::of(gpu[pass]);
    std::printf("  %-20s %9.3f ms %9.3f ms %9.3f ms %9.3f ms\n", pass.c_str(), c.median, g.median, g.p10,
                g.p90);
    passes.push_back({{"name", pass}, {"cpu_ms", c.toJson()}, {"gpu_ms", g.toJson()}});
  }
  const render::Stats f = render::Stats::of(total);
  std::printf("  %-20s %9.3f ms   (%.1f frames/s at the median)\n", "frame (wall)", f.median,
              1000.0 / f.median);
  return {{"benchmark", name},
          {"machine", {{"host", machine.host}, {"cpu", machine.cpu}, {"cores", machine.cores}}},
          {"renderer", {{"vendor", info.vendor}, {"renderer", info.renderer}, {"version", info.version}}},
          {"frames", o.frames},
          {"warmup", o.warmup},
          {"resolution", {o.width, o.height}},
          {"frame_ms", f.toJson()},
          {"passes", passes}};
}

} // namespace

void registerBench(CLI::App& app) {
  auto* command = app.add_subcommand("bench", "Measure CPU and GPU time per pass over N frames; writes JSON");
  auto o = std::make_shared<BenchOptions>();
  command->add_option("area", o->area, "What to measure: demo")
      ->check(CLI::IsMember({"demo"}))
      ->capture_default_str();
  o->context.add(*command);
  command->add_option("--frames", o->frames, "Measured frames")
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
  command->add_option("-o,--out", o->out, "JSON report path")->capture_default_str();
  command->callback([o] {
    auto context = platform::createHeadlessContext(o->context.options());
    shader::Library library;
    render::RenderTarget target(o->width, o->height);
    render::DemoScene scene(library);
    const render::Camera camera = scene.defaultCamera();
    nlohmann::json report = runFrames(*o, o->area, [&](render::GpuTimers& timers, double time) {
      target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      scene.render(camera, o->width, o->height, time, &timers);
    });
    report["context"] = context->description();
    saveJsonFile(o->out, report);
    std::printf("%s\n", o->out.c_str());
  });
}

} // namespace sylva::app
