// Capture CPU kernels: skeleton refining (paper §4.4) of a 128-knot blade swaying over 1 or 60 frames, with
// the heap refiner and the paper's O(n²) loop for comparison, and the movement difference D of one knot pair.
// Target (shared/specs/grass.md): refine 128 → 16 knots ≤ 0.1 ms. Run: sylva_benchmarks
// --benchmark_filter=Refine
#include <sylva/capture/Refine.hpp>

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using namespace sylva::capture;

/** A gently curved 0.3 m blade of `knots` knots swaying about X for `frames` frames, and its widths. */
struct BenchBlade {
  KnotFrames frames;
  std::vector<float> widths;
};

BenchBlade benchBlade(int knots, int frames) {
  std::vector<glm::vec3> rest;
  BenchBlade blade;
  for (int k = 0; k < knots; ++k) {
    const float s = static_cast<float>(k) / static_cast<float>(knots - 1);
    rest.emplace_back(0.0f, 0.3f * s, 0.02f * s * s);
    blade.widths.push_back(0.008f * (1.0f - s * s));
  }
  SwayOptions sway;
  sway.frames = frames;
  blade.frames = swayFrames(rest, {1.0f, 0.0f, 0.0f}, sway);
  return blade;
}

/** Args: input knots, frames, output knots. */
void BM_Refine(benchmark::State& state) {
  const BenchBlade blade = benchBlade(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  RefineOptions options;
  options.knots = static_cast<int>(state.range(2));
  for (auto _ : state) {
    benchmark::DoNotOptimize(refineKnots(blade.frames, blade.widths, options));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_Refine)
    ->ArgNames({"knots", "frames", "to"})
    ->Args({128, 1, 16})
    ->Args({128, 60, 16})
    ->Args({128, 60, 32})
    ->Args({128, 60, 64})
    ->Unit(benchmark::kMicrosecond);

/** The paper's Algorithm 1 as written (all differences recomputed per merge), same cases. */
void BM_RefineReference(benchmark::State& state) {
  const BenchBlade blade = benchBlade(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  RefineOptions options;
  options.knots = static_cast<int>(state.range(2));
  for (auto _ : state) {
    benchmark::DoNotOptimize(refineKnotsReference(blade.frames, blade.widths, options));
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_RefineReference)
    ->ArgNames({"knots", "frames", "to"})
    ->Args({128, 1, 16})
    ->Args({128, 60, 16})
    ->Args({128, 60, 32})
    ->Args({128, 60, 64})
    ->Unit(benchmark::kMicrosecond);

/** D (eq. 1–3) of the root and tip knots over 60 frames. */
void BM_RefineMovementDifference(benchmark::State& state) {
  const BenchBlade blade = benchBlade(128, 60);
  std::vector<glm::vec3> root;
  std::vector<glm::vec3> tip;
  for (const auto& frame : blade.frames) {
    root.push_back(frame.front());
    tip.push_back(frame.back());
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(movementDifference(root, tip, 0.5));
  }
  state.SetItemsProcessed(state.iterations() * 60);
}
BENCHMARK(BM_RefineMovementDifference);

} // namespace
