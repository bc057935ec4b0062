#pragma once

#include <cstddef>
#include <functional>

namespace sylva {

/** Number of worker threads parallelFor uses (hardware concurrency, or SYLVA_THREADS if set; at least 1). */
unsigned workerCount();

/**
 * Calls body(begin, end) over disjoint chunks covering [0, count), on up to workerCount() threads, and
 * returns when all are done. The first exception thrown by a chunk is rethrown on the caller's thread.
 * Results must not depend on chunking (write to disjoint outputs) so they stay deterministic.
 */
void parallelFor(std::size_t count, const std::function<void(std::size_t begin, std::size_t end)>& body,
                 std::size_t minChunk = 64);

} // namespace sylva
