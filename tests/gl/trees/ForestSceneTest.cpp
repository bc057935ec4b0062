// trees::ForestScene, the forest as one drawable pass: the same scene time gives the same picture (also after
// resetWind, and in a second scene), the wind moves the trees (the control), its bounds hold every tree, and
// the depth-only view used by shadow casters draws the foliage too.
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>

#include "GlTest.hpp"

#include <glm/trigonometric.hpp>

#include <memory>

namespace sylva::trees {
namespace {

using ForestSceneTest = test::GlTest;

render::Camera forestView() {
  render::Camera camera;
  camera.position = glm::vec3(-12.0f, 5.0f, 16.0f);
  camera.target = glm::vec3(3.0f, 3.0f, 3.0f);
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 0.1f;
  camera.farPlane = 300.0f;
  return camera;
}

constexpr int kW = 240;
constexpr int kH = 160;

struct Drawn {
  Image colour;
  Image depth;
};

Drawn draw(ForestScene& scene, double time, TreeView view = TreeView::Shaded) {
  render::RenderTarget target(kW, kH);
  target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  scene.advance(time, wind::WindSettings{}, 1 << 20);
  TreeDrawOptions options;
  options.view = view;
  scene.draw(forestView(), kW, kH, time, TreeLod{}, options);
  return {target.readColor(), target.readDepth()};
}

int changedPixels(const Image& a, const Image& b) {
  int changed = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      bool differs = false;
      for (int c = 0; c < a.channels(); ++c) {
        differs = differs || a.get(x, y, c) != b.get(x, y, c);
      }
      changed += differs ? 1 : 0;
    }
  }
  return changed;
}

TEST_F(ForestSceneTest, TheSameTimeGivesTheSamePictureAndTheWindMovesTheTrees) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "california-black-oak"}, 2, 6.0f, 5));
  ForestScene scene(shaders(), forest, true);
  scene.setFoliage(true);
  const Image first = draw(scene, 2.5).colour;
  // A later time: the springs have moved the crowns (the control: the comparison below can fail).
  const Image later = draw(scene, 3.5).colour;
  EXPECT_GT(changedPixels(first, later), 200);
  // Back at rest and stepped to the first time again: the same state, the same picture.
  scene.resetWind();
  EXPECT_TRUE(draw(scene, 2.5).colour == first);
  // A second scene of the same forest agrees.
  ForestScene other(shaders(), forest, true);
  other.setFoliage(true);
  EXPECT_TRUE(draw(other, 2.5).colour == first);
  // Without wind the rest pose: different from the swaying trees.
  scene.setWind(false);
  EXPECT_GT(changedPixels(draw(scene, 2.5).colour, first), 200);
}

TEST_F(ForestSceneTest, DepthViewCastsTheFoliageToo) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "california-black-oak"}, 2, 6.0f, 5));
  ForestScene scene(shaders(), forest, false);
  scene.setFoliage(false);
  const Image bare = draw(scene, 0.0, TreeView::Depth).depth;
  scene.setFoliage(true);
  const Image leafy = draw(scene, 0.0, TreeView::Depth).depth;
  const Image shaded = draw(scene, 0.0, TreeView::Shaded).depth;
  int covered = 0;
  int bareCovered = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      covered += leafy.get(x, y, 0) < 1.0f ? 1 : 0;
      bareCovered += bare.get(x, y, 0) < 1.0f ? 1 : 0;
    }
  }
  // The crowns' leaves cover much more than the bare branches, and the depth equals the shaded draw's.
  EXPECT_GT(covered, 2 * bareCovered);
  EXPECT_TRUE(leafy == shaded);
}

TEST_F(ForestSceneTest, BoundsHoldEveryTree) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "european-larch"}, 3, 7.0f, 9));
  const ForestScene scene(shaders(), forest, false);
  const Aabb& box = scene.bounds();
  std::vector<gpu::JointFrame> frames;
  forestFrames(*forest, {}, frames);
  ASSERT_FALSE(frames.empty());
  for (const gpu::JointFrame& f : frames) {
    const glm::vec3 p(f.x.w, f.y.w, f.z.w);
    EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, box.min + glm::vec3(2.0f))) &&
                glm::all(glm::lessThanEqual(p, box.max - glm::vec3(2.0f))))
        << "joint at " << p.x << ", " << p.y << ", " << p.z;
  }
  // Empty forest: a zero box.
  const Aabb empty = forestBounds(Forest{});
  EXPECT_EQ(empty.min, glm::vec3(0.0f));
  EXPECT_EQ(empty.max, glm::vec3(0.0f));
}

} // namespace
} // namespace sylva::trees
