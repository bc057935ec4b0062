#pragma once

#include <sylva/terrain/HeightField.hpp>

#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace sylva::terrain {

/**
 * Height sources: which files become a HeightField, and how.
 *
 * - `.png`, 8/16-bit grey (libpng via sylva::loadImage): normalised value v ∈ [0, 1] × heightScale
 *   metres (the paper's h·N), or minHeight + v·(maxHeight − minHeight) when a `<file>.json` sidecar
 *   exists; spacing from the sidecar, else 1 m.
 * - `.exr`, float (OpenEXR): metres as stored; spacing from the sidecar, else 1 m.
 * - `.npy`: metres as stored; int8/16/32/64, uint8/16/32/64, float32/64 in either byte order, C or
 *   Fortran order, 2D only (rows = z, columns = x); spacing 1 m.
 * - `.npz` (zip of `.npy`, via libzip): the member chosen by LoadOptions::npzArray. Spacing and orientation
 *   from 1D coordinate arrays when present (`lon`/`lat`, `longitude`/`latitude` or `x`/`y`, one value per
 *   column/row; rows whose latitude or y rises are flipped so that row 0 is north, falling longitude or x
 *   flips columns), else from the scalar members `dx`, `dy` (degrees when `xmin`, `xmax`, `ymin`, `ymax`
 *   describe a lon/lat box of that size), else 1 m.
 * - anything else, through GDAL (GeoTIFF, netCDF, ...): band 1 × scale + offset, metres (a band unit
 *   of feet is converted); masked/nodata samples absent; spacing = |pixel size| from the geotransform in the
 *   units of HorizontalUnits (CRS, netCDF/CF axis attributes). No geotransform: 1 m. A truncated classic
 *   netCDF file (whose library reads missing data as zeros) and any read GDAL flags as failed are errors.
 *
 * In every case LoadOptions::spacing, when non-zero, overrides the spacing on both axes (in metres), and
 * LoadOptions::flipY then reverses the rows.
 *
 * Conventions (all formats): sample (i, j) is column i from the west and row j from the north; row 0 is the
 * first row of the file for PNG/EXR/`.npy`, and the northern row for GDAL rasters (south-up rasters are
 * flipped) and `.npz` archives with coordinate arrays. Non-finite samples (NaN, ±inf) and values beyond the
 * float range become absent (NaN); absent samples are never height 0.
 *
 * PNG/EXR channels: 1 channel = heights; 2 channels = heights + alpha, where alpha 0 marks an absent sample;
 * RGB/RGBA images are rejected (a colour image is almost always the wrong file).
 *
 * Errors: every failure throws sylva::Error with one line `<file>: <reason>` — missing file, truncated or
 * corrupt data, unsupported dtype/bit depth/channels, not 2D, smaller than 2×2, more than kMaxHeightFieldSide
 * samples per side or kMaxHeightFieldSamples in all, no valid sample, invalid options (non-finite or ≤ 0
 * heightScale, negative or non-finite spacing), invalid sidecar (naming the field).
 *
 * Thread-safety: the functions here may be called concurrently (GDAL error handlers are per thread).
 */

/** Largest accepted side of a height field, samples. */
inline constexpr int kMaxHeightFieldSide = 65536;
/** Largest accepted number of samples in one height field (4 GiB of floats). */
inline constexpr std::size_t kMaxHeightFieldSamples = std::size_t{1} << 30;

/**
 * How the horizontal coordinates a file carries (geotransform, coordinate arrays, `dx`/`dy`) are read.
 * Degrees become metres with one spacing per axis taken at the centre latitude φ: 1° of latitude = 111320 m,
 * 1° of longitude = 111320 · cos φ m. East-west distances are then off by cos φ_row / cos φ − 1 on other rows
 * (LoadReport::eastWestError gives the worst row); reproject (e.g. `gdalwarp -t_srs EPSG:32633`) for wide
 * latitude ranges.
 */
enum class HorizontalUnits {
  /**
   * From the file: a CRS (geographic: degrees; projected: its linear unit), else netCDF/CF axis attributes
   * (`units` degrees_east/degrees_north or `standard_name` longitude/latitude), else NumPy coordinate array
   * names (`lon`/`lat`, `longitude`/`latitude`: degrees; `x`/`y`: metres), else metres with a warning.
   */
  Auto,
  Metres,  ///< the file's coordinates are metres, whatever it says.
  Degrees, ///< the file's coordinates are longitude/latitude degrees (`--geographic`).
};

/** Options for loadHeightField. Validated on every call, whatever the format. */
struct LoadOptions {
  /**
   * Metres represented by the normalised value 1.0 of a PNG without sidecar (the paper's N; a value v ∈ [0,
   * 1] becomes v · heightScale metres). Must be finite and > 0. Ignored by the other formats.
   */
  float heightScale = 100.0f;
  /** Metres between neighbouring samples on both axes; 0 = from the file (or 1 m if the file has none). */
  float spacing = 0.0f;
  /** Name of the array inside an `.npz` (member `<name>.npy`); empty = the first 2D array in archive order.
   */
  std::string npzArray;
  /** How the file's horizontal coordinates are read. */
  HorizontalUnits horizontal = HorizontalUnits::Auto;
  /**
   * Reverses the row order after the file's own orientation has been applied: for files whose coordinates
   * are missing or wrong about which row is north (`--flip-y`).
   */
  bool flipY = false;
  /**
   * Largest field accepted, in samples (4..kMaxHeightFieldSamples), checked before anything is allocated: a
   * memory guard for services and fuzzing, where a small file may legitimately claim a huge sparse raster.
   */
  std::size_t maxSamples = kMaxHeightFieldSamples;
  /**
   * Largest accepted side, samples, also checked before anything is allocated: e.g. the GPU's largest
   * texture for a renderer. `maxSideReason` says why, in the error message.
   */
  int maxSide = kMaxHeightFieldSide;
  /** Why maxSide is what it is, for the error (e.g. "the GPU's largest texture"); empty: the default limit.
   */
  std::string maxSideReason;
};

/**
 * What loadHeightField assumed about a file's coordinates: for `sylva terrain info`, and so that no guess is
 * silent. Every warning is also logged (log::warn) as it is made.
 */
struct LoadReport {
  /** Horizontal units read from the file: "metres", "degrees", or "none" (no coordinates: 1 m per sample). */
  std::string units = "none";
  /** Why, in words: "CRS 'WGS 84' is geographic", "netCDF/CF axes lon (degrees_east), lat ...", ... */
  std::string reason = "the file holds no coordinates";
  /** Degrees only: the latitude at which degrees became metres, and the rows' latitude range; NaN if unknown.
   */
  double centreLatitude = std::numeric_limits<double>::quiet_NaN();
  double southLatitude =
      std::numeric_limits<double>::quiet_NaN(); ///< degrees: the southernmost row's latitude
  double northLatitude =
      std::numeric_limits<double>::quiet_NaN(); ///< degrees: the northernmost row's latitude
  /** Degrees only: largest relative error of east-west distances over the rows (0.04 = 4 %). */
  double eastWestError = 0.0;
  /** How rows map to north: "row 0 is north (file order)", "flipped: latitude rises with the row", ... */
  std::string orientation = "row 0 is north (file order)";
  /** Everything the loader guessed or ignored, one line each (also logged as warnings). */
  std::vector<std::string> warnings;
};

/** Summary of a height field's valid samples. */
struct HeightFieldInfo {
  /** Smallest valid height, metres; NaN when there is no valid sample. */
  float minHeight = 0.0f;
  /** Largest valid height, metres; NaN when there is no valid sample. */
  float maxHeight = 0.0f;
  /** Number of valid (non-NaN) samples. */
  std::size_t validCount = 0;
  /** Number of absent (NaN) samples. */
  std::size_t absentCount = 0;
};

/** Min/max/counts over the valid samples of `field`. O(width·height). */
HeightFieldInfo heightFieldInfo(const HeightField& field);

/**
 * Loads heights in metres from `path`, choosing the reader by extension (case-insensitive; see the table
 * above). Throws sylva::Error `<file>: <reason>` on any failure; never returns a field without a valid
 * sample.
 */
HeightField loadHeightField(const std::filesystem::path& path, const LoadOptions& options = {},
                            LoadReport* report = nullptr);

/**
 * Saves `field` by extension, atomically (temporary file + rename):
 * - `.png`: 16-bit grey, value = round((h − min) / (max − min) · 65535) (0 when max = min); if any sample is
 *   absent, 16-bit grey+alpha with alpha 0 on absent samples. Needs the sidecar to recover metres.
 * - `.exr`: one float channel, metres; absent samples stay NaN.
 * - `.npy`: little-endian float32, C order, shape (height, width); absent samples NaN.
 * - `.tif`/`.tiff`: GeoTIFF (GDAL), float32, nodata NaN, geotransform (0, spacingX, 0, 0, 0, −spacingZ), no
 * CRS. For `.png` and `.exr` a JSON sidecar `<file>.json` (e.g. `h.png.json`) records
 * `{"version": 1, "format": "sylva-heightfield", "minHeight", "maxHeight", "spacingX", "spacingZ"}` (metres),
 * which loadHeightField reads back. Throws sylva::Error for an empty field, a field without valid samples, or
 * an unsupported extension.
 */
void saveHeightField(const std::filesystem::path& path, const HeightField& field);

} // namespace sylva::terrain
