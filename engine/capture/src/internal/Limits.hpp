#pragma once
// Size limits of the depth images the capture module reads (16-bit PNGs, Middlebury maps, fakenect frames):
// larger headers are refused before any allocation.

#include <cstdint>

namespace sylva::capture::internal {

/** Largest width or height, pixels. */
inline constexpr int kMaxSide = 65536;
/** Most pixels of one image (256 Mi). */
inline constexpr std::int64_t kMaxPixels = std::int64_t{1} << 28;

} // namespace sylva::capture::internal
