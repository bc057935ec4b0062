// Tree images: one almond tree in its random pose (shaded by the distance rule, and in the piece-type view),
// and a small forest of four species, each from a fixed camera over a plain background.
#include <sylva/render/RenderTarget.hpp>
#include <sylva/trees/TreeRenderer.hpp>

#include "GlTest.hpp"
#include "Golden.hpp"

#include <memory>

namespace sylva::trees {
namespace {

using TreeGolden = test::GlTest;

Image render(TreeRenderer& renderer, const render::Camera& camera, TreeView view, const TreeLod& lod = {}) {
  render::RenderTarget target(320, 240);
  target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
  renderer.cull(camera, target.aspect(), lod);
  TreeDrawOptions options;
  options.view = view;
  renderer.draw(camera, 320, 240, 0.0, lod, nullptr, options);
  return target.readColor();
}

// Tolerance: tessellated silhouettes of thin twigs move by a pixel with one rounding difference in the
// rasteriser; up to 8 levels on at most 1 % of the pixels.
const render::Tolerance kTreeTolerance{8, 0.01};

TEST_F(TreeGolden, OneAlmondTreeShadedAndPieceTypes) {
  auto forest = std::make_shared<Forest>(gridForest({"almond"}, 1, 1.0f, 4));
  TreeRenderer renderer(shaders(), forest);
  render::Camera camera;
  camera.position = {2.0f, 2.0f, 2.6f};
  camera.target = {0.0f, 1.8f, 0.0f};
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 0.05f;
  camera.farPlane = 100.0f;
  test::expectGolden(render(renderer, camera, TreeView::Shaded), "trees_almond_shaded", kTreeTolerance);
  test::expectGolden(render(renderer, camera, TreeView::PieceTypes), "trees_almond_pieces", kTreeTolerance);
}

TEST_F(TreeGolden, SmallForestOfFourSpecies) {
  auto forest = std::make_shared<Forest>(
      gridForest({"california-black-oak", "weeping-willow", "quaking-aspen", "apple"}, 3, 5.0f, 9));
  TreeRenderer renderer(shaders(), forest);
  render::Camera camera;
  camera.position = {-6.0f, 3.5f, 9.0f};
  camera.target = {0.5f, 1.8f, 0.0f};
  camera.fovY = glm::radians(55.0f);
  camera.nearPlane = 0.1f;
  camera.farPlane = 200.0f;
  test::expectGolden(render(renderer, camera, TreeView::Shaded), "trees_forest_shaded", kTreeTolerance);
}

} // namespace
} // namespace sylva::trees
