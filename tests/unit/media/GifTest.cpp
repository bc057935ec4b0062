// The GIF writer against its source frames, read back through giflib: error diffusion keeps smooth tones'
// local mean (skin, sky) where nearest-colour mapping posterises them into bands, still parts of an animation
// keep their pixels, and the file is deterministic.
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/media/Export.hpp>

#include "ExternalData.hpp"
#include "TempDir.hpp"

#include <gif_lib.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <utility>
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
 * the eye sees of smooth tones (dithering trades per-pixel error for the right local mean). `border`: blocks
 * that many pixels or fewer from the picture's edge are left out. */
double worstBlockMeanError(const std::vector<std::uint8_t>& decoded, const Image& source, int border = 0) {
  double worst = 0.0;
  const int w = source.width();
  for (int by = border; by + 8 + border <= source.height(); by += 8) {
    for (int bx = border; bx + 8 + border <= w; bx += 8) {
      for (int c = 0; c < 3; ++c) {
        double a = 0.0;
        double b = 0.0;
        for (int y = by; y < by + 8; ++y) {
          for (int x = bx; x < bx + 8; ++x) {
            a += decoded[3 * (static_cast<std::size_t>(y) * w + x) + static_cast<std::size_t>(c)];
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
  // Inside the picture. The gradient's extremes lie on its edges, outside every palette of pixel means (the
  // median cut's entries), where diffusion cannot reach them either: there the error is the palette's.
  const double ditheredError = worstBlockMeanError(dithered[0], frames[0], 8);
  const double nearestError = worstBlockMeanError(nearest[0], frames[0], 8);
  const double ditheredEdges = worstBlockMeanError(dithered[0], frames[0]);
  std::printf("worst 8x8 block-mean error inside: dithered %.2f, nearest %.2f levels; with the edges %.2f\n",
              ditheredError, nearestError, ditheredEdges);
  EXPECT_LE(ditheredError, 1.0);
  EXPECT_LT(ditheredError, nearestError);
  EXPECT_LE(ditheredEdges, 2.5);
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

/** A skin gradient (frame 0's colours) with, from frame 1 on, a 40×40 patch of a sky-to-leaf gradient at
 * (60 + 6f, 28): hues frame 0 does not have, on a small part of the picture. */
Image patchFrame(int f) {
  Image image = skinFrame(-100);
  if (f == 0) {
    return image;
  }
  const int px = 60 + 6 * f;
  for (int y = 28; y < 68; ++y) {
    for (int x = px; x < px + 40; ++x) {
      const float u = static_cast<float>(x - px) / 39.0f;
      const float v = static_cast<float>(y - 28) / 39.0f;
      image.set(x, y, 0, 0.10f + 0.25f * u);
      image.set(x, y, 1, 0.35f + 0.45f * v);
      image.set(x, y, 2, 0.85f - 0.55f * v);
    }
  }
  return image;
}

/** Mean and worst per-pixel error (levels of 255, largest channel) inside [x0, x1) × [y0, y1). */
std::pair<double, int> pixelError(const std::vector<std::uint8_t>& decoded, const Image& source, int x0,
                                  int y0, int x1, int y1) {
  double sum = 0.0;
  int worst = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      int e = 0;
      for (int c = 0; c < 3; ++c) {
        const int a = decoded[3 * (static_cast<std::size_t>(y) * kW + x) + static_cast<std::size_t>(c)];
        const int b = static_cast<int>(std::lround(source.get(x, y, c) * 255.0f));
        e = std::max(e, std::abs(a - b));
      }
      sum += e;
      worst = std::max(worst, e);
    }
  }
  return {sum / ((x1 - x0) * (y1 - y0)), worst};
}

// Per-frame palettes (issue 30: colours the one global palette lacked stayed off by up to 59 levels): each
// frame's changed rectangle is quantised on its own, so a patch of new hues on a small part of the picture is
// drawn from a palette of its own colours.
TEST(Gif, EachFrameGetsThePaletteOfWhatChanged) {
  const test::TempDir dir;
  std::vector<Image> frames;
  for (int f = 0; f < 4; ++f) {
    frames.push_back(patchFrame(f));
  }
  writeGif(dir / "patch.gif", frames, 4, true, true);
  const auto decoded = readFrames(dir / "patch.gif");
  ASSERT_EQ(decoded.size(), 4u);
  for (int f = 1; f < 4; ++f) {
    const int px = 60 + 6 * f;
    const auto [mean, worst] = pixelError(decoded[static_cast<std::size_t>(f)],
                                          frames[static_cast<std::size_t>(f)], px, 28, px + 40, 68);
    std::printf("frame %d: patch error mean %.2f, worst %d levels\n", f, mean, worst);
    EXPECT_LT(mean, 3.5) << "frame " << f; // one global palette: 6.35
    EXPECT_LE(worst, 10) << "frame " << f; // one global palette: 26 … 33
  }
  const auto [mean0, worst0] = pixelError(decoded[0], frames[0], 0, 0, kW, kH);
  std::printf("frame 0: error mean %.2f, worst %d levels\n", mean0, worst0);
  EXPECT_LT(mean0, 4.5); // one global palette sampled over all frames: 5.54, worst 42
}

// A real portrait (scikit-image's chelsea.png, a cat): no part of it goes far off. giflib's median cut split
// the box widest in colour whatever its pixels, and drew the pupil (26, 19, 11) as (68, 42, 22): an 8×8 block
// 58 levels off, 20 % of the pixels more than 8 levels off; the variance-based cut gives dense clusters
// entries of their own.
TEST(Gif, APortraitKeepsItsDarkAndItsSmoothParts) {
  const std::filesystem::path photo = test::externalData("chelsea.png");
  SYLVA_REQUIRE_EXTERNAL_DATA(photo);
  const Image source = loadImage(photo);
  Image frame(source.width(), source.height(), 4, PixelType::U8);
  for (int y = 0; y < source.height(); ++y) {
    for (int x = 0; x < source.width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        frame.set(x, y, c, source.get(x, y, std::min(c, source.channels() - 1)));
      }
      frame.set(x, y, 3, 1.0f);
    }
  }
  const test::TempDir dir;
  writeGif(dir / "cat.gif", std::vector<Image>{frame}, 4);
  const std::vector<std::uint8_t> decoded = readFrames(dir / "cat.gif").at(0);
  const int w = frame.width();
  const double worstBlock = worstBlockMeanError(decoded, frame);
  std::size_t far = 0;
  for (int y = 0; y < frame.height(); ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double d = decoded[3 * (static_cast<std::size_t>(y) * w + x) + static_cast<std::size_t>(c)] -
                         std::round(frame.get(x, y, c) * 255.0f);
        if (std::abs(d) > 8.0) {
          ++far;
          break;
        }
      }
    }
  }
  const double farShare = static_cast<double>(far) / (static_cast<double>(w) * frame.height());
  std::printf("chelsea.png as a GIF: worst 8x8 block %.1f levels, %.1f %% of the pixels more than 8 off\n",
              worstBlock, 100.0 * farShare);
  EXPECT_LT(worstBlock, 20.0);
  EXPECT_LT(farShare, 0.14);
}

} // namespace
} // namespace sylva::media
