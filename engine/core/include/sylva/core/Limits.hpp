#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

namespace sylva {

/**
 * Most that zlib's deflate can expand data by (about 1032:1: a 258-byte match coded in 2 bits). Loaders use
 * it to refuse a header that claims more decoded bytes than its compressed bytes can hold, before allocating
 * anything.
 */
inline constexpr std::uint64_t kMaxDeflateRatio = 1032;

/**
 * Memory the system can give this process now without swapping (bytes): MemAvailable from /proc/meminfo;
 * nullopt where that is unknown (not Linux). Commands check big allocations against it before any work, so an
 * absurd size is a one-line error instead of an out-of-memory kill.
 */
std::optional<std::size_t> availableMemoryBytes();

} // namespace sylva
