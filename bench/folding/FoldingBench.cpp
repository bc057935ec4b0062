// Folding-texture CPU kernels on the generated 1 MP case (FoldingCase.hpp): synthesis with the Shepard
// variants, polygon thresholds, region re-synthesis after moving one anchor, and the CPU reference render.
// Items are pixels, so "items_per_second" reads as pixels per second. Targets: docs/folding.md. Run:
// sylva_benchmarks --benchmark_filter=Fold
#include "FoldingCase.hpp"

#include <sylva/core/Parallel.hpp>
#include <sylva/folding/Renderer.hpp>

#include <benchmark/benchmark.h>

#include <array>

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
  const Project moved = movedAnchor(p, 500, Vec2(5.0, 3.0), textures.atlas.entries[0], region);
  for (auto _ : state) {
    resynthesize(moved, images, textures, region);
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t{region.width()} * region.height());
  state.counters["region_px"] = static_cast<double>(region.width()) * region.height();
}
BENCHMARK(BM_FoldResynthesisOneAnchor)->Unit(benchmark::kMillisecond)->UseRealTime();

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
