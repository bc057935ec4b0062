#include <sylva/core/Parallel.hpp>

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace sylva {

unsigned workerCount() {
  if (const char* env = std::getenv("SYLVA_THREADS")) {
    const int n = std::atoi(env);
    if (n > 0) {
      return static_cast<unsigned>(n);
    }
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

void parallelFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body,
                 std::size_t minChunk) {
  if (count == 0) {
    return;
  }
  const std::size_t workers = std::min<std::size_t>(
      workerCount(), (count + std::max<std::size_t>(minChunk, 1) - 1) / std::max<std::size_t>(minChunk, 1));
  if (workers <= 1) {
    body(0, count);
    return;
  }
  const std::size_t chunk = (count + workers - 1) / workers;
  std::exception_ptr firstError;
  std::mutex errorMutex;
  std::vector<std::thread> threads;
  threads.reserve(workers - 1);
  auto run = [&](std::size_t begin) {
    try {
      body(begin, std::min(count, begin + chunk));
    } catch (...) {
      const std::lock_guard lock(errorMutex);
      if (!firstError) {
        firstError = std::current_exception();
      }
    }
  };
  for (std::size_t w = 1; w < workers; ++w) {
    if (w * chunk < count) {
      threads.emplace_back(run, w * chunk);
    }
  }
  run(0);
  for (std::thread& t : threads) {
    t.join();
  }
  if (firstError) {
    std::rethrow_exception(firstError);
  }
}

} // namespace sylva
