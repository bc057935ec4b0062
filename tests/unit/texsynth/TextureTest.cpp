// Textures from pictures and back, photo loading (JPEG through OpenCV), procedural bark.
#include "ExternalData.hpp"
#include "TempDir.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/texsynth/Procedural.hpp>
#include <sylva/texsynth/Texture.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace sylva::texsynth {
namespace {

using testing::HasSubstr;

TEST(Texture, NormalMapsRoundTripThroughImages) {
  Image colour(5, 4, 3, PixelType::U8);
  Image normal(5, 4, 3, PixelType::U8);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 5; ++x) {
      colour.set(x, y, 0, x / 4.0f);
      normal.set(x, y, 0, 0.5f);
      normal.set(x, y, 1, 1.0f); // green up in the picture
      normal.set(x, y, 2, 0.5f);
    }
  }
  const Texture t = textureFromImages(colour, "c.png", &normal, "n.png", NormalGreen::Up);
  ASSERT_EQ(t.channels, 6);
  EXPECT_FLOAT_EQ(t.at(4, 0)[0], 1.0f);
  EXPECT_FLOAT_EQ(t.at(1, 1)[4], -1.0f) << "green up is towards row 0, so y along rows is negative";
  EXPECT_EQ(colourImage(t), colour);
  EXPECT_EQ(normalImage(t, NormalGreen::Up), normal);
  EXPECT_EQ(normalImage(t, NormalGreen::AlongRows).get(0, 0, 1), 0.0f);
  Image other(3, 3, 3, PixelType::U8);
  EXPECT_THROW(textureFromImages(colour, "c.png", &other, "n.png"), Error);
  EXPECT_THROW(normalImage(textureFromImages(colour, "c.png"), NormalGreen::Up), Error);
}

TEST(Texture, PhotoErrorsNameTheFile) {
  const test::TempDir dir;
  writeTextFile(dir / "broken.jpg", "not a jpeg");
  try {
    loadPhoto(dir / "broken.jpg");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("broken.jpg"));
  }
  EXPECT_THROW(loadPhoto(dir / "missing.jpg"), Error);
  writeTextFile(dir / "photo.gif", "GIF89a");
  EXPECT_THROW(loadPhoto(dir / "photo.gif"), Error);
  // A 2.6 KB progressive JPEG claiming 20000×20000 pixels is refused from its header, before libjpeg would
  // allocate and zero about 2 GB of coefficients.
  std::filesystem::copy_file(
      test::sourcePath("fuzz/regressions/flow/jpeg-progressive-claims-20000x20000.jpg"), dir / "huge.jpg");
  try {
    loadPhoto(dir / "huge.jpg");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("huge.jpg: image size 20000x20000 is out of range"));
  }
  // OpenCV decodes by content: a .jpg that holds another format OpenCV reads (a Radiance file claiming 13000²
  // pixels, which it would decode to 2 GB of floats; a small PPM) is refused before anything decodes.
  std::filesystem::copy_file(test::sourcePath("fuzz/regressions/flow/radiance-claims-13000x13000.hdr"),
                             dir / "radiance.jpg");
  try {
    loadPhoto(dir / "radiance.jpg");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("radiance.jpg: not a JPEG file (its content is Radiance HDR)"));
  }
  writeTextFile(dir / "small.jpg", "P6\n4 4\n255\n" + std::string(48, 'x'));
  try {
    loadPhoto(dir / "small.jpg");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("small.jpg: not a JPEG file (its content is PNM)"));
  }
}

TEST(Texture, LoadsTheBarkPhotosThroughOpenCv) {
  const auto colour = test::externalData("ez-tree/bark/oak_color_1k.jpg");
  const auto normal = test::externalData("ez-tree/bark/oak_normal_1k.jpg");
  SYLVA_REQUIRE_EXTERNAL_DATA(colour);
  SYLVA_REQUIRE_EXTERNAL_DATA(normal);
  const Texture t = loadPhotoTexture(colour, normal);
  EXPECT_EQ(t.width, 1024);
  EXPECT_EQ(t.height, 1024);
  EXPECT_EQ(t.channels, 6);
  double z = 0.0;
  for (int y = 0; y < t.height; y += 16) {
    for (int x = 0; x < t.width; x += 16) {
      z += t.at(x, y)[5];
    }
  }
  EXPECT_GT(z / (64 * 64), 0.5) << "tangent-space normals point mostly out of the surface";
}

TEST(ProceduralBark, DeterministicWithVerticalGrooves) {
  const Texture a = proceduralBark(128, 3);
  EXPECT_EQ(a.texels, proceduralBark(128, 3).texels);
  EXPECT_NE(a.texels, proceduralBark(128, 4).texels);
  ASSERT_EQ(a.channels, 6);
  // Grooves run along the rows: colour changes much more across columns than along rows.
  double acrossColumns = 0.0;
  double alongRows = 0.0;
  for (int y = 1; y < a.height; ++y) {
    for (int x = 1; x < a.width; ++x) {
      acrossColumns += std::abs(a.at(x, y)[0] - a.at(x - 1, y)[0]);
      alongRows += std::abs(a.at(x, y)[0] - a.at(x, y - 1)[0]);
      const float* n = a.at(x, y);
      ASSERT_NEAR(n[3] * n[3] + n[4] * n[4] + n[5] * n[5], 1.0f, 1e-4f);
    }
  }
  EXPECT_GT(acrossColumns, 1.5 * alongRows);
  EXPECT_THROW(proceduralBark(8, 1), Error);
}

} // namespace
} // namespace sylva::texsynth
