// The world the engine composes from a description built in code, as `sylva render --trees` builds it: the
// forest casts sun shadows on the terrain through the scene's one frame (the shadow pass darkens the ground
// around the trees and brightens nothing), the code-only fields reach the world (the region around the
// terrain's centre, the look), and the same time gives the same pixels.
#include <sylva/render/RenderTarget.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>

#include "GlTest.hpp"

#include <glm/geometric.hpp>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>

namespace sylva::scene {
namespace {

using SceneWorldTest = test::GlTest;

constexpr int kWidth = 192;
constexpr int kHeight = 108;

/** A 256 m procedural terrain with a forest of 40 trees within 30 m of its centre, as the command line does.
 */
SceneDesc forestDesc() {
  SceneDesc d;
  d.path = "test";
  d.name = "test";
  terrain::TerrainSetup t;
  t.source.proceduralSize = 129;
  t.source.proceduralSpacing = 2.0f;
  t.source.procedural.heightScale = 20.0f;
  t.seaLevel.kind = terrain::SeaLevelRule::Kind::None;
  d.terrain.setup = t;
  ForestDesc f;
  f.species = {{"almond", 1.0f}};
  f.count = 40;
  f.seed = 3;
  f.spacing = 3.0f;
  f.maxSlope = 60.0f;
  f.bare = 0.0f;
  f.regionRadius = 30.0f;
  f.regionAroundCentre = true;
  trees::ForestLook look;
  look.bark = "procedural";
  look.foliage = false;
  f.look = look;
  f.wind = false;
  d.forests.push_back(f);
  d.sun.elevation = 30.0f;
  d.shadows.distance = 150.0f;
  d.fog.density = 0.0f;
  return d;
}

/** Looking down at the forest's middle from the south-west, 25 m away. */
render::Camera forestCamera(SceneWorld& world) {
  const float c = 128.0f;
  render::Camera camera;
  camera.target = glm::vec3(c, world.groundHeight(c, c), c);
  camera.position = camera.target + glm::vec3(-14.0f, 16.0f, 14.0f);
  camera.fovY = glm::radians(50.0f);
  render::fitClipPlanes(camera, world.terrain().bounds());
  return camera;
}

Image draw(SceneWorld& world, const render::Camera& camera) {
  render::RenderTarget target(kWidth, kHeight);
  target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  world.draw(camera, kWidth, kHeight, 1.0, &target.depth(), nullptr);
  return target.readColor();
}

float luminance(const Image& image, int x, int y) {
  return 0.2126f * image.get(x, y, 0) + 0.7152f * image.get(x, y, 1) + 0.0722f * image.get(x, y, 2);
}

TEST_F(SceneWorldTest, ACodeBuiltForestCastsSunShadowsThroughTheScenesFrame) {
  SceneWorld world(shaders(), forestDesc());
  ASSERT_GE(world.treeCount(), 20u);
  // Every tree stands within the region around the terrain's centre (the code-only rule).
  for (const trees::ForestTree& t : world.forest(0).forest().trees) {
    EXPECT_LE(glm::length(glm::vec2(t.base[3].x, t.base[3].z) - glm::vec2(128.0f)), 30.0f + 1e-3f);
  }
  const render::Camera camera = forestCamera(world);
  const Image shadowed = draw(world, camera);
  world.passes().setEnabled(Pass::Shadows, false);
  const Image lit = draw(world, camera);
  std::size_t darker = 0;
  std::size_t brighter = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const float d = luminance(shadowed, x, y) - luminance(lit, x, y);
      darker += d < -10.0f / 255.0f ? 1 : 0;
      brighter += d > 2.0f / 255.0f ? 1 : 0;
    }
  }
  const std::size_t pixels = static_cast<std::size_t>(kWidth) * kHeight;
  EXPECT_GT(darker, pixels / 100) << "the trees and terrain cast too little shadow";
  EXPECT_LT(brighter, pixels / 1000) << "shadows only darken";
  // A fixed clock: the same time gives the same pixels.
  world.passes().setEnabled(Pass::Shadows, true);
  const Image again = draw(world, camera);
  EXPECT_EQ(std::memcmp(again.data(), shadowed.data(), shadowed.byteSize()), 0);
}

} // namespace
} // namespace sylva::scene
