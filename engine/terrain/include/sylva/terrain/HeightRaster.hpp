#pragma once

#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/HeightSources.hpp>

#include <filesystem>
#include <memory>

namespace sylva::terrain {

/** Largest side of a raster read window by window (HeightRaster): 2^21 samples. */
inline constexpr int kMaxRasterSide = 1 << 21;

/**
 * Heights read window by window: the source of a tile pyramid (TilePyramid.hpp), for DEMs larger than the
 * memory a process may use. GDAL rasters (GeoTIFF, …) are read on demand and never held whole; the other
 * formats (PNG, EXR, NumPy) are loaded whole through loadHeightField, whose size limits they keep.
 *
 * Samples follow HeightField's conventions exactly — column i from the west, row j from the north, metres,
 * NaN absent — and the same LoadOptions apply (scale/offset, elevation units, nodata masks, geotransform
 * orientation, --spacing, --geographic, --flip-y), so a window equals the same samples of loadHeightField's
 * field (tested). Thread-safe: read() may be called from several threads at once (GDAL rasters keep a small
 * pool of open datasets, one per concurrent reader).
 */
class HeightRaster {
public:
  /**
   * Opens `path` and checks what can be checked without reading samples (the header, the block layout,
   * missing blocks without nodata, options), throwing sylva::Error `<file>: <reason>` as loadHeightField
   * does. Sides up to kMaxRasterSide; LoadOptions::maxSamples and maxSide apply only to formats loaded whole.
   * Unlike loadHeightField, a raster whose samples are all absent is only found when they are read.
   */
  static std::shared_ptr<const HeightRaster>
  open(const std::filesystem::path& path, const LoadOptions& options = {}, LoadReport* report = nullptr);
  /** A raster over a field in memory (procedural heights, tests). */
  static std::shared_ptr<const HeightRaster> fromField(HeightField field);

  virtual ~HeightRaster() = default;
  HeightRaster(const HeightRaster&) = delete;
  HeightRaster& operator=(const HeightRaster&) = delete;

  int width() const { return mWidth; }         ///< samples along x (columns)
  int height() const { return mHeight; }       ///< samples along z (rows)
  float spacingX() const { return mSpacingX; } ///< metres between columns
  float spacingZ() const { return mSpacingZ; } ///< metres between rows

  /**
   * Reads samples i ∈ [i0, i0 + w), j ∈ [j0, j0 + h) into `out` (row-major, w·h floats, metres, NaN absent).
   * The window must lie inside the raster (throws otherwise); a failed read throws `<file>: …`.
   */
  virtual void read(int i0, int j0, int w, int h, float* out) const = 0;

  /**
   * Tells the raster that windows of `rows` rows will now sweep it row band by row band, west to east, so
   * that it can size its caches for one band (GDAL rasters: the block cache, process-wide, to about two
   * bands of blocks within 16..256 MiB). Memory stays bounded without it; reads get slower or larger.
   */
  virtual void prepareSweep(int rows) const { (void)rows; }

protected:
  /** A raster of width × height samples at spacingX × spacingZ metres (for the implementations). */
  HeightRaster(int width, int height, float spacingX, float spacingZ)
      : mWidth(width), mHeight(height), mSpacingX(spacingX), mSpacingZ(spacingZ) {}
  /** Throws unless the window lies inside the raster and is not empty. */
  void checkWindow(int i0, int j0, int w, int h) const;

private:
  int mWidth;
  int mHeight;
  float mSpacingX;
  float mSpacingZ;
};

} // namespace sylva::terrain
