#pragma once

#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/HeightSources.hpp>

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>

namespace sylva::terrain::detail {

/** Throws `<file>: ...` unless width × height is within 2..kMaxHeightFieldSide per side and `maxSamples`
 * (LoadOptions::maxSamples) in all. */
void checkHeightFieldSize(const std::filesystem::path& path, long long width, long long height,
                          std::size_t maxSamples = kMaxHeightFieldSamples);

/**
 * Common last step of every loader: applies LoadOptions::spacing, turns non-finite samples into NaN, checks
 * the spacing is finite and > 0 and that at least one sample is valid.
 */
void finishHeightField(const std::filesystem::path& path, HeightField& field, const LoadOptions& options);

/** `.npy` reader (Npy.cpp). */
HeightField loadNpy(const std::filesystem::path& path, const LoadOptions& options);
/** `.npz` reader through libzip (Npy.cpp). */
HeightField loadNpz(const std::filesystem::path& path, const LoadOptions& options);
/** `.npy` writer: little-endian float32, C order (Npy.cpp). */
void saveNpy(const std::filesystem::path& path, const HeightField& field);

/** Metres per degree of latitude (and of longitude at the equator) used for geographic rasters. */
inline constexpr double kMetresPerDegree = 111320.0;

/** A sample value as float metres: NaN if it is not finite or outside the float range. */
inline float toHeight(double value) {
  constexpr double kLimit = 3.4028234663852886e38; // FLT_MAX
  return value >= -kLimit && value <= kLimit ? static_cast<float>(value)
                                             : std::numeric_limits<float>::quiet_NaN();
}

} // namespace sylva::terrain::detail
