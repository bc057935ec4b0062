#pragma once
// Time on the CPU side of a frame: the frame clock (real or a fixed step) and the statistics benchmark
// reports give of timed samples. The GPU's own timers are gpu/GpuTimers.hpp.

#include <chrono>
#include <cstddef>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace sylva::render {

/** Median, spread (min, max, p10, p90) of samples; for `sylva bench` reports. */
struct Stats {
  double median = 0.0;   ///< middle sample
  double min = 0.0;      ///< smallest sample
  double max = 0.0;      ///< largest sample
  double p10 = 0.0;      ///< 10th percentile
  double p90 = 0.0;      ///< 90th percentile
  std::size_t count = 0; ///< samples
  /** The statistics of `samples` (all 0 when empty). */
  static Stats of(std::vector<double> samples);
  /** The fields as a JSON object. */
  nlohmann::json toJson() const;
};

/**
 * Frame clock: real time, or a fixed step (seconds per frame) so animation and simulation are deterministic
 * in tests, goldens and benchmarks.
 */
class FrameClock {
public:
  /** `fixedStep` > 0 selects the fixed clock. */
  explicit FrameClock(double fixedStep = 0.0);
  /** Advances one frame; returns the frame's dt in seconds. */
  double tick();
  /** Seconds since start (fixed: frames × step). */
  double time() const { return mTime; }
  /** Whether the clock steps by a fixed amount. */
  bool fixed() const { return mFixedStep > 0.0; }

private:
  double mFixedStep;
  double mTime = 0.0;
  std::chrono::steady_clock::time_point mLast;
  bool mStarted = false;
};

} // namespace sylva::render
