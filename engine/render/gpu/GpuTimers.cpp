#include <sylva/render/gpu/GpuTimers.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

GpuTimers::GpuTimers(int latency, bool synchronous)
    : mSlots(static_cast<std::size_t>(std::max(latency, 1))), mSynchronous(synchronous) {}

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
  mPassStart = std::chrono::steady_clock::now();
  mInPass = true;
}

void GpuTimers::end() {
  Slot& slot = mSlots[mCurrent];
  if (!mInPass || slot.timings.empty()) {
    fail("GpuTimers: end() without begin()");
  }
  const std::size_t index = slot.timings.size() - 1;
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
  }
  slot.pending = false;
  mLast = slot.timings;
}

} // namespace sylva::render
