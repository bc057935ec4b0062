// scene/Viewpoints.hpp: balls go on the steepest grassy slope a ball can roll down and the camera watches
// them from downhill; the grass and forest start cameras.
#include <sylva/grass/BladeType.hpp>
#include <sylva/scene/Viewpoints.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/Tree.hpp>

#include <glm/trigonometric.hpp>

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

TEST(Viewpoints, BallsGoOnTheSteepestGrassySlopeTheyCanRollDown) {
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

TEST(Viewpoints, TheCameraWatchesFromDownhillAtEyeHeight) {
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

TEST(Viewpoints, TheGrassCameraStandsAtEyeHeightInTheGrassLookingAcrossTheWind) {
  const terrain::HeightField flat(81, 81, 1.0f, 1.0f, 3.0f);
  const Aabb bounds{glm::vec3(0.0f, 3.0f, 0.0f), glm::vec3(80.0f, 3.0f, 80.0f)};
  const render::Camera c = grassCamera(flat, bounds, 3.0f, meadow(flat, 1.0f), 0.9f, 0.0f);
  EXPECT_NEAR(c.position.y, 3.0f + 1.7f, 1e-4f);
  EXPECT_GE(c.position.x, 20.0f); // the middle half
  EXPECT_LE(c.position.x, 60.0f);
  EXPECT_GE(c.position.z, 20.0f);
  EXPECT_LE(c.position.z, 60.0f);
  // 25 m along the wind (0°) turned 35°, a metre below the ground there: slightly down.
  const glm::vec3 d = c.target - c.position;
  EXPECT_NEAR(std::atan2(d.z, d.x), glm::radians(35.0f), 1e-3f);
  EXPECT_NEAR(glm::length(glm::vec2(d.x, d.z)), 25.0f, 1e-3f);
  EXPECT_NEAR(d.y, -2.7f, 1e-4f);
  EXPECT_FLOAT_EQ(c.nearPlane, 0.05f);
  EXPECT_FLOAT_EQ(c.fovY, 0.9f);
}

TEST(Viewpoints, TheForestCameraLooksAtTheTreeNearestTheCentre) {
  const terrain::HeightField flat(81, 81, 1.0f, 1.0f, 2.0f);
  render::Camera base;
  base.position = glm::vec3(-50.0f, 80.0f, -50.0f);
  EXPECT_EQ(forestCamera(flat, 1.0f, base, trees::Forest{}, 0.7f).position, base.position) << "no trees";

  trees::Forest forest;
  forest.pieces = trees::standardPieces();
  forest.species = {trees::speciesPreset("quaking-aspen")};
  for (const glm::vec3 at : {glm::vec3(10.0f, 2.0f, 10.0f), glm::vec3(42.0f, 2.0f, 38.0f)}) {
    trees::ForestTree tree;
    tree.topology = trees::generateTree(forest.pieces, forest.species[0], 5);
    tree.species = 0;
    tree.base = trees::baseFrame(at, 0.0f, forest.species[0].trunkRadius);
    forest.trees.push_back(std::move(tree));
  }
  forest.index();
  const render::Camera c = forestCamera(flat, 1.0f, base, forest, 0.7f);
  EXPECT_NEAR(c.target.x, 42.0f, 1e-3f); // the tree by (40, 40)
  EXPECT_NEAR(c.target.z, 38.0f, 1e-3f);
  EXPECT_GT(c.target.y, 2.0f); // part way up the tree
  EXPECT_NEAR(c.position.y, 2.0f + 2.5f, 1e-3f);
  const float distance = glm::length(glm::vec2(c.position.x - 42.0f, c.position.z - 38.0f));
  EXPECT_GE(distance, 8.0f);
  EXPECT_LE(distance, 60.0f);
  EXPECT_GT(c.position.x, 42.0f); // from +x+z
  EXPECT_GT(c.position.z, 38.0f);
  EXPECT_FLOAT_EQ(c.fovY, 0.7f);
}

} // namespace
} // namespace sylva::scene
