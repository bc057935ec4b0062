#pragma once

#include <sylva/gl/Query.hpp>
#include <sylva/render/Timing.hpp>

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sylva::render {

/** Timing of one named pass in one frame, milliseconds. GPU time is -1 until its query result is known. */
struct PassTiming {
  std::string name;
  double cpuMs = 0.0;
  double gpuMs = -1.0;
  /**
   * Synchronous mode only: wall time from begin() until the pass's work has finished (glFinish). The honest
   * figure on llvmpipe, whose timestamps do not cover rasterisation deferred to its worker threads; -1
   * otherwise.
   */
  double wallMs = -1.0;
};

/**
 * Per-pass CPU and GPU timings. Each pass is bracketed by begin(name)/end(); GPU time comes from GL_TIMESTAMP
 * queries kept in a ring of `latency` frames, so reading results never stalls the pipeline (except in
 * `synchronous` mode, used by benchmarks and tests, which waits for each frame's results at endFrame() and
 * finishes each pass's work before its end timestamp, also recording the pass's wall time to completion).
 */
class GpuTimers {
public:
  explicit GpuTimers(int latency = 3, bool synchronous = false);

  void beginFrame();
  void begin(const std::string& pass);
  void end();
  void endFrame();
  /** The most recent frame whose GPU results are complete. */
  const std::vector<PassTiming>& lastFrame() const { return mLast; }

private:
  struct Slot {
    std::vector<gl::Query> queries; // 2 per pass
    std::vector<PassTiming> timings;
    bool pending = false;
  };
  void collect(Slot& slot, bool wait);

  std::vector<Slot> mSlots;
  std::size_t mCurrent = 0;
  bool mSynchronous;
  std::vector<PassTiming> mLast;
  std::chrono::steady_clock::time_point mPassStart;
  bool mInPass = false;
};

/**
 * Times the enclosing scope as pass `name` of `timers`: begin() on construction, end() on destruction (early
 * returns included); nothing when `timers` is null, so a pass can be timed or not with one line.
 */
class GpuTimerScope {
public:
  GpuTimerScope(GpuTimers* timers, const std::string& name) : mTimers(timers) {
    if (mTimers != nullptr) {
      mTimers->begin(name);
    }
  }
  ~GpuTimerScope() {
    if (mTimers != nullptr) {
      mTimers->end();
    }
  }
  GpuTimerScope(const GpuTimerScope&) = delete;
  GpuTimerScope& operator=(const GpuTimerScope&) = delete;

private:
  GpuTimers* mTimers;
};

} // namespace sylva::render
