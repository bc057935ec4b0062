#pragma once

#include <sylva/core/Image.hpp>

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace sylva::render {

/**
 * Tolerance of an image comparison. A pixel fails when any channel differs by more than `maxChannelDiff`
 * (in 8-bit steps, 0..255, whatever the image type); the comparison fails when the fraction of failing pixels
 * among compared pixels exceeds `maxFailingFraction`.
 */
struct Tolerance {
  int maxChannelDiff = 0;          ///< 8-bit steps a channel may differ by
  double maxFailingFraction = 0.0; ///< share of pixels (0..1) that may fail
};

/** Outcome of comparing an actual image with a reference. */
struct CompareResult {
  bool sizeMatches = true;        ///< false: the sizes differ and nothing was compared
  bool passed = false;            ///< within the tolerance
  int maxChannelDiff = 0;         ///< largest difference seen, 8-bit steps
  double meanChannelDiff = 0;     ///< mean absolute difference over compared channels, 8-bit steps
  std::size_t comparedPixels = 0; ///< pixels compared
  std::size_t failingPixels = 0;  ///< of those, over maxChannelDiff
  /** failingPixels / comparedPixels (0 with nothing compared). */
  double failingFraction() const {
    return comparedPixels == 0 ? 0.0
                               : static_cast<double>(failingPixels) / static_cast<double>(comparedPixels);
  }
  /** Visual diff: grey reference with failing pixels red (intensity ∝ difference), passing differences blue.
   */
  Image diff;
  /** The figures above and `tolerance`, for golden-test reports. */
  nlohmann::json toJson(const Tolerance& tolerance) const;
};

/**
 * Compares `actual` with `reference` (same size; channel counts may differ: missing channels compare as
 * opaque/zero). `mask`, if given, is a 1-channel image of the same size: pixels where it is 0 are ignored.
 */
CompareResult compareImages(const Image& actual, const Image& reference, const Tolerance& tolerance,
                            const Image* mask = nullptr);

} // namespace sylva::render
