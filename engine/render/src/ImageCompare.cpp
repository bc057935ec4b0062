#include <sylva/render/ImageCompare.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

namespace {

/** Channel c of (x, y) in 8-bit steps; absent channels read as 255 for alpha and 0 otherwise. */
float channel8(const Image& image, int x, int y, int c) {
  if (c < image.channels()) {
    return image.get(x, y, c) * 255.0f;
  }
  if (image.channels() == 1 && c < 3) {
    return image.get(x, y, 0) * 255.0f; // grey expands to RGB
  }
  return c == 3 ? 255.0f : 0.0f;
}

} // namespace

CompareResult compareImages(const Image& actual, const Image& reference, const Tolerance& tolerance,
                            const Image* mask) {
  CompareResult result;
  if (actual.width() != reference.width() || actual.height() != reference.height()) {
    result.sizeMatches = false;
    result.passed = false;
    return result;
  }
  if (mask != nullptr && (mask->width() != actual.width() || mask->height() != actual.height())) {
    fail("image compare: mask is {}x{}, images are {}x{}", mask->width(), mask->height(), actual.width(),
         actual.height());
  }
  const int channels = std::max(actual.channels(), reference.channels());
  result.diff = Image(actual.width(), actual.height(), 3, PixelType::U8);
  double sum = 0.0;
  std::size_t summed = 0;
  for (int y = 0; y < actual.height(); ++y) {
    for (int x = 0; x < actual.width(); ++x) {
      float grey = 0.0f;
      for (int c = 0; c < std::min(3, reference.channels() == 1 ? 3 : reference.channels()); ++c) {
        grey += channel8(reference, x, y, c) / 3.0f;
      }
      grey = grey / 255.0f * 0.35f;
      if (mask != nullptr && mask->get(x, y, 0) == 0.0f) {
        for (int c = 0; c < 3; ++c) {
          result.diff.set(x, y, c, grey * 0.4f);
        }
        continue;
      }
      int pixelMax = 0;
      for (int c = 0; c < channels; ++c) {
        const float d = std::abs(channel8(actual, x, y, c) - channel8(reference, x, y, c));
        const int rounded = static_cast<int>(std::lround(d));
        pixelMax = std::max(pixelMax, rounded);
        sum += d;
        ++summed;
      }
      ++result.comparedPixels;
      result.maxChannelDiff = std::max(result.maxChannelDiff, pixelMax);
      const bool failing = pixelMax > tolerance.maxChannelDiff;
      if (failing) {
        ++result.failingPixels;
      }
      const float strength = 0.4f + 0.6f * static_cast<float>(pixelMax) / 255.0f;
      result.diff.set(x, y, 0, failing ? strength : grey);
      result.diff.set(x, y, 1, grey);
      result.diff.set(x, y, 2, !failing && pixelMax > 0 ? strength : grey);
    }
  }
  result.meanChannelDiff = summed == 0 ? 0.0 : sum / static_cast<double>(summed);
  result.passed = result.failingFraction() <= tolerance.maxFailingFraction;
  return result;
}

nlohmann::json CompareResult::toJson(const Tolerance& tolerance) const {
  return {{"passed", passed},
          {"size_matches", sizeMatches},
          {"max_channel_diff", maxChannelDiff},
          {"mean_channel_diff", meanChannelDiff},
          {"compared_pixels", comparedPixels},
          {"failing_pixels", failingPixels},
          {"failing_fraction", failingFraction()},
          {"tolerance",
           {{"max_channel_diff", tolerance.maxChannelDiff},
            {"max_failing_fraction", tolerance.maxFailingFraction}}}};
}

} // namespace sylva::render
