#pragma once

// Target tables of `sylva bench <area>` for CPU work: each row is a measured value against a target from the
// specs, printed as a table and returned as JSON.

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sylva::app {

/** One measured metric against its target. */
struct BenchRow {
  std::string metric;
  /** NaN when not measured (the note says why). */
  double value;
  std::string unit;
  double target;
  /** The target is an upper bound (else a lower bound). */
  bool atMost;
  /** Threads the measurement used (0: the GPU). */
  unsigned threads;
  std::string note;
};

/** Resident set size of this process in bytes (Linux /proc/self/statm), 0 if unknown. */
std::uint64_t residentBytes();

/**
 * `bench scene`: the scene file's output camera over `frames` frames after `warmup` (simulations stepping at
 * the file's fps), per-pass CPU, GPU and wall times, frames per second against the llvmpipe target (≥ 5 fps
 * at 1280×720), GPU memory the subsystems report and the process's resident memory; needs a current GL
 * context.
 */
void benchScene(const std::string& file, int frames, int warmup, int width, int height,
                nlohmann::json& report);

/** Seconds of each of `runs` calls of `fn` after `warmup` unmeasured calls. */
std::vector<double> timeRuns(int warmup, int runs, const std::function<void()>& fn);

/** Prints the rows as a table (measured, target, ok/MISS) and returns them as a JSON array. */
nlohmann::json printBenchRows(const std::vector<BenchRow>& rows);

/** `bench capture`: grass capture targets (docs/capture.md): extraction latency, refining. */
void benchCapture(nlohmann::json& report);

/**
 * `bench trees`: the paper's Fig. 16 workloads (1 … 1,000 trees) instanced and per piece, tessellation levels
 * 1 and 10, generation of 1,000 trees, wind on 100,000 joints; needs a current GL context. `frames` is
 * divided by 10 (at least 3) per configuration: a forest frame on llvmpipe is slow.
 */
void benchTrees(int frames, int width, int height, nlohmann::json& report);

} // namespace sylva::app
