// Image quilting: outputs made only of source texels, determinism by seed, settings checks.
#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/texsynth/Procedural.hpp>
#include <sylva/texsynth/Quilt.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "TestUtil.hpp"

namespace sylva::texsynth {
namespace {

using testing::HasSubstr;

/** A source whose texels are all different (random colours), so texel identity is checkable. */
Texture noiseSource(int w, int h, int channels, std::uint64_t seed) {
  Texture t = Texture::blank(w, h, channels, "noise.png");
  Rng rng(seed);
  for (float& v : t.texels) {
    v = rng.uniform();
  }
  return t;
}

std::set<std::vector<float>> texelSet(const Texture& t) {
  std::set<std::vector<float>> set;
  for (int y = 0; y < t.height; ++y) {
    for (int x = 0; x < t.width; ++x) {
      set.emplace(t.at(x, y), t.at(x, y) + t.channels);
    }
  }
  return set;
}

using test::errorOf;

TEST(Quilt, EveryOutputTexelIsASourceTexel) {
  for (const int channels : {3, 6}) {
    const Texture source = noiseSource(40, 36, channels, 5);
    QuiltSettings settings;
    settings.block = 12;
    settings.seed = 3;
    const Texture out = quilt(source, 71, 53, settings);
    ASSERT_EQ(out.width, 71);
    ASSERT_EQ(out.height, 53);
    ASSERT_EQ(out.channels, channels);
    const std::set<std::vector<float>> texels = texelSet(source);
    for (int y = 0; y < out.height; ++y) {
      for (int x = 0; x < out.width; ++x) {
        ASSERT_TRUE(texels.count(std::vector<float>(out.at(x, y), out.at(x, y) + channels)))
            << "texel " << x << "," << y << " is not in the source";
      }
    }
  }
}

TEST(Quilt, SameSeedSameTextureOtherSeedOtherTexture) {
  const Texture source = proceduralBark(96, 2);
  QuiltSettings settings;
  settings.block = 24;
  settings.seed = 9;
  const Texture a = quilt(source, 100, 80, settings);
  const Texture b = quilt(source, 100, 80, settings);
  EXPECT_EQ(a.texels, b.texels);
  settings.seed = 10;
  const Texture c = quilt(source, 100, 80, settings);
  EXPECT_NE(a.texels, c.texels);
}

TEST(Quilt, OverlapsAreSmoothedByTheCut) {
  // Quilting a smooth texture must beat pasting random blocks side by side: its mean squared difference
  // between neighbouring texels across block boundaries stays close to that inside the source.
  const Texture source = proceduralBark(128, 4);
  QuiltSettings settings;
  settings.block = 32;
  settings.overlap = 6;
  const Texture out = quilt(source, 160, 160, settings);
  const auto seamError = [&](const Texture& t) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < t.height; ++y) {
      for (int x = 1; x < t.width; ++x) {
        for (int c = 0; c < 3; ++c) {
          const double d = t.at(x, y)[c] - t.at(x - 1, y)[c];
          sum += d * d;
        }
        ++n;
      }
    }
    return sum / n;
  };
  EXPECT_LT(seamError(out), 1.5 * seamError(source));
}

TEST(Quilt, BadSettingsAndSourcesAreOneLineErrors) {
  const Texture source = noiseSource(20, 30, 3, 1);
  QuiltSettings settings;
  settings.block = 24;
  EXPECT_THAT(errorOf([&] { quilt(source, 50, 50, settings); }), HasSubstr("noise.png: the image is 20x30"));
  settings.block = 8;
  settings.overlap = 5;
  EXPECT_THAT(errorOf([&] { quilt(source, 50, 50, settings); }), HasSubstr("overlap"));
  settings.overlap = 0;
  settings.tolerance = std::nan("");
  EXPECT_THAT(errorOf([&] { quilt(source, 50, 50, settings); }), HasSubstr("tolerance"));
  settings.tolerance = 0.1;
  settings.block = 2;
  EXPECT_THAT(errorOf([&] { quilt(source, 50, 50, settings); }), HasSubstr("block"));
  settings.block = 8;
  EXPECT_THAT(errorOf([&] { quilt(source, 0, 50, settings); }), HasSubstr("size"));
  EXPECT_THAT(errorOf([&] { quilt(source, 100000, 50, settings); }), HasSubstr("size"));
  EXPECT_THAT(errorOf([&] { quilt(Texture{}, 10, 10, settings); }), HasSubstr("empty"));
}

} // namespace
} // namespace sylva::texsynth
