// Bark tiles on the GPU against the CPU rules (docs/trees.md "Bark"): every drawn fragment shows the tile
// chooseTile() picks for its piece instance and quad, among the tiles of the quad's class; textured drawing
// is deterministic and differs from the flat colours; invalid tile sets are refused.
#include <sylva/core/Error.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include "GlTest.hpp"

#include <set>

namespace sylva::trees {
namespace {

class BarkTilesTest : public test::GlTest {
protected:
  /** Draws the tile-id view with a solid set of `colours` edge colours; every fragment is checked. */
  void expectTilesAsTheCpu(int colours);
};

render::Camera barkCloseUp(glm::vec3 from, glm::vec3 to) {
  render::Camera camera;
  camera.position = from;
  camera.target = to;
  camera.fovY = glm::radians(45.0f);
  camera.nearPlane = 0.1f;
  camera.farPlane = 200.0f;
  return camera;
}

/**
 * Solid tiles of size 8, each its own colour. One edge colour: 8 tiles (class 0: 4, class 1: 2, class 2: 2);
 * two edge colours: 3 classes × 16 colourings × 1 tile.
 */
BarkSet solidSet(const std::string& name, int shift, int edgeColours = 1) {
  BarkSet set;
  set.name = name;
  set.tileSize = 8;
  set.edgeColours = edgeColours;
  const int tiles = edgeColours == 1 ? 8 : 48;
  for (int i = 0; i < tiles; ++i) {
    Image tile(8, 8, 3, PixelType::U8);
    for (int y = 0; y < 8; ++y) {
      for (int x = 0; x < 8; ++x) {
        tile.set(x, y, 0, static_cast<float>((i + shift) % 48) / 48.0f);
        tile.set(x, y, 1, 0.2f + 0.1f * static_cast<float>(i % 3));
        tile.set(x, y, 2, 0.5f);
      }
    }
    set.colour.push_back(tile);
  }
  if (edgeColours == 1) {
    set.classFirst = {0, 4, 6, 0};
    set.classCount = {4, 2, 2, 0};
  } else {
    set.classFirst = {0, 16, 32, 0};
    set.classCount = {16, 16, 16, 0};
  }
  return set;
}

TEST_F(BarkTilesTest, EveryFragmentShowsTheTileTheCpuChooses) {
  for (const int colours : {1, 2}) {
    SCOPED_TRACE(colours);
    expectTilesAsTheCpu(colours);
  }
}

void BarkTilesTest::expectTilesAsTheCpu(int colours) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "apple"}, 2, 5.0f, 3));
  TreeRenderer renderer(shaders(), forest);
  ASSERT_LT(renderer.instances().instances.size(), 254u * 256u) << "instance ids are read back as two bytes";
  const std::vector<BarkSet> sets{solidSet("a", 0, colours)};
  renderer.setBark(sets);
  ASSERT_TRUE(renderer.textured());
  std::vector<PieceTiling> tilings;
  for (const Piece& piece : forest->pieces.pieces) {
    tilings.push_back(pieceTiling(piece));
  }
  const render::Camera camera = barkCloseUp({-3, 2.0f, 3.5f}, {0, 2.0f, 0});
  render::RenderTarget target(240, 180);
  TreeLod lod;
  lod.fixedLevel = 3.0f;
  target.begin(glm::vec4(0.0f));
  renderer.cull(camera, target.aspect(), lod);
  TreeDrawOptions options;
  options.view = TreeView::Tiles;
  renderer.draw(camera, 240, 180, 0.0, lod, nullptr, options);
  const Image image = target.readColor();
  std::size_t covered = 0;
  std::size_t wrong = 0;
  std::set<int> tiles;
  std::set<int> classes;
  const auto& instances = renderer.instances().instances;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const auto high = std::lround(image.get(x, y, 3) * 255.0f);
      if (high == 0) {
        continue;
      }
      ++covered;
      const auto tile = static_cast<std::uint32_t>(std::lround(image.get(x, y, 0) * 255.0f));
      const auto quad = static_cast<std::uint32_t>(std::lround(image.get(x, y, 1) * 255.0f));
      const auto instance =
          static_cast<std::size_t>(std::lround(image.get(x, y, 2) * 255.0f) + 256 * (high - 1));
      ASSERT_LT(instance, instances.size());
      const glm::uvec4 inst = instances[instance].joints;
      const std::size_t type = (inst.z >> 8) & 255u;
      const Piece& piece = forest->pieces[type];
      ASSERT_LT(quad, piece.quads.size());
      const std::uint32_t cls = piece.tileClass[quad];
      const std::uint32_t expected = barkTile(sets[0], piece, tilings[type], inst.x, quad);
      wrong += tile != expected ? 1 : 0;
      tiles.insert(static_cast<int>(tile));
      classes.insert(static_cast<int>(cls));
    }
  }
  EXPECT_GT(covered, 2000u);
  EXPECT_EQ(wrong, 0u) << "of " << covered << " fragments";
  // Enough variety that agreement means something: most tiles and at least the plain and fork classes.
  EXPECT_GE(tiles.size(), colours == 1 ? 6u : 24u);
  EXPECT_GE(classes.size(), 2u);
}

TEST_F(BarkTilesTest, TexturedDrawIsDeterministicAndUsesTheTiles) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "apple"}, 2, 5.0f, 3));
  TreeRenderer renderer(shaders(), forest);
  const render::Camera camera = barkCloseUp({-6, 3, 8}, {0, 2.5f, 0});
  render::RenderTarget target(160, 120);
  TreeLod lod;
  auto draw = [&] {
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    renderer.cull(camera, target.aspect(), lod);
    renderer.draw(camera, 160, 120, 0.0, lod);
    return target.readColor();
  };
  const Image flat = draw();
  // Species 0 uses set 0, species 1 set 1 (other colours).
  const std::vector<BarkSet> sets{solidSet("a", 0), solidSet("b", 3)};
  const std::vector<int> speciesSet{0, 1};
  renderer.setBark(sets, speciesSet);
  const Image a = draw();
  const Image b = draw();
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == flat);
  renderer.setBark({});
  EXPECT_FALSE(renderer.textured());
  EXPECT_TRUE(draw() == flat);
}

TEST_F(BarkTilesTest, InvalidSetsAreRefused) {
  auto forest = std::make_shared<Forest>(gridForest({"almond"}, 1, 5.0f, 3));
  TreeRenderer renderer(shaders(), forest);
  BarkSet missing = solidSet("missing", 0);
  missing.classCount[0] = 0;
  EXPECT_THROW(renderer.setBark(std::vector<BarkSet>{missing}), Error);
  BarkSet odd = solidSet("odd", 0);
  odd.colour[3] = Image(4, 4, 3, PixelType::U8);
  EXPECT_THROW(renderer.setBark(std::vector<BarkSet>{odd}), Error);
  const std::vector<BarkSet> mixed{solidSet("a", 0), [] {
                                     BarkSet s = solidSet("b", 0);
                                     s.classCount = {6, 1, 1, 0};
                                     s.classFirst = {0, 6, 7, 0};
                                     return s;
                                   }()};
  EXPECT_THROW(renderer.setBark(mixed), Error);
  const std::vector<int> badSpecies{4};
  EXPECT_THROW(renderer.setBark(std::vector<BarkSet>{solidSet("a", 0)}, badSpecies), Error);
}

} // namespace
} // namespace sylva::trees
