// Folding-texture CPU kernels on the generated 1 MP case (FoldingCase.hpp): synthesis with the Shepard
// variants, polygon thresholds, region re-synthesis after moving one anchor, the CPU part of an editor drag
// step, and the CPU reference render.
// Items are pixels, so "items_per_second" reads as pixels per second. Targets: docs/folding.md. Run:
// sylva_benchmarks --benchmark_filter=Fold
#include "FoldingCase.hpp"

#include <sylva/core/Parallel.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Renderer.hpp>

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <numbers>

namespace {

using namespace sylva::folding;
using namespace sylva::folding::bench;

Interpolation interpolation(Interpolation::Type type) {
  Interpolation interp;
  interp.type = type;
  interp.radius = 64.0;
  interp.power = 2.0;
  return interp;
}

void setPixels(benchmark::State& state, std::int64_t pixels) {
  state.SetItemsProcessed(state.iterations() * pixels);
  state.counters["s_per_MP"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * pixels / 1048576.0,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Synthesis and thresholds run on every worker thread: their times are wall-clock (UseRealTime), not the
// calling thread's CPU time.

/** Whole synthesis (atlas, anchors, field, thresholds, on every worker) of the 1 MP zone. */
void BM_FoldSynthesisModifiedShepard(benchmark::State& state) {
  const Project p =
      benchProject(static_cast<int>(state.range(0)), interpolation(Interpolation::Type::ModifiedShepard));
  const ProjectImages images = benchImages();
  for (auto _ : state) {
    benchmark::DoNotOptimize(synthesize(p, images));
  }
  setPixels(state, std::int64_t{kCaseSide} * kCaseSide);
}
BENCHMARK(BM_FoldSynthesisModifiedShepard)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_FoldSynthesisShepard(benchmark::State& state) {
  const Project p =
      benchProject(static_cast<int>(state.range(0)), interpolation(Interpolation::Type::Shepard));
  const ProjectImages images = benchImages();
  for (auto _ : state) {
    benchmark::DoNotOptimize(synthesize(p, images));
  }
  setPixels(state, std::int64_t{kCaseSide} * kCaseSide);
}
BENCHMARK(BM_FoldSynthesisShepard)->Arg(100)->Unit(benchmark::kMillisecond)->UseRealTime();

/** Fold intervals of every pixel's jump path against the 64-vertex star (on every worker, as synthesis). */
void BM_FoldThresholds64(benchmark::State& state) {
  const std::array<std::vector<Vec2>, 1> polygons{benchStar()};
  for (auto _ : state) {
    sylva::parallelFor(kCaseSide, [&](std::size_t begin, std::size_t end) {
      for (std::size_t y = begin; y < end; ++y) {
        for (int x = 0; x < kCaseSide; ++x) {
          const Vec2 q(x + 0.5, static_cast<double>(y) + 0.5);
          benchmark::DoNotOptimize(foldIntervals(polygons, q, benchJump(x, static_cast<int>(y))));
        }
      }
    });
  }
  setPixels(state, std::int64_t{kCaseSide} * kCaseSide);
}
BENCHMARK(BM_FoldThresholds64)->Unit(benchmark::kMillisecond)->UseRealTime();

/** Re-synthesis of the region one moved anchor affects (modified Shepard, 1,000 anchors, R = 64 px). */
void BM_FoldResynthesisOneAnchor(benchmark::State& state) {
  const Project p = benchProject(1000, interpolation(Interpolation::Type::ModifiedShepard));
  const ProjectImages images = benchImages();
  Textures textures = synthesize(p, images);
  Rect region;
  const Project moved = movedAnchor(p, 500, Vec2(5.0, 3.0), textures.atlas, region);
  for (auto _ : state) {
    resynthesize(moved, images, textures, region);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t{region.width()} * region.height());
  state.counters["region_px"] = static_cast<double>(region.width()) * region.height();
}
BENCHMARK(BM_FoldResynthesisOneAnchor)->Unit(benchmark::kMillisecond)->UseRealTime();

/**
 * The CPU part of one drag step in the editor (the GPU upload and preview frame are timed by `sylva bench
 * fold`): the validated edit moving anchor 500 (movePointAnchor through EditHistory::apply), the region it
 * can change (anchorMoveAtlasRect) and its re-synthesis; the anchor walks a circle of 6 px in 30 steps.
 */
void BM_FoldDragStepCpu(benchmark::State& state) {
  const Project p = benchProject(1000, interpolation(Interpolation::Type::ModifiedShepard));
  const ProjectImages images = benchImages();
  Textures textures = synthesize(p, images);
  EditHistory history(p);
  const Vec2 centre = std::get<PointsTool>(p.zones[0].tools[0]).pairs[500][1];
  Vec2 position = centre;
  int step = 0;
  double regionPixels = 0.0;
  for (auto _ : state) {
    const double angle = 2.0 * std::numbers::pi * (++step % 30) / 30.0;
    const Vec2 next = centre + 6.0 * Vec2(std::cos(angle), std::sin(angle));
    movePointAnchor(history, 0, 0, 500, 1, next);
    const Rect region = anchorMoveAtlasRect(history.project(), textures.atlas, 0, position, next);
    resynthesize(history.project(), images, textures, region);
    position = next;
    regionPixels = static_cast<double>(region.width()) * region.height();
  }
  state.counters["region_px"] = regionPixels;
}
BENCHMARK(BM_FoldDragStepCpu)->Unit(benchmark::kMillisecond)->UseRealTime();

/** One frame of the CPU reference renderer on one thread (the whole 1 MP atlas moves). */
void BM_FoldRenderCpuOneThread(benchmark::State& state) {
  const Project p = benchProject(1000, interpolation(Interpolation::Type::ModifiedShepard));
  const Textures textures = synthesize(p, benchImages());
  double t = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderFrame(textures, p.profiles, p.jumpLayers, t, 1));
    t += 1.0 / 30.0;
  }
  setPixels(state, std::int64_t{textures.width()} * textures.height());
}
BENCHMARK(BM_FoldRenderCpuOneThread)->Unit(benchmark::kMillisecond);

} // namespace
