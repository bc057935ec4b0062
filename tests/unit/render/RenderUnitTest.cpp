#include <sylva/core/Geometry.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/Timing.hpp>

#include <nlohmann/json.hpp>
#include <sylva/render/ImageCompare.hpp>

#include <shared/Demo.h>
#include <shared/Frame.h>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace sylva::render {
namespace {

TEST(Frustum, ClassifiesBoxesAndPoints) {
  Camera camera;
  camera.position = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.nearPlane = 1.0f;
  camera.farPlane = 100.0f;
  const Frustum f = camera.frustum(1.0f);
  EXPECT_TRUE(f.contains({0, 0, -10}));
  EXPECT_FALSE(f.contains({0, 0, 10}));
  EXPECT_FALSE(f.contains({0, 0, -200}));
  EXPECT_FALSE(f.contains({50, 0, -10})); // 60° fov: half-width at z = -10 is ~5.8
  EXPECT_EQ(f.test({{-1, -1, -12}, {1, 1, -8}}), Containment::Inside);
  EXPECT_EQ(f.test({{-1, -1, 5}, {1, 1, 8}}), Containment::Outside);
  EXPECT_EQ(f.test({{-1, -1, -2}, {1, 1, 2}}), Containment::Intersects);
  EXPECT_TRUE(f.intersectsSphere({0, 0, 3}, 4.5f)); // reaches past the near plane at z = -1
  EXPECT_FALSE(f.intersectsSphere({0, 0, 3}, 1.0f));
}

TEST(Frustum, PlaneDistancesAreMetric) {
  const Frustum f(glm::ortho(-10.0f, 10.0f, -10.0f, 10.0f, 0.0f, 100.0f));
  // Left plane: x ≥ -10 → distance of origin is 10 m.
  EXPECT_NEAR(glm::dot(glm::vec3(f.planes()[0]), glm::vec3(0)) + f.planes()[0].w, 10.0f, 1e-4f);
}

TEST(Camera, OrbitKeepsDistanceAndLooksAtTarget) {
  OrbitController orbit;
  orbit.target = {5, 1, -3};
  orbit.distance = 42.0f;
  orbit.rotate(120, -40);
  Camera camera;
  orbit.apply(camera);
  EXPECT_NEAR(glm::length(camera.position - orbit.target), 42.0f, 1e-3f);
  EXPECT_EQ(camera.target, orbit.target);
  orbit.zoom(3);
  EXPECT_LT(orbit.distance, 42.0f);
}

TEST(Camera, FlyMovesForward) {
  FlyController fly;
  fly.position = {0, 0, 0};
  fly.yaw = 0.0f;
  fly.pitch = 0.0f;
  fly.speed = 10.0f;
  fly.update({0, 0, 1}, 0, 0, 0.5f);
  EXPECT_NEAR(fly.position.z, 5.0f, 1e-4f);
}

TEST(Stats, MedianAndQuantiles) {
  const Stats s = Stats::of({5, 1, 4, 2, 3});
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  EXPECT_NEAR(s.p10, 1.4, 1e-9);
  EXPECT_EQ(Stats::of({}).count, 0u);
}

TEST(FrameClock, FixedStepIsDeterministic) {
  FrameClock clock(1.0 / 60.0);
  for (int i = 0; i < 60; ++i) {
    EXPECT_DOUBLE_EQ(clock.tick(), 1.0 / 60.0);
  }
  EXPECT_NEAR(clock.time(), 1.0, 1e-12);
}

Image solid(int w, int h, float v) {
  Image image(w, h, 4, PixelType::U8);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 4; ++c) {
        image.set(x, y, c, c == 3 ? 1.0f : v);
      }
    }
  }
  return image;
}

TEST(ImageCompare, CountsFailingPixelsAgainstTolerance) {
  const Image a = solid(10, 10, 0.5f);
  Image b = a;
  b.set(3, 4, 0, 0.5f + 10.0f / 255.0f); // one pixel off by 10 steps
  b.set(5, 5, 1, 0.5f + 2.0f / 255.0f);  // one pixel off by 2 steps
  const CompareResult strict = compareImages(b, a, {1, 0.0});
  EXPECT_FALSE(strict.passed);
  EXPECT_EQ(strict.failingPixels, 2u);
  EXPECT_EQ(strict.maxChannelDiff, 10);
  const CompareResult loose = compareImages(b, a, {2, 0.0});
  EXPECT_EQ(loose.failingPixels, 1u);
  EXPECT_TRUE(compareImages(b, a, {2, 0.011}).passed);
  EXPECT_FALSE(compareImages(b, a, {2, 0.009}).passed);
  EXPECT_NEAR(loose.diff.get(3, 4, 0), 0.4f + 0.6f * 10.0f / 255.0f, 0.01f) << "failing pixels are red";
}

TEST(ImageCompare, MaskAndSizeMismatch) {
  const Image a = solid(8, 8, 0.2f);
  Image b = a;
  b.set(2, 2, 0, 1.0f);
  Image mask(8, 8, 1, PixelType::U8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 0; x < 8; ++x) {
      mask.set(x, y, 0, (x == 2 && y == 2) ? 0.0f : 1.0f);
    }
  }
  EXPECT_TRUE(compareImages(b, a, {0, 0.0}, &mask).passed);
  EXPECT_EQ(compareImages(b, a, {0, 0.0}, &mask).comparedPixels, 63u);
  EXPECT_FALSE(compareImages(solid(8, 9, 0.2f), a, {255, 1.0}).passed);
}

TEST(SharedLayouts, MatchStd140Expectations) {
  // The GLSL side declares the same structs; offsets here are the std140 offsets the shaders read.
  EXPECT_EQ(offsetof(gpu::FrameUniforms, cameraPos), 128u);
  EXPECT_EQ(offsetof(gpu::FrameUniforms, viewport), 176u);
  EXPECT_EQ(offsetof(gpu::DemoUniforms, field), 32u);
}

} // namespace
} // namespace sylva::render
