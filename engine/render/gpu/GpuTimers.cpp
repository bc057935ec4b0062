#include <sylva/render/gpu/GpuTimers.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

namespace {

/** The pipeline statistics PassCounts holds, in its field order. */
constexpr std::array<GLenum, 7> kCounterTargets = {
    GL_VERTICES_SUBMITTED_ARB,         GL_PRIMITIVES_SUBMITTED_ARB,
    GL_VERTEX_SHADER_INVOCATIONS_ARB,  GL_TESS_EVALUATION_SHADER_INVOCATIONS_ARB,
    GL_CLIPPING_OUTPUT_PRIMITIVES_ARB, GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
    GL_COMPUTE_SHADER_INVOCATIONS_ARB};
constexpr std::size_t kCounters = kCounterTargets.size();

/** PassCounts' fields in kCounterTargets' order. */
constexpr std::array<std::int64_t PassCounts::*, kCounters> kFields = {
    &PassCounts::verticesSubmitted, &PassCounts::primitivesSubmitted, &PassCounts::vertexInvocations,
    &PassCounts::tessEvaluations,   &PassCounts::clippedPrimitives,   &PassCounts::fragmentInvocations,
    &PassCounts::computeInvocations};

} // namespace

nlohmann::json PassCounts::toJson() const {
  return {{"vertices_submitted", verticesSubmitted},  {"primitives_submitted", primitivesSubmitted},
          {"vertex_invocations", vertexInvocations},  {"tess_evaluations", tessEvaluations},
          {"clipped_primitives", clippedPrimitives},  {"fragment_invocations", fragmentInvocations},
          {"compute_invocations", computeInvocations}};
}

PassCounts medianCounts(const std::vector<PassCounts>& frames) {
  PassCounts m;
  if (frames.empty()) {
    return m;
  }
  std::vector<std::int64_t> v(frames.size());
  for (auto field : kFields) {
    for (std::size_t i = 0; i < frames.size(); ++i) {
      v[i] = frames[i].*field;
    }
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    m.*field = v[v.size() / 2];
  }
  return m;
}

GpuTimers::GpuTimers(int latency, bool synchronous, bool countWork)
    : mSlots(static_cast<std::size_t>(std::max(latency, 1))), mSynchronous(synchronous),
      mCountWork(countWork) {
  if (mCountWork && !mSynchronous) {
    fail("GpuTimers: counting work needs synchronous mode");
  }
  if (mCountWork && !epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query") && epoxy_gl_version() < 46) {
    fail("GpuTimers: counting work needs GL_ARB_pipeline_statistics_query, which this driver lacks");
  }
}

void GpuTimers::beginFrame() {
  Slot& slot = mSlots[mCurrent];
  if (slot.pending) {
    collect(slot, true); // the ring wrapped: this frame's results are `latency` frames old and done by now
  }
  slot.timings.clear();
}

void GpuTimers::begin(const std::string& pass) {
  if (mInPass) {
    fail("GpuTimers: pass '{}' begun inside another pass", pass);
  }
  Slot& slot = mSlots[mCurrent];
  const std::size_t index = slot.timings.size();
  while (slot.queries.size() < 2 * (index + 1)) {
    slot.queries.emplace_back(GL_TIMESTAMP);
  }
  slot.timings.push_back({pass, 0.0, -1.0});
  slot.queries[2 * index].timestamp();
  if (mCountWork) {
    while (slot.counters.size() < kCounters * (index + 1)) {
      slot.counters.emplace_back(kCounterTargets[slot.counters.size() % kCounters]);
    }
    for (std::size_t k = 0; k < kCounters; ++k) {
      slot.counters[kCounters * index + k].begin();
    }
  }
  mPassStart = std::chrono::steady_clock::now();
  mInPass = true;
}

void GpuTimers::end() {
  Slot& slot = mSlots[mCurrent];
  if (!mInPass || slot.timings.empty()) {
    fail("GpuTimers: end() without begin()");
  }
  const std::size_t index = slot.timings.size() - 1;
  if (mCountWork) {
    for (std::size_t k = 0; k < kCounters; ++k) {
      slot.counters[kCounters * index + k].end();
    }
  }
  slot.timings[index].cpuMs =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mPassStart).count();
  if (mSynchronous) {
    // Benchmarks are synchronous anyway, so finishing here costs no overlap, and gives the pass's wall time.
    glFinish();
    slot.timings[index].wallMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mPassStart).count();
  }
  slot.queries[2 * index + 1].timestamp();
  mInPass = false;
}

void GpuTimers::endFrame() {
  Slot& slot = mSlots[mCurrent];
  slot.pending = true;
  if (mSynchronous) {
    collect(slot, true);
  }
  mCurrent = (mCurrent + 1) % mSlots.size();
  // Collect whatever older frames finished without waiting.
  for (std::size_t i = 1; i < mSlots.size(); ++i) {
    Slot& older = mSlots[(mCurrent + i) % mSlots.size()];
    if (older.pending) {
      collect(older, false);
    }
  }
}

void GpuTimers::collect(Slot& slot, bool wait) {
  if (!wait && !slot.queries.empty() && !slot.queries[2 * slot.timings.size() - 1].available()) {
    return;
  }
  for (std::size_t i = 0; i < slot.timings.size(); ++i) {
    const auto start = slot.queries[2 * i].result(true);
    const auto stop = slot.queries[2 * i + 1].result(true);
    slot.timings[i].gpuMs = static_cast<double>(*stop - *start) * 1e-6;
    if (mCountWork) {
      for (std::size_t k = 0; k < kCounters; ++k) {
        slot.timings[i].counts.*kFields[k] =
            static_cast<std::int64_t>(*slot.counters[kCounters * i + k].result(true));
      }
    }
  }
  slot.pending = false;
  mLast = slot.timings;
}

} // namespace sylva::render
