#pragma once

#include <sylva/terrain/HeightField.hpp>

#include <cstddef>
#include <filesystem>
#include <string>

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
 * - `.npz` (zip of `.npy`, via libzip): the member chosen by LoadOptions::npzArray; spacing from the
 *   scalar members `dx`, `dy` when present (see NpzSpacing), else 1 m.
 * - anything else, through GDAL (GeoTIFF, netCDF, ...): band 1 × scale + offset, metres (a band unit
 *   of feet is converted); masked/nodata samples absent; spacing = |pixel size| from the geotransform,
 *   projected units converted to metres, geographic degrees converted at the centre latitude φ:
 *   1° of latitude = 111320 m, 1° of longitude = 111320 · cos φ m. No geotransform: 1 m.
 *
 * In every case LoadOptions::spacing, when non-zero, overrides the spacing on both axes.
 *
 * Conventions (all formats): sample (i, j) is column i from the west and row j from the north; row 0 is the
 * first row of the file for PNG/EXR/NumPy, and the northern row for GDAL rasters (south-up rasters are
 * flipped). Non-finite samples (NaN, ±inf) and values beyond the float range become absent (NaN); absent
 * samples are never height 0.
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

/** How the scalar `dx`/`dy` members of an `.npz` archive are read (e.g. matplotlib's Jacksboro DEM). */
enum class NpzSpacing {
  /**
   * Degrees when the archive also holds `xmin`, `xmax`, `ymin`, `ymax` that look like longitude/latitude
   * (|x| ≤ 180, |y| ≤ 90) and span width·dx and height·dy (±1 sample); metres otherwise.
   */
  Auto,
  Metres,  ///< `dx`, `dy` are metres per sample.
  Degrees, ///< `dx`, `dy` are degrees; converted with the latitude at the centre of ymin..ymax (0 if absent).
  Ignore,  ///< do not read `dx`/`dy`; spacing is 1 m unless LoadOptions::spacing is set.
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
  /** How `.npz` spacing members are interpreted. */
  NpzSpacing npzSpacing = NpzSpacing::Auto;
  /**
   * Largest field accepted, in samples (4..kMaxHeightFieldSamples), checked before anything is allocated: a
   * memory guard for services and fuzzing, where a small file may legitimately claim a huge sparse raster.
   */
  std::size_t maxSamples = kMaxHeightFieldSamples;
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
HeightField loadHeightField(const std::filesystem::path& path, const LoadOptions& options = {});

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
