// `sylva bench capture`: the grass-capture targets of docs/capture.md and the issue: latency of one 640x480
// depth frame to blades on one core (OpenCV limited to one thread; colour-guided edges on and off, and the
// Canny contour), refining 128 -> 16 knots (heap, one frame and 60 frames of motion; the paper's O(n^2) loop
// beside it), a whole blade model (three levels over a 60-frame simulated sway) and the synthetic generator.
// Inputs are the synthetic clusters of the accuracy tests. Medians of 9 runs after 2 warm-ups.
#include "Bench.hpp"

#include <sylva/capture/Extract.hpp>
#include <sylva/capture/Pipeline.hpp>
#include <sylva/capture/Refine.hpp>
#include <sylva/capture/Synthetic.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>

#include <cmath>
#include <cstdio>

namespace sylva::bench {

void benchCapture(nlohmann::json& report) {
  using namespace sylva::capture;
  const MachineInfo machine = machineInfo();
  constexpr int kRuns = 9;
  constexpr int kWarmup = 2;
  const double nan = std::nan("");
  std::vector<BenchRow> rows;
  const auto median = [&](const std::function<void()>& fn) {
    return render::Stats::of(timeRuns(kWarmup, kRuns, fn)).median;
  };
  std::printf("capture: 640x480 synthetic clusters, %s, %u cores\n", machine.cpu.c_str(), machine.cores);

  const SyntheticFrame frame = renderScene(makeCluster(BladeShape::SlimGrass, 7, 0.4f, 0.0f, 1));
  volatile std::size_t sink = 0;
  setExtractionThreads(1);
  const auto extractRow = [&](const std::string& name, ExtractOptions options) {
    const double s = median([&] { sink = extractBlades(frame.frame, options).blades.size(); });
    rows.push_back({name, s * 1e3, "ms/frame", 30.0, true, 1, ""});
  };
  ExtractOptions colour;
  ExtractOptions depthOnly;
  depthOnly.colourRefine = false;
  ExtractOptions canny = depthOnly;
  canny.contour = ContourMethod::Canny;
  extractRow("640x480 frame to blades, colour-guided edges", colour);
  extractRow("640x480 frame to blades, depth only", depthOnly);
  extractRow("640x480 frame to blades, Canny on depth", canny);
  setExtractionThreads(0);

  const ExtractResult captured = extractBlades(frame.frame);
  const CapturedBlade& blade = captured.blades.front();
  SwayOptions sway;
  sway.frames = 60;
  KnotFrames still{blade.knots};
  KnotFrames moving = swayFrames(blade.knots, blade.sides.front(), sway);
  RefineOptions refine;
  refine.knots = 16;
  const auto refineRow = [&](const std::string& name, const KnotFrames& frames, bool reference,
                             double target) {
    const double s = median([&] {
      const RefineResult r = reference ? refineKnotsReference(frames, blade.widths, refine)
                                       : refineKnots(frames, blade.widths, refine);
      sink = r.widths.size();
    });
    rows.push_back(
        {name, s * 1e3, "ms", target, true, 1, reference ? "the paper's loop, for comparison" : ""});
  };
  refineRow("refine 128 -> 16 knots, 1 frame", still, false, 0.1);
  refineRow("refine 128 -> 16 knots, 60 frames of motion", moving, false, 0.1);
  refineRow("refine 128 -> 16 knots, 60 frames, O(n^2) loop", moving, true, nan);
  {
    ModelOptions model;
    const double s = median([&] { sink = makeBladeModel(blade, {}, model, {}).lods.size(); });
    rows.push_back({"blade model: 64/32/16 knots over a 60-frame sway", s * 1e3, "ms", nan, true, 1, ""});
  }
  {
    const SyntheticScene scene = makeCluster(BladeShape::SlimGrass, 7, 0.4f, 0.0f, 1);
    const double s = median([&] { sink = renderScene(scene).frame.depth.size(); });
    rows.push_back({"synthetic 640x480 frame with noise and colour", s * 1e3, "ms", nan, true, 1, ""});
  }
  const nlohmann::json rowsJson = printBenchRows(rows);
  report = {{"benchmark", "capture"},
            {"machine", {{"host", machine.host}, {"cpu", machine.cpu}, {"cores", machine.cores}}},
            {"case", {{"size", {640, 480}}, {"shape", "slim"}, {"blades", 7}}},
            {"runs", kRuns},
            {"rows", rowsJson}};
  (void)sink;
}

} // namespace sylva::bench
