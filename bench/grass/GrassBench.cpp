// The grass constraint solver on the CPU (docs/grass-simulation.md, "Benchmarks"): one solver step of the
// paper's Table 1 workloads (SolverCase.hpp) on every core (SYLVA_THREADS=1: on one), with the SIMD kernel
// and, for the largest, the scalar reference. Target: 709 tiles, 128 bodies in ≤ 10 ms on 2 cores. Run:
// sylva_benchmarks --benchmark_filter=GrassSolver
#include "SolverCase.hpp"

#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

namespace {

using namespace sylva::grass;

const std::shared_ptr<GrassField>& field() {
  static const std::shared_ptr<GrassField> shared = bench::solverField();
  return shared;
}

void stepTable1(benchmark::State& state, SolverKernel kernel) {
  const int tiles = static_cast<int>(state.range(0));
  const int bodies = static_cast<int>(state.range(1));
  PoolSettings pool;
  pool.tiles = tiles;
  SolverSettings solver;
  solver.kernel = kernel;
  TileSimulation sim(field(), pool, solver);
  const sylva::wind::WindSettings wind = bench::solverWind();
  const std::vector<std::vector<BladeCollider>> colliders =
      bench::setUpSolverCase(sim, *field(), tiles, bodies, wind);
  std::size_t blades = 0;
  for (std::size_t i = 0; i < sim.blades().count(); ++i) {
    blades += sim.bladeInUse(i) ? 1 : 0;
  }
  for (auto _ : state) {
    sim.stepSolver(colliders, wind);
  }
  state.counters["blades"] = static_cast<double>(blades);
  state.counters["ns_per_blade"] =
      benchmark::Counter(static_cast<double>(blades) * state.iterations(),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

/** The SIMD kernel (the default). */
void BM_GrassSolverTable1(benchmark::State& state) {
  stepTable1(state, SolverKernel::Simd);
}
BENCHMARK(BM_GrassSolverTable1)
    ->Args({6, 1})
    ->Args({150, 20})
    ->Args({709, 128})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/** The scalar reference, one blade at a time (the code the compute shader mirrors). */
void BM_GrassSolverTable1_Scalar(benchmark::State& state) {
  stepTable1(state, SolverKernel::Scalar);
}
BENCHMARK(BM_GrassSolverTable1_Scalar)->Args({709, 128})->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
