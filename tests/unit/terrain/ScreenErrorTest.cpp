#include <sylva/terrain/ScreenError.hpp>

#include <sylva/core/Error.hpp>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace sylva::terrain {
namespace {

// A 3×3-sample field, 1 m spacing, with a twisted cell: h = x·z on [0, 2]².
HeightField saddle() {
  HeightField f(3, 3, 1.0f, 1.0f);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      f.at(i, j) = static_cast<float>(i * j);
    }
  }
  return f;
}

TEST(ScreenErrorTest, GapIsZeroOnEitherTriangulationAndVerticalElsewhere) {
  const HeightField f = saddle();
  // Cell (0, 0): corners 0, 0, 0, 1. At its centre one diagonal gives 0.5, the other 0.
  EXPECT_EQ(fullResolutionGap(f, {0.5f, 0.5f, 0.5f}), 0.0f);
  EXPECT_EQ(fullResolutionGap(f, {0.5f, 0.0f, 0.5f}), 0.0f);
  EXPECT_EQ(fullResolutionGap(f, {0.5f, 0.25f, 0.5f}), 0.0f); // the bilinear surface lies between them
  EXPECT_NEAR(fullResolutionGap(f, {0.5f, 1.5f, 0.5f}), 1.0f, 1e-6f);
  EXPECT_NEAR(fullResolutionGap(f, {0.5f, -2.0f, 0.5f}), 2.0f, 1e-6f);
  // A sample point: both triangulations agree.
  EXPECT_NEAR(fullResolutionGap(f, {2.0f, 4.25f, 2.0f}), 0.25f, 1e-6f);
  EXPECT_TRUE(std::isnan(fullResolutionGap(f, {-0.1f, 0.0f, 1.0f})));
  EXPECT_TRUE(std::isnan(fullResolutionGap(f, {1.0f, 0.0f, 2.5f})));
  // A 1 m lattice over 1 m samples is the sample grid; a 2 m lattice spans the saddle's four cells at once.
  EXPECT_EQ(fullResolutionGap(f, {0.5f, 1.5f, 0.5f}, 1.0f), fullResolutionGap(f, {0.5f, 1.5f, 0.5f}));
  EXPECT_EQ(fullResolutionGap(f, {1.0f, 2.0f, 1.0f}, 2.0f), 0.0f); // either diagonal of 0, 0, 0, 4: 0 or 2
  EXPECT_NEAR(fullResolutionGap(f, {1.0f, 3.0f, 1.0f}, 2.0f), 1.0f, 1e-6f);
  HeightField holes = saddle();
  holes.at(1, 1) = std::nanf("");
  EXPECT_TRUE(std::isnan(fullResolutionGap(holes, {0.5f, 0.0f, 0.5f})));
}

// A flat field seen straight down from 10 m with a 90° field of view on 100 × 100 pixels: 1 m at 10 m spans
// 5 pixels at the image centre. A drawn surface 1 m low at the centre pixel gives ~5 px there.
TEST(ScreenErrorTest, ProjectsTheVerticalGapIntoPixels) {
  HeightField flat(21, 21, 1.0f, 1.0f, 0.0f);
  const glm::vec3 eye(10.0f, 10.0f, 10.0f);
  const glm::mat4 viewProj = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 100.0f) *
                             glm::lookAt(eye, glm::vec3(10.0f, 0.0f, 10.0f), glm::vec3(0.0f, 0.0f, -1.0f));
  Image positions(100, 100, 4, PixelType::F32);
  // Exact surface everywhere except one pixel, and some uncovered pixels.
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 100; ++x) {
      if (x < 10) {
        continue; // alpha 0: no terrain
      }
      positions.set(x, y, 0, 5.0f + 0.1f * static_cast<float>(x));
      positions.set(x, y, 1, 0.0f);
      positions.set(x, y, 2, 5.0f + 0.1f * static_cast<float>(y));
      positions.set(x, y, 3, 1.0f);
    }
  }
  ScreenErrorStats exact = measureScreenError(flat, positions, viewProj);
  EXPECT_EQ(exact.pixels, 90u * 100u);
  EXPECT_EQ(exact.worstPx, 0.0);
  positions.set(50, 50, 0, 10.0f);
  positions.set(50, 50, 1, -1.0f);
  positions.set(50, 50, 2, 10.0f);
  const ScreenErrorStats one = measureScreenError(flat, positions, viewProj);
  // Straight down, a vertical segment projects to the image centre: 0 px. Move it off-axis.
  EXPECT_LT(one.worstPx, 1e-3);
  positions.set(50, 50, 0, 15.0f);
  const ScreenErrorStats side = measureScreenError(flat, positions, viewProj);
  // From (10, 10, 10) the segment (15, −1 … 0, 10) spans x/depth 5/11 … 5/10 of the half-width (50 px).
  EXPECT_NEAR(side.worstPx, 50.0 * (5.0 / 10.0 - 5.0 / 11.0), 0.05);
  EXPECT_GT(side.meanPx, 0.0);
  EXPECT_EQ(side.p999Px, 0.0); // one pixel in 9,000 is beyond the 99.9th percentile
  EXPECT_THROW(measureScreenError(flat, Image(4, 4, 3, PixelType::F32), viewProj), sylva::Error);
}

} // namespace
} // namespace sylva::terrain
