// ui::CameraRig: which camera the viewer looks through and how mouse and keys move it, without a window.
#include <sylva/ui/CameraRig.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::ui {
namespace {

/** A world with one named camera ("tower", looking at the origin) and a ground plane at y = 10 m. */
CameraRig::World towerWorld(int* namedCalls = nullptr) {
  CameraRig::World w;
  w.namedCamera = [namedCalls](const std::string& name, float) {
    if (namedCalls != nullptr) {
      ++*namedCalls;
    }
    render::Camera c;
    c.position = name == "tower" ? glm::vec3(0.0f, 50.0f, -100.0f) : glm::vec3(100.0f, 20.0f, 0.0f);
    c.target = glm::vec3(0.0f);
    c.fovY = 0.7f;
    return c;
  };
  w.groundHeight = [](float, float) { return 10.0f; };
  return w;
}

render::Camera startCamera() {
  render::Camera c;
  c.position = glm::vec3(0.0f, 30.0f, 60.0f);
  c.target = glm::vec3(0.0f);
  c.fovY = 1.0f;
  c.nearPlane = 0.2f;
  c.farPlane = 900.0f;
  return c;
}

constexpr glm::vec3 kForward(0.0f, 0.0f, 1.0f);

TEST(CameraRig, StartsAtTheNamedCameraOrOrbitsTheStart) {
  const CameraRig atTower({"tower", "field"}, "tower", startCamera(), towerWorld(), 1.5f);
  EXPECT_TRUE(atTower.named());
  EXPECT_EQ(atTower.camera().position, glm::vec3(0.0f, 50.0f, -100.0f));
  const CameraRig unknown({"tower"}, "nowhere", startCamera(), towerWorld(), 1.5f);
  EXPECT_FALSE(unknown.named());
  EXPECT_FALSE(unknown.flying());
  EXPECT_EQ(unknown.camera().position, startCamera().position);
}

TEST(CameraRig, MovingLeavesTheNamedCameraForFlyAndFGoesBack) {
  CameraRig rig({"tower"}, "tower", startCamera(), towerWorld(), 1.5f);
  const platform::InputState still;
  rig.update(still, glm::vec3(0.0f), true, 0.1f, 1.5f);
  EXPECT_TRUE(rig.named());
  const glm::vec3 before = rig.camera().position;
  rig.flySpeed = 10.0f;
  const render::Camera& moved = rig.update(still, kForward, true, 0.5f, 1.5f);
  EXPECT_TRUE(rig.flying());
  // Flying starts where the named camera was, looking its way: 5 m towards the origin.
  const glm::vec3 towards = glm::normalize(glm::vec3(0.0f) - before);
  EXPECT_NEAR(glm::dot(moved.position - before, towards), 5.0f, 1e-3f);
  EXPECT_FLOAT_EQ(moved.fovY, 0.7f); // the named camera's field of view
  rig.toggleFly();
  EXPECT_TRUE(rig.named());
  rig.update(still, glm::vec3(0.0f), true, 0.1f, 1.5f);
  EXPECT_EQ(rig.camera().position, before);
}

TEST(CameraRig, WalkingKeepsTheEyeAboveTheGround) {
  CameraRig rig({}, "", startCamera(), towerWorld(), 1.5f);
  rig.toggleWalk();
  EXPECT_TRUE(rig.flying());
  EXPECT_TRUE(rig.walking());
  const platform::InputState still;
  for (int i = 0; i < 5; ++i) {
    const render::Camera& c = rig.update(still, kForward, true, 0.25f, 1.5f);
    EXPECT_FLOAT_EQ(c.position.y, 10.0f + CameraRig::kWalkEyeHeight);
    EXPECT_FLOAT_EQ(c.nearPlane, 0.2f); // free cameras keep the start's planes until the viewer fits them
  }
  rig.toggleFly(); // F from walking: back to the orbit, walking off
  EXPECT_FALSE(rig.flying());
  EXPECT_FALSE(rig.walking());
}

TEST(CameraRig, WithoutGroundThereIsNoFlying) {
  CameraRig rig({}, "", startCamera(), CameraRig::World{}, 1.5f);
  EXPECT_FALSE(rig.flyAllowed());
  rig.toggleFly();
  rig.toggleWalk();
  const platform::InputState still;
  rig.update(still, kForward, true, 1.0f, 1.5f);
  EXPECT_FALSE(rig.flying());
  EXPECT_FALSE(rig.walking());
  EXPECT_NEAR(glm::length(rig.camera().position - startCamera().position), 0.0f, 1e-3f);
}

TEST(CameraRig, TheOrbitRotatesOnlyWhenTheMouseIsFreeAndZoomStopsAtItsLimits) {
  CameraRig rig({}, "", startCamera(), towerWorld(), 1.5f);
  rig.setOrbitLimits(20.0f, 80.0f);
  platform::InputState drag;
  drag.mouseLeft = true;
  drag.cursorDelta = glm::dvec2(40.0, 0.0);
  const glm::vec3 start = rig.camera().position;
  rig.update(drag, glm::vec3(0.0f), false, 0.1f, 1.5f);
  EXPECT_NEAR(glm::length(rig.camera().position - start), 0.0f, 1e-3f) << "dragged over a panel";
  rig.update(drag, glm::vec3(0.0f), true, 0.1f, 1.5f);
  EXPECT_GT(glm::length(rig.camera().position - start), 1.0f);
  platform::InputState wheel;
  wheel.scrollDelta = 100.0; // far in
  rig.update(wheel, glm::vec3(0.0f), true, 0.1f, 1.5f);
  EXPECT_NEAR(glm::length(rig.camera().position - rig.camera().target), 20.0f, 1e-3f);
  wheel.scrollDelta = -100.0; // far out
  rig.update(wheel, glm::vec3(0.0f), true, 0.1f, 1.5f);
  EXPECT_NEAR(glm::length(rig.camera().position - rig.camera().target), 80.0f, 1e-2f);
  EXPECT_FALSE(rig.flying());
}

TEST(CameraRig, NamedCamerasAreAskedEveryFrameAtTheWorldsTime) {
  int calls = 0;
  CameraRig rig({"tower"}, "tower", startCamera(), towerWorld(&calls), 1.5f);
  const int atStart = calls;
  const platform::InputState still;
  for (int i = 0; i < 3; ++i) {
    rig.update(still, glm::vec3(0.0f), true, 0.1f, 1.5f);
  }
  EXPECT_EQ(calls - atStart, 3);
}

} // namespace
} // namespace sylva::ui
