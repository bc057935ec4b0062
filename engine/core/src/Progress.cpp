#include <sylva/core/Progress.hpp>

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace sylva {

namespace {
std::atomic<int> gActive{0};
std::atomic<bool> gCancelAll{false};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free,
              "SIGINT handlers may only touch lock-free atomics");
} // namespace

void Progress::cancelAll() noexcept {
  gCancelAll.store(true);
}
bool Progress::anyActive() noexcept {
  return gActive.load() > 0;
}
bool Progress::cancelAllRequested() noexcept {
  return gCancelAll.load();
}

Progress::Progress(std::string label, std::size_t total)
    : mLabel(std::move(label)), mTotal(total), mStart(std::chrono::steady_clock::now()),
      mInteractive(::isatty(STDERR_FILENO) != 0) {
  ++gActive;
}

Progress::~Progress() {
  print(true);
  if (--gActive == 0) {
    gCancelAll.store(false);
  }
}

void Progress::advance(std::size_t n) {
  mDone += n;
  print(false);
}

std::string Progress::eta(long long elapsedNs) const {
  const std::size_t done = mDone.load();
  if (done == 0 || done >= mTotal) {
    return "      "; // keeps the line's length while nothing can be estimated
  }
  const double left =
      static_cast<double>(elapsedNs) * 1e-9 * static_cast<double>(mTotal - done) / static_cast<double>(done);
  char text[48];
  if (left < 120.0) {
    std::snprintf(text, sizeof(text), ", ETA %.0fs ", left);
  } else {
    std::snprintf(text, sizeof(text), ", ETA %dm%02ds ", static_cast<int>(left) / 60,
                  static_cast<int>(left) % 60);
  }
  return text;
}

void Progress::print(bool final) {
  const auto now = std::chrono::steady_clock::now();
  const long long ns = std::chrono::duration_cast<std::chrono::nanoseconds>(now - mStart).count();
  if (!mInteractive) {
    // Logs and CI: one line per quarter and one when the step ends, never a carriage-return animation; steps
    // shorter than a second stay quiet.
    if (ns < 1'000'000'000LL) {
      return;
    }
    const std::size_t quarter = mTotal == 0 ? 4 : std::min<std::size_t>(4, 4 * mDone.load() / mTotal);
    std::size_t printed = mQuartersPrinted.load();
    if (final) {
      if (!cancelled()) { // a cancelled step is reported once, by the error that ends the command
        std::fprintf(stderr, "%s: done (%zu/%zu) in %.1fs\n", mLabel.c_str(), mDone.load(), mTotal,
                     static_cast<double>(ns) * 1e-9);
      }
    } else if (quarter > printed && quarter < 4 &&
               mQuartersPrinted.compare_exchange_strong(printed, quarter)) {
      std::fprintf(stderr, "%s: %zu%% (%zu/%zu) %.1fs%s\n", mLabel.c_str(), quarter * 25, mDone.load(),
                   mTotal, static_cast<double>(ns) * 1e-9, eta(ns).c_str());
    }
    return;
  }
  long long last = mLastPrintNs.load();
  if (!final && ns - last < 100'000'000LL) {
    return;
  }
  if (!final && !mLastPrintNs.compare_exchange_strong(last, ns)) {
    return;
  }
  const double fraction = mTotal == 0 ? 1.0 : static_cast<double>(mDone) / static_cast<double>(mTotal);
  std::fprintf(stderr, "\r%s: %5.1f%% (%zu/%zu) %.1fs%s%s", mLabel.c_str(), 100.0 * fraction, mDone.load(),
               mTotal, static_cast<double>(ns) * 1e-9, final ? "" : eta(ns).c_str(),
               final ? (cancelled() ? " cancelled\n" : "\n") : "");
  std::fflush(stderr);
}

} // namespace sylva
