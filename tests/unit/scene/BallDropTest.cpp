// scene::ballDropPoint and ballCamera: balls go on the steepest grassy slope a ball can roll down, and the
// camera watches them from downhill.
#include <sylva/grass/BladeType.hpp>
#include <sylva/scene/BallDrop.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::scene {
namespace {

/** 81 × 81 m rising in +x: 11.3° (a 0.2 grade) up to x = 40 m, 35° (0.7) beyond. */
terrain::HeightField twoSlopes() {
  terrain::HeightField t(81, 81, 1.0f, 1.0f);
  for (int j = 0; j < 81; ++j) {
    for (int i = 0; i < 81; ++i) {
      t.at(i, j) = i <= 40 ? 0.2f * static_cast<float>(i) : 8.0f + 0.7f * static_cast<float>(i - 40);
    }
  }
  return t;
}

grass::GrassField meadow(const terrain::HeightField& t, float density) {
  grass::FieldSettings fs;
  fs.patch.blades = 1024;
  fs.bladesPerTile = 32;
  fs.density.base = density;
  fs.density.coverage = 1.0f;
  fs.density.maxSlopeDegrees =
      60.0f; // grass on both slopes: the 25° rule alone must keep balls off the steep one
  return grass::GrassField(t, grass::proceduralBladeTypes(), fs);
}

float slopeDegrees(const terrain::HeightField& t, glm::vec2 p) {
  return std::acos(terrain::normalAt(t, p.x, p.y).y) * 57.29578f;
}

TEST(BallDrop, BallsGoOnTheSteepestGrassySlopeTheyCanRollDown) {
  const terrain::HeightField t = twoSlopes();
  render::Camera camera;
  camera.position = glm::vec3(40.0f, 20.0f, 40.0f);
  const glm::vec2 drop = ballDropPoint(t, meadow(t, 1.0f), camera);
  // The steepest place at most 25°: the foot of the steep slope, where the grades meet (24°), never on it.
  EXPECT_LE(drop.x, 40.0f) << "dropped on the 35° slope";
  EXPECT_LE(slopeDegrees(t, drop), 25.0f);
  EXPECT_GT(slopeDegrees(t, drop), 20.0f);
  EXPECT_LE(glm::length(drop - glm::vec2(40.0f)), 40.0f);
  // No grass anywhere: the camera's own place.
  EXPECT_EQ(ballDropPoint(t, meadow(t, 0.0f), camera), glm::vec2(40.0f, 40.0f));
}

TEST(BallDrop, TheCameraWatchesFromDownhillAtEyeHeight) {
  const terrain::HeightField t = twoSlopes();
  const Aabb bounds{glm::vec3(0.0f), glm::vec3(80.0f, 36.0f, 80.0f)};
  const glm::vec2 drop(30.0f, 40.0f);
  const render::Camera c = ballCamera(t, bounds, drop, 0.8f);
  EXPECT_NEAR(c.position.x, 21.0f, 1e-3f);        // 9 m downhill (−x)
  EXPECT_NEAR(c.position.z, 40.0f - 2.5f, 1e-3f); // and 2.5 m to the side, so they roll past at an angle
  EXPECT_NEAR(c.position.y, terrain::heightAt(t, c.position.x, c.position.z) + 1.8f, 1e-3f);
  EXPECT_NEAR(c.target.x, 26.0f, 1e-3f); // looking back up the slope
  EXPECT_GT(c.target.y, c.position.y - 1.8f);
  EXPECT_FLOAT_EQ(c.fovY, 0.8f);
  EXPECT_FLOAT_EQ(c.nearPlane, 0.05f);
  EXPECT_GT(c.farPlane, 80.0f);
}

} // namespace
} // namespace sylva::scene
