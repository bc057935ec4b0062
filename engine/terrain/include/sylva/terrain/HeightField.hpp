#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace sylva::terrain {

/**
 * Heights in metres on a regular grid of samples. Sample (i, j) — column i from the west, row j from the
 * north (file order) — sits at world position x = i · spacingX, z = j · spacingZ (metres, y up). NaN marks an
 * absent sample (nodata, outside the raster): it is never treated as height 0. Value type; not thread-safe
 * for writes.
 */
class HeightField {
public:
  HeightField() = default;
  /** A field of `width`×`height` samples, all `fill` metres; spacing in metres per sample. */
  HeightField(int width, int height, float spacingX = 1.0f, float spacingZ = 1.0f, float fill = 0.0f)
      : mWidth(width), mHeight(height), mSpacingX(spacingX), mSpacingZ(spacingZ),
        mHeights(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill) {}

  int width() const { return mWidth; }         ///< samples along x (columns)
  int height() const { return mHeight; }       ///< samples along z (rows)
  float spacingX() const { return mSpacingX; } ///< metres between columns
  float spacingZ() const { return mSpacingZ; } ///< metres between rows
  /** Sets the metres between columns (x) and rows (z). */
  void setSpacing(float x, float z) {
    mSpacingX = x;
    mSpacingZ = z;
  }
  /** World extent covered by the samples, metres: (width - 1) · spacingX. */
  float extentX() const { return static_cast<float>(mWidth - 1) * mSpacingX; }
  /** World extent along z, metres: (height - 1) · spacingZ. */
  float extentZ() const { return static_cast<float>(mHeight - 1) * mSpacingZ; }

  /** Height of sample (i, j), metres (NaN: absent); no bounds checks. */
  float at(int i, int j) const { return mHeights[index(i, j)]; }
  /** Height of sample (i, j), metres, for writing; no bounds checks. */
  float& at(int i, int j) { return mHeights[index(i, j)]; }
  /** Whether sample (i, j) is present (not NaN). */
  bool valid(int i, int j) const { return !std::isnan(at(i, j)); }

  /** All heights, row-major (row j = z index), width × height values. */
  const std::vector<float>& samples() const { return mHeights; }
  /** All heights, row-major, for writing. */
  std::vector<float>& samples() { return mHeights; }

private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(mWidth) + static_cast<std::size_t>(i);
  }

  int mWidth = 0;
  int mHeight = 0;
  float mSpacingX = 1.0f;
  float mSpacingZ = 1.0f;
  std::vector<float> mHeights;
};

} // namespace sylva::terrain
