#include <sylva/render/ExactCoverage.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace sylva::render {
namespace {

/** A clip-space vertex at window position (x, y) pixels of a w×h viewport, window depth `depth`, with
 * `clipW`. */
glm::vec4 atWindow(double x, double y, double depth, glm::ivec2 size, double clipW = 1.0) {
  return glm::vec4(static_cast<float>((2.0 * x / size.x - 1.0) * clipW),
                   static_cast<float>((2.0 * y / size.y - 1.0) * clipW),
                   static_cast<float>((2.0 * depth - 1.0) * clipW), static_cast<float>(clipW));
}

const glm::ivec2 kView{64, 32};

TEST(ExactCoverage, AFlatTriangleCoversItsInsideAtItsDepthAndNothingOutside) {
  const ClipTriangle tri{
      {atWindow(8, 4, 0.25, kView), atWindow(40, 4, 0.25, kView), atWindow(8, 28, 0.25, kView)}, 7};
  const std::vector<glm::dvec2> samples{{10.5, 6.5}, {30.5, 20.5}, {8.5, 28.5}};
  const auto hits = exactCoverage(std::span(&tri, 1), kView, samples);
  ASSERT_EQ(hits[0].size(), 1u);
  EXPECT_EQ(hits[0][0].tag, 7);
  EXPECT_NEAR(hits[0][0].depth, 0.25, 1e-7);
  // (10.5, 6.5): 2.5 px above the bottom edge y = 4 and 2.5 px right of x = 8; the hypotenuse is farther.
  EXPECT_NEAR(hits[0][0].edgeDistance, 2.5, 1e-5);
  EXPECT_TRUE(hits[1].empty()); // beyond the hypotenuse
  EXPECT_TRUE(hits[2].empty()); // above the top vertex
}

TEST(ExactCoverage, WindingDoesNotMatterAndDepthIsInterpolatedAcrossTheScreen) {
  // Clockwise on screen; depth 0 at the left edge, 1 at the right.
  const ClipTriangle tri{
      {atWindow(0, 0, 0.0, kView), atWindow(0, 32, 0.0, kView), atWindow(64, 16, 1.0, kView)}};
  const std::vector<glm::dvec2> samples{{16.0, 16.0}, {48.0, 16.0}};
  const auto hits = exactCoverage(std::span(&tri, 1), kView, samples);
  ASSERT_EQ(hits[0].size(), 1u);
  ASSERT_EQ(hits[1].size(), 1u);
  EXPECT_NEAR(hits[0][0].depth, 0.25, 1e-6);
  EXPECT_NEAR(hits[1][0].depth, 0.75, 1e-6);
}

TEST(ExactCoverage, NeighboursSharingAnEdgeSplitSamplesByTheirExactSide) {
  // Two triangles sharing the diagonal (0, 0)–(64, 32) of the viewport; samples a hair on either side.
  const ClipTriangle below{
      {atWindow(0, 0, 0.5, kView), atWindow(64, 0, 0.5, kView), atWindow(64, 32, 0.5, kView)}, 1};
  const ClipTriangle above{
      {atWindow(0, 0, 0.5, kView), atWindow(64, 32, 0.5, kView), atWindow(0, 32, 0.5, kView)}, 2};
  const std::vector<ClipTriangle> tris{below, above};
  const double hair = 1e-4; // px, far below any rasteriser's sub-pixel grid
  const glm::dvec2 onDiagonal(32.0, 16.0);
  const glm::dvec2 normal = glm::normalize(glm::dvec2(-32.0, 64.0)); // points into `above`
  const std::vector<glm::dvec2> samples{onDiagonal + hair * normal, onDiagonal - hair * normal};
  const auto hits = exactCoverage(tris, kView, samples);
  ASSERT_EQ(hits[0].size(), 1u);
  ASSERT_EQ(hits[1].size(), 1u);
  EXPECT_EQ(hits[0][0].tag, 2);
  EXPECT_EQ(hits[1][0].tag, 1);
  EXPECT_NEAR(hits[0][0].edgeDistance, hair, 1e-6);
  EXPECT_NEAR(hits[1][0].edgeDistance, hair, 1e-6);
}

TEST(ExactCoverage, HitsAreSortedNearestFirst) {
  std::vector<ClipTriangle> tris;
  for (double depth : {0.9, 0.1, 0.5}) {
    tris.push_back(
        {{atWindow(0, 0, depth, kView), atWindow(64, 0, depth, kView), atWindow(0, 32, depth, kView)},
         static_cast<int>(depth * 10)});
  }
  const std::vector<glm::dvec2> samples{{4.5, 4.5}};
  const auto hits = exactCoverage(tris, kView, samples);
  ASSERT_EQ(hits[0].size(), 3u);
  EXPECT_EQ(hits[0][0].tag, 1);
  EXPECT_EQ(hits[0][1].tag, 5);
  EXPECT_EQ(hits[0][2].tag, 9);
  EXPECT_EQ(hits[0][0].triangle, 1u);
}

TEST(ExactCoverage, PerspectiveVerticesProjectThroughW) {
  // The same window triangle written with w = 3: identical coverage and depth.
  const ClipTriangle tri{
      {atWindow(8, 4, 0.3, kView, 3.0), atWindow(40, 4, 0.3, kView, 3.0), atWindow(8, 28, 0.3, kView, 3.0)}};
  const std::vector<glm::dvec2> samples{{10.5, 6.5}};
  const auto hits = exactCoverage(std::span(&tri, 1), kView, samples);
  ASSERT_EQ(hits[0].size(), 1u);
  EXPECT_NEAR(hits[0][0].depth, 0.3, 1e-6);
}

TEST(ExactCoverage, TrianglesAreClippedAtTheNearPlane) {
  // A floor through a perspective camera (near 1, far 100, 90° field of view): clip = P·(x, −1, z, 1).
  // Vertices far ahead and one behind the camera; samples in the lower half see the floor, the upper half
  // (above the horizon) sees nothing, whatever the vertex behind the eye projects to.
  const double n = 1.0;
  const double f = 100.0;
  auto clipOf = [&](double x, double y, double z) {
    // Eye space looks down −z; OpenGL perspective with a 90° field of view and aspect 2 (64×32).
    const double cx = x / 2.0;
    const double cy = y;
    const double cz = (f + n) / (n - f) * z + 2.0 * f * n / (n - f);
    const double cw = -z;
    return glm::vec4(static_cast<float>(cx), static_cast<float>(cy), static_cast<float>(cz),
                     static_cast<float>(cw));
  };
  const ClipTriangle floor{{clipOf(-50.0, -1.0, -50.0), clipOf(50.0, -1.0, -50.0), clipOf(0.0, -1.0, 10.0)}};
  const std::vector<glm::dvec2> samples{{32.0, 8.0}, {32.0, 15.0}, {32.0, 24.0}};
  const auto hits = exactCoverage(std::span(&floor, 1), kView, samples);
  ASSERT_EQ(hits[0].size(), 1u);
  ASSERT_EQ(hits[1].size(), 1u);
  EXPECT_TRUE(hits[2].empty());
  // Window y = 8 is ndc −0.5: the ray (0, −0.5, −1) meets the floor y = −1 at eye depth 2.
  const double zNdc = ((f + n) / (n - f) * -2.0 + 2.0 * f * n / (n - f)) / 2.0;
  EXPECT_NEAR(hits[0][0].depth, (zNdc + 1.0) / 2.0, 1e-6);
  EXPECT_GT(hits[1][0].depth, hits[0][0].depth);
  EXPECT_LE(hits[1][0].depth, 1.0);
}

TEST(ExactCoverage, TrianglesWithNoAreaOrBehindTheEyeCoverNothing) {
  const std::vector<ClipTriangle> tris{
      {{atWindow(0, 0, 0.5, kView), atWindow(32, 16, 0.5, kView), atWindow(64, 32, 0.5, kView)}}, // a line
      {{glm::vec4(0, 0, 0, -1), glm::vec4(1, 0, 0, -1), glm::vec4(0, 1, 0, -1)}},                 // w < 0
  };
  const std::vector<glm::dvec2> samples{{32.0, 16.0}, {33.0, 16.5}};
  const auto hits = exactCoverage(tris, kView, samples);
  EXPECT_TRUE(hits[0].empty());
  EXPECT_TRUE(hits[1].empty());
}

} // namespace
} // namespace sylva::render
