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

// Seen straight down from 10 m with a 90° field of view on 100 × 100 pixels, a point x metres off the axis at
// depth z sits 50·x/z pixels from the image centre.
TEST(ScreenErrorTest, ProjectsTheVerticalOffsetFromTheReferenceSurfaceIntoPixels) {
  HeightField slope(21, 21, 1.0f, 1.0f);
  for (int j = 0; j < 21; ++j) {
    for (int i = 0; i < 21; ++i) {
      slope.at(i, j) = 0.5f * static_cast<float>(i); // y = 0.5·x
    }
  }
  const glm::vec3 eye(10.0f, 30.0f, 10.0f);
  const glm::mat4 viewProj = glm::perspective(glm::radians(90.0f), 1.0f, 0.1f, 100.0f) *
                             glm::lookAt(eye, glm::vec3(10.0f, 0.0f, 10.0f), glm::vec3(0.0f, 0.0f, -1.0f));
  Image reference(100, 100, 4, PixelType::F32);
  for (int y = 0; y < 100; ++y) {
    for (int x = 10; x < 100; ++x) { // columns 0..9: no terrain
      const float wx = 5.0f + 0.1f * static_cast<float>(x);
      reference.set(x, y, 0, wx);
      reference.set(x, y, 1, 0.5f * wx);
      reference.set(x, y, 2, 5.0f + 0.1f * static_cast<float>(y));
      reference.set(x, y, 3, 1.0f);
    }
  }
  const ScreenErrorStats same = measureScreenError(slope, reference, reference, viewProj, 1.0f);
  EXPECT_EQ(same.pixels, 90u * 100u);
  EXPECT_EQ(same.worstPx, 0.0);
  EXPECT_EQ(same.coverageMismatch, 0u);
  // A point moved along the reference plane: the surfaces agree, error 0.
  Image along = reference;
  along.set(50, 50, 0, reference.get(50, 50, 0) + 1.0f);
  along.set(50, 50, 1, reference.get(50, 50, 1) + 0.5f);
  EXPECT_LT(measureScreenError(slope, along, reference, viewProj, 1.0f).worstPx, 1e-4);
  // A point 1 m below the plane, at (15, 6.5, 10): the segment to (15, 7.5, 10) spans 50·5/23.5 … 50·5/22.5
  // px.
  Image below = reference;
  below.set(50, 50, 0, 15.0f);
  below.set(50, 50, 1, 6.5f);
  below.set(50, 50, 2, 10.0f);
  below.set(50, 51, 0, 15.0f);
  below.set(50, 51, 1, 6.5f);
  below.set(50, 51, 2, 10.0f);
  reference.set(50, 51, 0, 15.0f);
  reference.set(50, 51, 1, 7.5f);
  reference.set(50, 51, 2, 10.0f);
  below.set(60, 60, 3, 0.0f); // terrain in the reference only
  const ScreenErrorStats one = measureScreenError(slope, below, reference, viewProj, 1.0f);
  EXPECT_NEAR(one.worstPx, 50.0 * (5.0 / 22.5 - 5.0 / 23.5), 0.02) << "1 m below R at (15, 7.5, 10)";
  EXPECT_EQ(one.coverageMismatch, 1u);
  EXPECT_EQ(one.pixels, 90u * 100u - 1u);
  EXPECT_THROW(measureScreenError(slope, Image(4, 4, 3, PixelType::F32), reference, viewProj, 1.0f),
               sylva::Error);
  EXPECT_THROW(measureScreenError(slope, Image(4, 4, 4, PixelType::F32), reference, viewProj, 1.0f),
               sylva::Error);
}

} // namespace
} // namespace sylva::terrain
