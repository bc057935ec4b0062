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

  int width() const { return mWidth; }
  int height() const { return mHeight; }
  float spacingX() const { return mSpacingX; }
  float spacingZ() const { return mSpacingZ; }
  void setSpacing(float x, float z) {
    mSpacingX = x;
    mSpacingZ = z;
  }
  /** World extent covered by the samples, metres: (width - 1) · spacingX. */
  float extentX() const { return static_cast<float>(mWidth - 1) * mSpacingX; }
  float extentZ() const { return static_cast<float>(mHeight - 1) * mSpacingZ; }

  float at(int i, int j) const { return mHeights[index(i, j)]; }
  float& at(int i, int j) { return mHeights[index(i, j)]; }
  bool valid(int i, int j) const { return !std::isnan(at(i, j)); }

  const std::vector<float>& samples() const { return mHeights; }
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
