// What every area shares: the GPU-timed frame loop, the report's head, the machine, the target table, and the
// demo area (the built-in pipeline scene).
#include "Bench.hpp"

#include <sylva/gl/ContextInfo.hpp>
#include <sylva/render/gpu/DemoScene.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/shader/Library.hpp>

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <thread>

namespace sylva::bench {

std::uint64_t residentBytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size = 0;
  std::uint64_t resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::vector<double> timeRuns(int warmup, int runs, const std::function<void()>& fn) {
  std::vector<double> seconds;
  for (int i = 0; i < warmup + runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (i >= warmup) {
      seconds.push_back(s);
    }
  }
  return seconds;
}

nlohmann::json printBenchRows(const std::vector<BenchRow>& rows) {
  std::printf("  %-62s %12s %-16s %8s %5s %7s  %s\n", "metric", "measured", "unit", "target", "", "threads",
              "note");
  nlohmann::json rowsJson = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    const bool measured = !std::isnan(r.value);
    const bool hasTarget = !std::isnan(r.target);
    const bool pass = measured && hasTarget && (r.atMost ? r.value <= r.target : r.value >= r.target);
    const std::string target = hasTarget ? fmt::format("{:g}", r.target) : std::string();
    std::printf("  %-62s %12.4g %-16s %2s %5s %5s %7s  %s\n", r.metric.c_str(), r.value, r.unit.c_str(),
                !hasTarget ? ""
                : r.atMost ? "<="
                           : ">=",
                target.c_str(),
                !measured || !hasTarget ? "-"
                : pass                  ? "ok"
                                        : "MISS",
                r.threads == 0 ? "gpu" : std::to_string(r.threads).c_str(), r.note.c_str());
    rowsJson.push_back({{"metric", r.metric},
                        {"value", measured ? nlohmann::json(r.value) : nlohmann::json(nullptr)},
                        {"unit", r.unit},
                        {"target", hasTarget ? nlohmann::json(r.target) : nlohmann::json(nullptr)},
                        {"target_is", r.atMost ? "at most" : "at least"},
                        {"met", measured && hasTarget ? nlohmann::json(pass) : nlohmann::json(nullptr)},
                        {"threads", r.threads},
                        {"note", r.note}});
  }
  return rowsJson;
}

MachineInfo machineInfo() {
  MachineInfo info;
  char host[256] = {};
  ::gethostname(host, sizeof(host) - 1);
  info.host = host;
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      info.cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  info.cores = std::thread::hardware_concurrency();
  return info;
}

Samples measure(const BenchOptions& o, const std::function<void(render::GpuTimers&, int, Samples&)>& frame) {
  render::GpuTimers timers(1, true, true);
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
      s.counts[t.name].push_back(t.counts);
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

} // namespace sylva::bench
