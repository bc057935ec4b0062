#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace sylva {
namespace {

Image pattern(int w, int h, int channels, PixelType type) {
  Image image(w, h, channels, type);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < channels; ++c) {
        image.set(x, y, c, static_cast<float>((x * 7 + y * 13 + c * 29) % 97) / 96.0f);
      }
    }
  }
  return image;
}

struct PngCase {
  int channels;
  PixelType type;
};

class PngRoundTrip : public ::testing::TestWithParam<PngCase> {};

TEST_P(PngRoundTrip, SavesAndLoadsExactly) {
  test::TempDir dir;
  const Image original = pattern(37, 21, GetParam().channels, GetParam().type);
  saveImage(dir / "a.png", original);
  const Image loaded = loadImage(dir / "a.png");
  EXPECT_EQ(loaded, original);
}

INSTANTIATE_TEST_SUITE_P(AllLayouts, PngRoundTrip,
                         ::testing::Values(PngCase{1, PixelType::U8}, PngCase{2, PixelType::U8},
                                           PngCase{3, PixelType::U8}, PngCase{4, PixelType::U8},
                                           PngCase{1, PixelType::U16}, PngCase{3, PixelType::U16},
                                           PngCase{4, PixelType::U16}));

TEST(Image, SixteenBitKeepsFullPrecision) {
  test::TempDir dir;
  Image image(3, 1, 1, PixelType::U16);
  auto v = image.values<std::uint16_t>();
  v[0] = 0;
  v[1] = 1;
  v[2] = 65535;
  saveImage(dir / "h.png", image);
  const Image loaded = loadPng(dir / "h.png");
  ASSERT_EQ(loaded.type(), PixelType::U16);
  EXPECT_EQ(loaded.values<std::uint16_t>()[1], 1);
  EXPECT_EQ(loaded.values<std::uint16_t>()[2], 65535);
}

TEST(Image, ExrRoundTripKeepsFloats) {
  test::TempDir dir;
  Image image(5, 4, 1, PixelType::F32);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) {
      image.set(x, y, 0, -120.5f + static_cast<float>(x * 1000 + y));
    }
  }
  saveImage(dir / "f.exr", image);
  EXPECT_EQ(loadImage(dir / "f.exr"), image);
  const Image rgba = pattern(6, 3, 4, PixelType::F32);
  saveImage(dir / "c.exr", rgba);
  EXPECT_EQ(loadImage(dir / "c.exr"), rgba);
}

TEST(Image, MissingFileNamesTheFile) {
  try {
    loadImage("/nonexistent/dir/heights.png");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("heights.png"), std::string::npos) << e.what();
  }
}

TEST(Image, TruncatedPngIsAnError) {
  test::TempDir dir;
  saveImage(dir / "full.png", pattern(64, 64, 3, PixelType::U8));
  std::ifstream in(dir / "full.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "cut.png", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  try {
    loadImage(dir / "cut.png");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cut.png"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "errors are one line";
  }
}

TEST(Image, NonPngAndCorruptExrAreErrors) {
  test::TempDir dir;
  std::ofstream(dir / "text.png") << "hello, not an image";
  EXPECT_THROW(loadImage(dir / "text.png"), Error);
  std::ofstream(dir / "bad.exr") << "garbage garbage garbage";
  EXPECT_THROW(loadImage(dir / "bad.exr"), Error);
  EXPECT_THROW(loadImage(dir / "x.bmp"), Error);
}

TEST(Image, FailedSaveLeavesNoFile) {
  test::TempDir dir;
  EXPECT_THROW(saveImage(dir / "empty.png", Image()), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "empty.png"));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(Image, RejectsAbsurdSizes) {
  EXPECT_THROW(Image(0, 10, 1, PixelType::U8), Error);
  EXPECT_THROW(Image(10, 1 << 20, 1, PixelType::U8), Error);
  EXPECT_THROW(Image(10, 10, 5, PixelType::U8), Error);
}

TEST(Image, FlipAndConvert) {
  Image image = pattern(4, 3, 2, PixelType::U8);
  Image flipped = image;
  flipped.flipVertically();
  EXPECT_EQ(flipped.get(1, 0, 1), image.get(1, 2, 1));
  flipped.flipVertically();
  EXPECT_EQ(flipped, image);
  EXPECT_EQ(image.converted(PixelType::U16).converted(PixelType::U8), image);
  EXPECT_THROW(image.values<float>(), Error);
}

} // namespace
} // namespace sylva
