// Tree images: one almond tree in its random pose (shaded by the distance rule, and in the piece-type view),
// and a small forest of four species, each from a fixed camera over a plain background.
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/gpu/FoliageRenderer.hpp>
#include <sylva/trees/gpu/ImpostorRenderer.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"
#include "Golden.hpp"

#include <cstdlib>
#include <filesystem>
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

// The trunk above the foot and the first fork of the oak of trees_bark_closeup, close.
render::Camera barkCloseUpCamera() {
  render::Camera camera;
  camera.position = {1.6f, 4.2f, 2.2f};
  camera.target = {0.0f, 4.4f, 0.0f};
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 0.05f;
  camera.farPlane = 100.0f;
  return camera;
}

TEST_F(TreeGolden, BarkTilesCloseUp) {
  // Procedural bark (no photos needed): the tile rule, rotations and seams at a trunk and a fork, close.
  auto forest = std::make_shared<Forest>(gridForest({"california-black-oak"}, 1, 1.0f, 4));
  TreeRenderer renderer(shaders(), forest);
  BarkSources sources;
  sources.mode = "procedural";
  std::vector<int> speciesSet;
  renderer.setBark(barkSetsFor(*forest, sources, speciesSet), speciesSet);
  const render::Camera camera = barkCloseUpCamera();
  test::expectGolden(render(renderer, camera, TreeView::Shaded), "trees_bark_closeup", kTreeTolerance);
}

// Bark synthesised from ez-tree's oak photo and normal map for `forest` (its first set must be the oak's).
std::vector<BarkSet> oakPhotoBark(const Forest& forest, std::vector<int>& speciesSet) {
  BarkSources sources;
  sources.photoDir = test::externalData("ez-tree/bark/oak_color_1k.jpg").parent_path();
  std::vector<BarkSet> sets = barkSetsFor(forest, sources, speciesSet);
  EXPECT_EQ(sets[0].name, "oak");
  return sets;
}

// One oak and an apple tree behind it with photo bark and foliage impostors of ez-tree's oak leaf (leaves
// depth-tested against each other and the branches), width × height.
Image leafyOak(const shader::Library& library, int width, int height) {
  auto forest = std::make_shared<Forest>(gridForest({"california-black-oak", "apple"}, 2, 4.0f, 11));
  forest->trees.resize(2);
  forest->index();
  TreeRenderer renderer(library, forest);
  std::vector<int> speciesSet;
  renderer.setBark(oakPhotoBark(*forest, speciesSet), speciesSet);
  FoliageRenderer foliage(library, forest);
  foliage.setLeafTexture(loadLeafImage(test::externalData("ez-tree/leaves/oak_color.png")));
  render::Camera camera;
  camera.position = {-7.0f, 5.0f, 19.0f};
  camera.target = {1.0f, 6.0f, 0.0f};
  camera.fovY = glm::radians(55.0f);
  camera.nearPlane = 0.1f;
  camera.farPlane = 200.0f;
  render::RenderTarget target(width, height);
  target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
  const TreeLod lod;
  renderer.cull(camera, target.aspect(), lod);
  renderer.draw(camera, width, height, 0.0, lod);
  foliage.bake(camera);
  foliage.draw(camera, width, height, 0.0, renderer, lod);
  return target.readColor();
}

TEST_F(TreeGolden, LeafyOakWithPhotoBarkAndLeaves) {
  // The real thing: bark tiles synthesised from ez-tree's oak photo and normal map, foliage impostors of its
  // oak leaf.
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("ez-tree/bark/oak_color_1k.jpg"));
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("ez-tree/leaves/oak_color.png"));
  test::expectGolden(leafyOak(shaders(), 320, 240), "trees_leafy_oak", kTreeTolerance);
}

TEST_F(TreeGolden, DocumentationPictures) {
  // docs/trees.md "Pictures": the bark close-ups (photo bark and flat colours, at the camera of
  // trees_bark_closeup), the leafy oak at 960 × 720 and an almond's impostor atlas, into a directory.
  const char* dir = std::getenv("SYLVA_TREE_PICTURES");
  if (dir == nullptr) {
    GTEST_SKIP() << "set SYLVA_TREE_PICTURES=<directory> to render the documentation pictures";
  }
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("ez-tree/bark/oak_color_1k.jpg"));
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("ez-tree/leaves/oak_color.png"));
  const std::filesystem::path out(dir);
  {
    auto forest = std::make_shared<Forest>(gridForest({"california-black-oak"}, 1, 1.0f, 4));
    TreeRenderer renderer(shaders(), forest);
    const render::Camera camera = barkCloseUpCamera();
    auto closeUp = [&] {
      render::RenderTarget target(480, 720);
      target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      const TreeLod lod;
      renderer.cull(camera, target.aspect(), lod);
      renderer.draw(camera, 480, 720, 0.0, lod);
      return target.readColor();
    };
    saveImage(out / "bark-flat-closeup.png", closeUp());
    std::vector<int> speciesSet;
    renderer.setBark(oakPhotoBark(*forest, speciesSet), speciesSet);
    saveImage(out / "bark-oak-closeup.png", closeUp());
  }
  saveImage(out / "leafy-oak.png", leafyOak(shaders(), 960, 720));
  {
    auto forest = std::make_shared<Forest>(gridForest({"almond"}, 1, 1.0f, 4));
    std::vector<int> speciesSet;
    const std::vector<BarkSet> bark = oakPhotoBark(*forest, speciesSet);
    const Image leaf = loadLeafImage(test::externalData("ez-tree/leaves/oak_color.png"));
    ImpostorRenderer impostors(shaders());
    impostors.bake(*forest, sceneBakeOptions(shaders(), bark, speciesSet, true, &leaf));
    saveImage(out / "impostor-atlas.png", impostors.readAtlas(0));
  }
}

TEST_F(TreeGolden, ForestToTheHorizon) {
  // 36 trees as pieces (procedural bark, foliage) and 20,000 impostor-only trees out to 1.5 km, from eye
  // height; trees between 30 and 45 m dissolve into their impostors. Ground and sky are two clear colours
  // split at the horizon (the camera looks level, so the horizon is the middle row).
  auto forest = std::make_shared<Forest>(gridForest({"almond", "apple"}, 6, 8.0f, 12));
  TreeRenderer renderer(shaders(), forest);
  BarkSources sources;
  sources.mode = "procedural";
  std::vector<int> speciesSet;
  const std::vector<BarkSet> bark = barkSetsFor(*forest, sources, speciesSet);
  renderer.setBark(bark, speciesSet);
  FoliageRenderer foliage(shaders(), forest);
  ImpostorSettings settings;
  settings.layout.views = 6;
  settings.layout.cell = 64;
  ImpostorRenderer impostors(shaders(), settings);
  impostors.bake(*forest, sceneBakeOptions(shaders(), bark, speciesSet, true));
  std::vector<FarTree> far = farTrees(*forest);
  FarTreeFieldSettings field;
  field.count = 20000;
  field.innerRadius = 40.0f;
  field.outerRadius = 1500.0f;
  field.species = 2;
  field.firstId = static_cast<std::uint32_t>(forest->trees.size());
  const std::vector<FarTree> extra = farTreeField(field);
  far.insert(far.end(), extra.begin(), extra.end());
  impostors.setTrees(far);
  render::Camera camera;
  camera.position = {-32.0f, 1.7f, -26.0f};
  camera.target = {10.0f, 1.7f, 20.0f};
  camera.fovY = glm::radians(60.0f);
  camera.nearPlane = 0.2f;
  camera.farPlane = 3000.0f;
  render::RenderTarget target(320, 240);
  target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 320, 120);
  glClearColor(0.36f, 0.45f, 0.22f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  TreeLod lod;
  lod.farRange = glm::vec2(30.0f, 45.0f);
  renderer.cull(camera, target.aspect(), lod);
  renderer.draw(camera, 320, 240, 0.0, lod);
  foliage.bake(camera);
  foliage.draw(camera, 320, 240, 0.0, renderer, lod);
  impostors.draw(camera, 320, 240, 0.0, lod.farRange);
  EXPECT_GT(impostors.readVisibleCount(), 1000u);
  test::expectGolden(target.readColor(), "trees_forest_horizon", kTreeTolerance);
}

} // namespace
} // namespace sylva::trees
