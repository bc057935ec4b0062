#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <string>

namespace sylva {

/**
 * Progress of long work (preprocessing, synthesis, batch renders). Prints a single updating line to stderr
 * when it is a terminal (at most 10 times a second, with the time left estimated from the rate so far);
 * otherwise (logs, CI) a line at 25, 50 and 75 % and one when the step ends, for steps that run longer than a
 * second. cancel() may be called from another thread (e.g. a SIGINT handler); the worker checks cancelled()
 * and stops.
 */
class Progress {
public:
  /** A step named `label` (e.g. "synthesis") of `total` units; shows nothing until work takes a second. */
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /** Adds `n` completed units. Thread-safe. */
  void advance(std::size_t n = 1);
  /** Requests cancellation. Thread-safe. */
  void cancel() { mCancelled = true; }
  /** True after cancel() or cancelAll(). */
  bool cancelled() const { return mCancelled || cancelAllRequested(); }

  /**
   * Cancels every live Progress; async-signal-safe (one lock-free store), for a SIGINT handler. The request
   * is forgotten when the last live Progress is destroyed.
   */
  static void cancelAll() noexcept;
  /** True while at least one Progress exists (long work is running); async-signal-safe. */
  static bool anyActive() noexcept;
  /** Units completed so far. */
  std::size_t done() const { return mDone; }

private:
  static bool cancelAllRequested() noexcept;
  void print(bool final);
  /** ", ETA 12s" from the rate so far (blank before the first unit and after the last). */
  std::string eta(long long elapsedNs) const;

  std::string mLabel;
  std::size_t mTotal;
  std::atomic<std::size_t> mDone{0};
  std::atomic<bool> mCancelled{false};
  std::atomic<long long> mLastPrintNs{0};
  std::atomic<std::size_t> mQuartersPrinted{0};
  std::chrono::steady_clock::time_point mStart;
  bool mInteractive;
};

} // namespace sylva
