// The Bullet world on a terrain: bodies rest on the heightfield where the terrain draws it, roll downhill,
// export their shapes for the grass; bad bodies are one-line errors; the same calls give the same states.
#include <sylva/core/Error.hpp>
#include <sylva/physics/World.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

namespace sylva::physics {
namespace {

/** A plane rising towards +x with slope `grade` (rise over run), 1 m samples. */
terrain::HeightField ramp(float grade, int size = 65) {
  terrain::HeightField f(size, size, 1.0f, 1.0f);
  for (int j = 0; j < size; ++j) {
    for (int i = 0; i < size; ++i) {
      f.at(i, j) = 10.0f + grade * static_cast<float>(i);
    }
  }
  return f;
}

TEST(Physics, SphereRestsOnTheTerrainWhereItIsDrawn) {
  const terrain::HeightField flat = ramp(0.0f);
  World world(flat);
  BodySpec ball;
  ball.size = glm::vec3(0.4f);
  ball.position = {30.0f, 13.0f, 20.0f};
  world.addBody(ball);
  world.step(3.0f);
  const BodyState s = world.body(0);
  EXPECT_NEAR(s.position.y, 10.0f + 0.4f, 0.01f);
  EXPECT_NEAR(s.position.x, 30.0f, 0.01f);
  EXPECT_NEAR(s.position.z, 20.0f, 0.01f);
  EXPECT_NEAR(world.time(), 3.0, 1e-3);
}

TEST(Physics, BallsRollDownhillAndExportTheirShapes) {
  const terrain::HeightField slope = ramp(0.3f);
  World world(slope);
  BodySpec ball;
  ball.size = glm::vec3(0.3f);
  ball.position = {40.0f, 10.0f + 0.3f * 40.0f + 0.5f, 30.0f};
  world.addBody(ball);
  BodySpec capsule;
  capsule.shape = Shape::Capsule;
  capsule.size = {0.2f, 0.5f, 0.0f};
  capsule.position = {20.0f, 30.0f, 30.0f};
  capsule.mass = 5.0f;
  world.addBody(capsule);
  world.step(2.0f);
  const BodyState s = world.body(0);
  // A rolling sphere accelerates at 5/7 g sin θ (2.0 m/s² here): about 3.7 m in 2 s after its drop.
  EXPECT_LT(s.position.x, 37.0f) << "rolled towards −x, downhill";
  EXPECT_LT(s.velocity.x, -1.0f);
  // On the ground at its position (within the heightfield's triangulation of the bilinear surface).
  EXPECT_NEAR(s.position.y, terrain::heightAt(slope, s.position.x, s.position.z) + 0.3f * std::sqrt(1.09f),
              0.05f);
  const std::vector<ShapeExport> shapes = world.shapes();
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_EQ(shapes[0].a, shapes[0].b);
  EXPECT_FLOAT_EQ(shapes[0].radius, 0.3f);
  EXPECT_GT(shapes[0].mass, 0.0f);
  EXPECT_NEAR(glm::length(shapes[1].b - shapes[1].a), 1.0f, 1e-4f);
  EXPECT_LE(shapes[0].box.min.x, s.position.x - 0.29f);
  EXPECT_GE(shapes[0].box.max.y, s.position.y + 0.29f);
}

TEST(Physics, SameCallsSameStates) {
  const terrain::HeightField slope = ramp(0.2f);
  auto run = [&] {
    World world(slope);
    for (const BodySpec& b : seededBalls(slope, {30.0f, 30.0f}, 10.0f, 12, 7)) {
      world.addBody(b);
    }
    for (int i = 0; i < 90; ++i) {
      world.step(1.0f / 60.0f);
    }
    std::vector<glm::vec3> out;
    for (std::size_t i = 0; i < world.bodyCount(); ++i) {
      out.push_back(world.body(static_cast<int>(i)).position);
    }
    return out;
  };
  EXPECT_EQ(run(), run());
}

TEST(Physics, BadBodiesAreOneLineErrors) {
  World world(ramp(0.0f, 9));
  const auto message = [&](const BodySpec& b) {
    try {
      world.addBody(b, "balls[3]");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  BodySpec nan;
  nan.position.x = std::nanf("");
  EXPECT_NE(message(nan).find("balls[3]: position"), std::string::npos);
  BodySpec zero;
  zero.size = glm::vec3(0.0f);
  EXPECT_NE(message(zero).find("balls[3]: size"), std::string::npos);
  BodySpec heavy;
  heavy.mass = -1.0f;
  EXPECT_NE(message(heavy).find("balls[3]: mass"), std::string::npos);
  BodySpec huge;
  huge.size = glm::vec3(1e6f);
  EXPECT_NE(message(huge).find("absurd"), std::string::npos);
  EXPECT_THROW(World(ramp(0.0f, 9), std::nanf("")), Error);
  EXPECT_THROW(seededBalls(ramp(0.0f, 9), {}, 1.0f, -1, 1), Error);
  EXPECT_EQ(world.bodyCount(), 0u);
}

} // namespace
} // namespace sylva::physics
