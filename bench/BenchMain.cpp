// Google Benchmark entry point for Sylva's CPU kernels. GPU work is measured by `sylva bench`.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
