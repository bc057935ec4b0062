#include <sylva/core/Error.hpp>
#include <sylva/scene/CameraPath.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace sylva::scene {
namespace {

WorldCameraKey key(double t, glm::vec3 p, glm::vec3 target = {0, 0, -100}, float fov = 50.0f) {
  return {t, p, target, fov};
}

/** Keys with uneven spacing in time and space, including a sharp turn. */
std::vector<WorldCameraKey> wiggle() {
  return {key(0.0, {0, 10, 0}, {0, 0, -50}, 60), key(1.0, {10, 12, 0}, {5, 0, -50}, 55),
          key(1.5, {11, 12, 1}, {10, 0, -50}, 50), key(4.0, {40, 20, -30}, {20, 0, -60}, 40),
          key(6.0, {0, 15, -35}, {0, 0, -70}, 45)};
}

TEST(CameraPath, PassesThroughEveryKeyExactly) {
  const auto keys = wiggle();
  for (const WorldCameraKey& k : keys) {
    const CameraSample s = evaluate(keys, k.time, false);
    EXPECT_EQ(s.position, k.position);
    EXPECT_EQ(s.target, k.target);
    EXPECT_EQ(s.fov, k.fov);
  }
  // Just off a key, the curve is next to it (no jump into the segment).
  for (const WorldCameraKey& k : keys) {
    const CameraSample s = evaluate(keys, k.time + 1e-6, false);
    EXPECT_LT(glm::length(s.position - k.position), 1e-3f);
  }
}

TEST(CameraPath, ClampsOutsideTheKeysAndOneKeyIsStill) {
  const auto keys = wiggle();
  EXPECT_EQ(evaluate(keys, -10.0, false).position, keys.front().position);
  EXPECT_EQ(evaluate(keys, 100.0, false).position, keys.back().position);
  const std::vector<WorldCameraKey> still{key(3.0, {1, 2, 3}, {4, 5, 6}, 33)};
  for (double t : {-1.0, 3.0, 1e6}) {
    const CameraSample s = evaluate(still, t, false);
    EXPECT_EQ(s.position, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.target, glm::vec3(4, 5, 6));
    EXPECT_EQ(s.fov, 33.0f);
  }
}

TEST(CameraPath, IsContinuousAndTangentContinuousAtKeys) {
  const auto keys = wiggle();
  // Position: the step over a tiny dt is tiny everywhere (no jumps), also across keys.
  const double dt = 1e-4;
  for (double t = 0.0; t < 6.0; t += 0.01) {
    const glm::vec3 a = evaluate(keys, t, false).position;
    const glm::vec3 b = evaluate(keys, t + dt, false).position;
    ASSERT_LT(glm::length(b - a), 0.05f) << "jump at t = " << t;
  }
  // Direction of travel: the one-sided tangents at an interior key point the same way (C1 in direction for
  // Catmull-Rom: both segments use the same neighbours there).
  for (std::size_t i = 1; i + 1 < keys.size(); ++i) {
    const double t = keys[i].time;
    const double h = 1e-3;
    const glm::vec3 before =
        glm::normalize(evaluate(keys, t, false).position - evaluate(keys, t - h, false).position);
    const glm::vec3 after =
        glm::normalize(evaluate(keys, t + h, false).position - evaluate(keys, t, false).position);
    EXPECT_GT(glm::dot(before, after), 0.99f) << "kink at key " << i;
  }
}

TEST(CameraPath, CentripetalHasNoCuspOrLoopOnUnevenSpacing) {
  // The classic case (Yuksel et al. 2011, fig. 1): two close control points between two far ones that lie
  // across each other. Uniform Catmull-Rom makes a loop between the close points (it overshoots past both
  // ends of the chord and turns back); centripetal does not: the segment keeps moving forward along its
  // chord.
  const glm::vec3 p0(3, 0, 0), p1(1, 10, 0), p2(1.5, 10, 0), p3(-0.5, 0, 0);
  const glm::vec3 chord = glm::normalize(p2 - p1);
  float previous = -1.0f;
  float maxOff = 0.0f;
  for (int i = 0; i <= 200; ++i) {
    const float u = static_cast<float>(i) / 200.0f;
    const glm::vec3 p = centripetalCatmullRom(p0, p1, p2, p3, u);
    const float along = glm::dot(p - p1, chord);
    EXPECT_GE(along, previous - 1e-5f) << "goes backwards at u = " << u;
    previous = along;
    maxOff = std::max(maxOff, glm::length((p - p1) - along * chord));
  }
  EXPECT_LT(maxOff, 0.5f * glm::length(p2 - p1));
  // The uniform spline (tangents (p2 − p0)/2, (p3 − p1)/2) does go backwards here: the test can fail.
  auto uniform = [&](float u) {
    const glm::vec3 m1 = 0.5f * (p2 - p0), m2 = 0.5f * (p3 - p1);
    const float u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * p1 + (u3 - 2 * u2 + u) * m1 + (-2 * u3 + 3 * u2) * p2 + (u3 - u2) * m2;
  };
  bool backwards = false;
  for (int i = 1; i <= 200; ++i) {
    const float a = glm::dot(uniform(static_cast<float>(i - 1) / 200.0f) - p1, chord);
    const float b = glm::dot(uniform(static_cast<float>(i) / 200.0f) - p1, chord);
    backwards = backwards || b < a - 1e-5f;
  }
  EXPECT_TRUE(backwards);
}

TEST(CameraPath, StraightEvenKeysGiveAStraightLine) {
  std::vector<WorldCameraKey> keys;
  for (int i = 0; i < 5; ++i) {
    keys.push_back(key(i, {2.0f * i, 5, 0}));
  }
  for (double t = 0.0; t <= 4.0; t += 0.125) {
    const CameraSample s = evaluate(keys, t, false);
    EXPECT_NEAR(s.position.x, 2.0 * t, 1e-4);
    EXPECT_NEAR(s.position.y, 5.0, 1e-5);
    EXPECT_NEAR(s.fov, 50.0f, 1e-5f);
  }
}

TEST(CameraPath, LoopWraps) {
  // A closed square: the last key returns to the first.
  const std::vector<WorldCameraKey> keys{key(0, {0, 1, 0}), key(1, {10, 1, 0}), key(2, {10, 1, 10}),
                                         key(3, {0, 1, 10}), key(4, {0, 1, 0})};
  for (double t : {0.3, 1.7, 2.5, 3.9}) {
    const CameraSample a = evaluate(keys, t, true);
    const CameraSample b = evaluate(keys, t + 4.0, true);
    const CameraSample c = evaluate(keys, t - 8.0, true);
    EXPECT_LT(glm::length(a.position - b.position), 1e-4f);
    EXPECT_LT(glm::length(a.position - c.position), 1e-4f);
  }
  EXPECT_EQ(evaluate(keys, 4.0, true).position, keys[0].position);
  // Smooth through the seam: the direction just before the end matches the one just after the start.
  const double h = 1e-3;
  const glm::vec3 before = glm::normalize(keys[0].position - evaluate(keys, 4.0 - h, true).position);
  const glm::vec3 after = glm::normalize(evaluate(keys, h, true).position - keys[0].position);
  EXPECT_GT(glm::dot(before, after), 0.99f);
  // Without loop the same time clamps.
  EXPECT_EQ(evaluate(keys, 5.0, false).position, keys.back().position);
}

TEST(CameraPath, RefusesBadKeys) {
  EXPECT_THROW((void)evaluate({}, 0.0, false), Error);
  EXPECT_THROW((void)evaluate({key(1, {0, 0, 0}), key(1, {1, 0, 0})}, 0.0, false), Error);
  EXPECT_THROW((void)evaluate({key(0, {0, 0, 0}), key(1, {1, 0, 0})}, std::nan(""), false), Error);
}

TEST(CameraPath, ResolvesAboveGroundPoints) {
  CameraDesc camera;
  CameraKey k;
  k.position = {{10, 2, 20}, true};
  k.target = {{30, 5, 40}, false};
  camera.keys.push_back(k);
  const auto keys = resolveKeys(camera, [](float x, float z) { return x + z; });
  ASSERT_EQ(keys.size(), 1u);
  EXPECT_EQ(keys[0].position, glm::vec3(10, 32, 20));
  EXPECT_EQ(keys[0].target, glm::vec3(30, 5, 40));
  EXPECT_THROW((void)resolveKeys(camera, GroundHeight{}), Error);
}

TEST(CameraPath, TheTimelineEndsWithTheOutputOrTheLongestPath) {
  SceneDesc desc;
  desc.output.fps = 24.0;
  desc.output.lastFrame = 47; // 48 frames: 2 s
  CameraKey key;
  desc.cameras["main"].keys = {key};
  EXPECT_DOUBLE_EQ(timelineEnd(desc), 2.0);
  key.time = 0.5;
  CameraKey last = key;
  last.time = 7.5;
  desc.cameras["fly"].keys = {key, last};
  EXPECT_DOUBLE_EQ(timelineEnd(desc), 7.5);
  desc.output.lastFrame = 239; // 10 s
  EXPECT_DOUBLE_EQ(timelineEnd(desc), 10.0);
}

} // namespace
} // namespace sylva::scene
