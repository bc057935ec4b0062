// The GIF writer against its source frames, read back through giflib: error diffusion keeps smooth tones'
// local mean (skin, sky) where nearest-colour mapping posterises them into bands, still parts of an animation
// keep their pixels, and the file is deterministic.
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/media/Export.hpp>

#include "TempDir.hpp"

#include <gif_lib.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace sylva::media {
namespace {

constexpr int kW = 192;
constexpr int kH = 96;

/** A smooth skin-to-shadow gradient in two directions with a mid-grey square at (x, 24): wider than a
 * 256-colour palette can hold without steps. */
Image skinFrame(int squareX) {
  Image image(kW, kH, 4, PixelType::U8);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const float u = static_cast<float>(x) / (kW - 1);
      const float v = static_cast<float>(y) / (kH - 1);
      const bool square = x >= squareX && x < squareX + 12 && y >= 24 && y < 36;
      image.set(x, y, 0, square ? 0.5f : 0.35f + 0.55f * u);
      image.set(x, y, 1, square ? 0.5f : 0.22f + 0.40f * u * (1.0f - 0.3f * v));
      image.set(x, y, 2, square ? 0.5f : 0.18f + 0.30f * v);
      image.set(x, y, 3, 1.0f);
    }
  }
  return image;
}

/** The frames of a GIF as RGB8 (frames drawn over the previous one, as the writer's "do not dispose"). */
std::vector<std::vector<std::uint8_t>> readFrames(const std::filesystem::path& path) {
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  EXPECT_NE(gif, nullptr);
  std::vector<std::vector<std::uint8_t>> frames;
  if (gif == nullptr || DGifSlurp(gif) != GIF_OK) {
    return frames;
  }
  std::vector<std::uint8_t> canvas(static_cast<std::size_t>(gif->SWidth) * gif->SHeight * 3, 0);
  for (int f = 0; f < gif->ImageCount; ++f) {
    const SavedImage& image = gif->SavedImages[f];
    const ColorMapObject* map = image.ImageDesc.ColorMap ? image.ImageDesc.ColorMap : gif->SColorMap;
    for (int y = 0; y < image.ImageDesc.Height; ++y) {
      for (int x = 0; x < image.ImageDesc.Width; ++x) {
        const GifColorType& c = map->Colors[image.RasterBits[y * image.ImageDesc.Width + x]];
        const std::size_t i =
            3 * (static_cast<std::size_t>(y + image.ImageDesc.Top) * gif->SWidth + x + image.ImageDesc.Left);
        canvas[i] = c.Red;
        canvas[i + 1] = c.Green;
        canvas[i + 2] = c.Blue;
      }
    }
    frames.push_back(canvas);
  }
  DGifCloseFile(gif, &error);
  return frames;
}

/** The largest difference of 8×8 block means between a decoded frame and its source, levels of 255: what
 * the eye sees of smooth tones (dithering trades per-pixel error for the right local mean). */
double worstBlockMeanError(const std::vector<std::uint8_t>& decoded, const Image& source) {
  double worst = 0.0;
  for (int by = 0; by + 8 <= kH; by += 8) {
    for (int bx = 0; bx + 8 <= kW; bx += 8) {
      for (int c = 0; c < 3; ++c) {
        double a = 0.0;
        double b = 0.0;
        for (int y = by; y < by + 8; ++y) {
          for (int x = bx; x < bx + 8; ++x) {
            a += decoded[3 * (static_cast<std::size_t>(y) * kW + x) + static_cast<std::size_t>(c)];
            b += std::round(source.get(x, y, c) * 255.0f);
          }
        }
        worst = std::max(worst, std::abs(a - b) / 64.0);
      }
    }
  }
  return worst;
}

TEST(Gif, DiffusionKeepsSmoothTonesAndStillPartsStill) {
  const test::TempDir dir;
  const std::vector<Image> frames{skinFrame(20), skinFrame(26), skinFrame(32)};
  writeGif(dir / "dithered.gif", frames, 4, true, true);
  writeGif(dir / "nearest.gif", frames, 4, true, false);
  const auto dithered = readFrames(dir / "dithered.gif");
  const auto nearest = readFrames(dir / "nearest.gif");
  ASSERT_EQ(dithered.size(), 3u);
  ASSERT_EQ(nearest.size(), 3u);
  const double ditheredError = worstBlockMeanError(dithered[0], frames[0]);
  const double nearestError = worstBlockMeanError(nearest[0], frames[0]);
  std::printf("worst 8x8 block-mean error: dithered %.2f, nearest %.2f levels\n", ditheredError,
              nearestError);
  EXPECT_LE(ditheredError, 1.5);
  EXPECT_LT(ditheredError, nearestError);
  // Outside the square's path (x 20..44, y 24..36) the later frames keep frame 0's pixels exactly.
  for (std::size_t f = 1; f < dithered.size(); ++f) {
    std::size_t moved = 0;
    for (int y = 0; y < kH; ++y) {
      for (int x = 0; x < kW; ++x) {
        if (x >= 20 && x < 44 && y >= 24 && y < 36) {
          continue;
        }
        const std::size_t i = 3 * (static_cast<std::size_t>(y) * kW + x);
        moved += dithered[f][i] != dithered[0][i] || dithered[f][i + 1] != dithered[0][i + 1] ||
                         dithered[f][i + 2] != dithered[0][i + 2]
                     ? 1
                     : 0;
      }
    }
    EXPECT_EQ(moved, 0u) << "frame " << f;
  }
  // The same frames, the same bytes.
  writeGif(dir / "again.gif", frames, 4, true, true);
  EXPECT_EQ(readTextFile(dir / "dithered.gif"), readTextFile(dir / "again.gif"));
}

} // namespace
} // namespace sylva::media
