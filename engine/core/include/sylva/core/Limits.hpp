#pragma once

#include <cstdint>

namespace sylva {

/**
 * Most that zlib's deflate can expand data by (about 1032:1: a 258-byte match coded in 2 bits). Loaders use
 * it to refuse a header that claims more decoded bytes than its compressed bytes can hold, before allocating
 * anything.
 */
inline constexpr std::uint64_t kMaxDeflateRatio = 1032;

} // namespace sylva
