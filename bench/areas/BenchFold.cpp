#include "Bench.hpp"

#include <folding/FoldingCase.hpp>
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Session.hpp>
#ifdef SYLVA_HAVE_FOLDING_GPU
#include <sylva/folding/gpu/FoldRenderer.hpp>
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

namespace sylva::bench {

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
    auto context = platform::createHeadlessContext(o.context);
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

} // namespace sylva::bench
