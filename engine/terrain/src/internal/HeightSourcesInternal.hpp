#pragma once

#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/HeightSources.hpp>

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>

namespace sylva::terrain::detail {

/** Throws `<file>: ...` unless width × height is within 2..kMaxHeightFieldSide (and LoadOptions::maxSide) per
 * side and LoadOptions::maxSamples in all. */
void checkHeightFieldSize(const std::filesystem::path& path, long long width, long long height,
                          const LoadOptions& limits = {});

/**
 * Common last step of every loader: applies LoadOptions::spacing and flipY, turns non-finite samples into
 * NaN, checks the spacing is finite and > 0 and that at least one sample is valid.
 */
void finishHeightField(const std::filesystem::path& path, HeightField& field, const LoadOptions& options,
                       LoadReport& report);

/** The horizontal coordinates a file carries, in its own units, before HorizontalUnits is applied. */
struct FileCoordinates {
  enum class Kind {
    None,    ///< no coordinates: 1 m per sample
    Metres,  ///< known to be metres (a projected CRS, already converted)
    Unknown, ///< a step without units (taken as metres, with a warning)
    Degrees, ///< longitude/latitude degrees
  };
  Kind kind = Kind::None;
  /** Units per sample along columns (x, east) and rows (z, south); > 0. */
  double stepX = 1.0;
  double stepZ = 1.0;
  /** Latitudes of the southern and northern rows, when the coordinates could be degrees; NaN if unknown. */
  double south = std::numeric_limits<double>::quiet_NaN();
  double north = std::numeric_limits<double>::quiet_NaN();
  /** Why this kind, for LoadReport::reason. */
  std::string reason;
  /** For Unknown: whether the numbers look like longitude/latitude (sharpens the warning). */
  bool looksLikeDegrees = false;
};

/**
 * Sets `field`'s spacing in metres from `coordinates` and LoadOptions::horizontal, and fills `report` (units,
 * reason, latitudes, east-west error, warnings). Throws for --geographic on a file without coordinates.
 */
void applyCoordinates(const std::filesystem::path& path, HeightField& field,
                      const FileCoordinates& coordinates, const LoadOptions& options, LoadReport& report);

/** Appends a warning to `report` and logs it as `<file>: <text>`. */
void warn(const std::filesystem::path& path, LoadReport& report, const std::string& text);

/** Reverses the order of rows (north ↔ south) or columns (east ↔ west). */
void flipRows(HeightField& field);
void flipColumns(HeightField& field);

/**
 * Classic netCDF (CDF-1/2/5): throws `<file>: truncated netCDF file ...` when the file is shorter than its
 * header's variables need, or the header itself is cut or corrupt. Other files are left alone.
 */
void checkNetCdfClassicSize(const std::filesystem::path& path);

/** `.npy` reader (Npy.cpp). */
HeightField loadNpy(const std::filesystem::path& path, const LoadOptions& options, LoadReport& report);
/** `.npz` reader through libzip (Npy.cpp). */
HeightField loadNpz(const std::filesystem::path& path, const LoadOptions& options, LoadReport& report);
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
