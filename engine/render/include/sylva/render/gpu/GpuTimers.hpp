#pragma once

#include <sylva/gl/Query.hpp>
#include <sylva/render/Timing.hpp>

#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sylva::render {

/**
 * The work a pass made the GPU do (ARB_pipeline_statistics_query): figures that carry from llvmpipe to any
 * GPU, unlike its times. Every field is -1 when the pass was not counted.
 */
struct PassCounts {
  std::int64_t verticesSubmitted = -1;   ///< vertices read by draws
  std::int64_t primitivesSubmitted = -1; ///< primitives assembled from them (before tessellation)
  std::int64_t vertexInvocations = -1;   ///< vertex-shader runs
  std::int64_t tessEvaluations = -1;     ///< tessellation-evaluation runs (vertices the tessellator made)
  std::int64_t clippedPrimitives = -1;   ///< primitives that left clipping (what the rasteriser received)
  std::int64_t fragmentInvocations = -1; ///< fragment-shader runs (pixels shaded, overdraw included)
  std::int64_t computeInvocations = -1;  ///< compute-shader runs (culling, simulation, LOD)
  /** Whether the counts were measured (-1: not counted). */
  bool counted() const { return verticesSubmitted >= 0; }
  /** {"vertices_submitted": …, …} for benchmark JSON. */
  nlohmann::json toJson() const;
};

/** Field-wise median of a pass's counts over frames (-1 fields when `frames` is empty). */
PassCounts medianCounts(const std::vector<PassCounts>& frames);

/** Timing of one named pass in one frame, milliseconds. GPU time is -1 until its query result is known. */
struct PassTiming {
  std::string name;    ///< the pass, as given to begin()
  double cpuMs = 0.0;  ///< CPU time between begin() and end()
  double gpuMs = -1.0; ///< GPU time between the pass's timestamps
  /**
   * Synchronous mode only: wall time from begin() until the pass's work has finished (glFinish). The honest
   * figure on llvmpipe, whose timestamps do not cover rasterisation deferred to its worker threads; -1
   * otherwise.
   */
  double wallMs = -1.0;
  PassCounts counts; ///< when the timers count work (synchronous mode with countWork)
};

/**
 * Per-pass CPU and GPU timings. Each pass is bracketed by begin(name)/end(); GPU time comes from GL_TIMESTAMP
 * queries kept in a ring of `latency` frames, so reading results never stalls the pipeline (except in
 * `synchronous` mode, used by benchmarks and tests, which waits for each frame's results at endFrame() and
 * finishes each pass's work before its end timestamp, also recording the pass's wall time to completion).
 */
class GpuTimers {
public:
  /**
   * `countWork` (synchronous mode only) also counts each pass's work (PassCounts) with pipeline-statistics
   * queries; passes must then not run queries of those kinds themselves (e.g. the grass's primitive count).
   */
  explicit GpuTimers(int latency = 3, bool synchronous = false, bool countWork = false);

  /** Starts a frame (collects the results of the frame `latency` frames ago). */
  void beginFrame();
  /** Starts timing pass `pass`. */
  void begin(const std::string& pass);
  /** Ends the current pass. */
  void end();
  /** Ends the frame (synchronous mode: waits for its results). */
  void endFrame();
  /** The most recent frame whose GPU results are complete. */
  const std::vector<PassTiming>& lastFrame() const { return mLast; }

private:
  struct Slot {
    std::vector<gl::Query> queries;  // 2 per pass
    std::vector<gl::Query> counters; // kCounters per pass when counting work
    std::vector<PassTiming> timings;
    bool pending = false;
  };
  void collect(Slot& slot, bool wait);

  std::vector<Slot> mSlots;
  std::size_t mCurrent = 0;
  bool mSynchronous;
  bool mCountWork;
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
  /** Begins pass `name` of `timers` (nothing when null). */
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
