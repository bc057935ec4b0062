// Bark tiles on the GPU against the CPU rules (docs/trees.md "Bark"): every drawn fragment shows the tile
// chooseTile() picks for its piece instance, quad and sub-tile along the grain, among the tiles of the quad's
// class; textured drawing is deterministic and differs from the flat colours; invalid tile sets are refused.
#include <sylva/core/Error.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
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
  ASSERT_LT(renderer.instances().instances.size(), 254u * 32u) << "instance ids are read back in 13 bits";
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
  std::size_t repeated = 0;
  std::set<std::uint32_t> subs;
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
      const auto blue = std::lround(image.get(x, y, 2) * 255.0f);
      const auto instance = static_cast<std::size_t>((blue & 31) + 32 * (high - 1));
      const auto sub = static_cast<std::uint32_t>(blue >> 5);
      ASSERT_LT(instance, instances.size());
      const glm::uvec4 inst = instances[instance].joints;
      const std::size_t type = SYLVA_TREE_INSTANCE_TYPE(inst.z);
      const Piece& piece = forest->pieces[type];
      ASSERT_LT(quad, piece.quads.size());
      const std::uint32_t cls = piece.tileClass[quad];
      // The sub-tile comes back mod 8: the repeat may be larger, so any sub-tile ≡ it (mod 8) may be right.
      const std::uint32_t repeat = tileRepeat(tilings[type], quad, SYLVA_TREE_INSTANCE_STRETCH(inst.z));
      bool right = false;
      for (std::uint32_t k = sub; k < repeat && !right; k += 8) {
        right = tile == barkTile(sets[0], piece, tilings[type], inst.x, quad, k, repeat);
      }
      wrong += right ? 0 : 1;
      repeated += repeat > 1 ? 1 : 0;
      subs.insert(sub);
      tiles.insert(static_cast<int>(tile));
      classes.insert(static_cast<int>(cls));
    }
  }
  EXPECT_GT(covered, 2000u);
  EXPECT_EQ(wrong, 0u) << "of " << covered << " fragments";
  // Enough variety that agreement means something: most tiles and at least the plain and fork classes.
  EXPECT_GE(tiles.size(), colours == 1 ? 6u : 24u);
  EXPECT_GE(classes.size(), 2u);
  // Long quads take several tiles along their grain, and fragments show more than their first.
  EXPECT_GT(repeated, covered / 4);
  EXPECT_GE(subs.size(), 3u);
}

/**
 * Mean luminance steps between neighbouring pixels of the bark (its albedo and relief: the textured frame's
 * linear luminance over that of the same frame in plain grey, so the shading of the shape divides out;
 * sRGB-encoded, 0 … 255) by where the pair lies: across a tile edge (another quad or sub-tile of the same
 * piece instance) or next to one (both in one sub-tile, one of them on its border), the same for rims (a
 * piece and its parent or child), and inside (both at least 3 pixels from any border). A seam shows as a step
 * across; a frame line (a band of its own brightness along the border) as a step next to it. Pairs within 2
 * pixels of the background or of a depth jump (a piece in front of another) are left out.
 */
struct LuminanceSteps {
  double inside = 0.0;
  double acrossEdges = 0.0;
  double nextToEdges = 0.0;
  double acrossRims = 0.0;
  double nextToRims = 0.0;
  std::size_t insidePairs = 0;
  std::size_t edgePairs = 0;
  std::size_t rimPairs = 0;

  /** The largest step at an edge or a rim over the step inside tiles. */
  double worstRatio() const { return std::max({acrossEdges, nextToEdges, acrossRims, nextToRims}) / inside; }
};

std::ostream& operator<<(std::ostream& out, const LuminanceSteps& s) {
  return out << "inside " << s.inside << " (" << s.insidePairs << " pairs); tile edges: across "
             << s.acrossEdges << ", next to " << s.nextToEdges << " (" << s.edgePairs << "); rims: across "
             << s.acrossRims << ", next to " << s.nextToRims << " (" << s.rimPairs << ")";
}

/** The frames of one view of a forest the measure needs. */
struct BarkFrames {
  Image textured;
  Image grey;
  Image ids;
  /** Linear depth, metres. */
  Image depth;
};

double linearLuminance(const Image& image, int x, int y) {
  auto linear = [](float c) {
    return c <= 0.04045f ? c / 12.92 : std::pow((static_cast<double>(c) + 0.055) / 1.055, 2.4);
  };
  return 0.2126 * linear(image.get(x, y, 0)) + 0.7152 * linear(image.get(x, y, 1)) +
         0.0722 * linear(image.get(x, y, 2));
}

LuminanceSteps luminanceSteps(const BarkFrames& frames, const Forest& forest, const PackedInstances& packed) {
  const int width = frames.textured.width();
  const int height = frames.textured.height();
  struct Id {
    long instance = -1; // -1: background
    long quad = 0;
    long sub = 0;
  };
  std::vector<Id> id(static_cast<std::size_t>(width * height));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const auto high = std::lround(frames.ids.get(x, y, 3) * 255.0f);
      if (high > 0) {
        const auto blue = std::lround(frames.ids.get(x, y, 2) * 255.0f);
        id[static_cast<std::size_t>(y * width + x)] = {
            (blue & 31) + 32 * (high - 1), std::lround(frames.ids.get(x, y, 1) * 255.0f), blue >> 5};
      }
    }
  }
  auto at = [&](int x, int y) -> const Id& { return id[static_cast<std::size_t>(y * width + x)]; };
  // A rim joins instance a to b when a's root joint is one of b's terminal joints, or the other way round.
  auto onRim = [&](long a, long b) {
    const glm::uvec4 ia = packed.instances[static_cast<std::size_t>(a)].joints;
    const glm::uvec4 ib = packed.instances[static_cast<std::size_t>(b)].joints;
    const auto leaves = [&](const glm::uvec4& inst) {
      return static_cast<std::uint32_t>(forest.pieces[SYLVA_TREE_INSTANCE_TYPE(inst.z)].leafRims());
    };
    return (ia.x >= ib.y && ia.x < ib.y + leaves(ib)) || (ib.x >= ia.y && ib.x < ia.y + leaves(ia));
  };
  // Per pixel, the border it lies on: none, a tile edge, a rim, or a silhouette (the background, a depth jump
  // of over 2 %, or a piece that is not a neighbour on the surface).
  enum Border : std::uint8_t { kNone = 0, kEdge = 1, kRim = 2, kSilhouette = 3 };
  std::vector<std::uint8_t> border(id.size(), kNone);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const Id& a = at(x, y);
      std::uint8_t kind = a.instance < 0 ? kSilhouette : kNone;
      for (const glm::ivec2 d : {glm::ivec2(1, 0), glm::ivec2(-1, 0), glm::ivec2(0, 1), glm::ivec2(0, -1)}) {
        const int nx = x + d.x;
        const int ny = y + d.y;
        if (nx < 0 || ny < 0 || nx >= width || ny >= height) {
          kind = kSilhouette;
          continue;
        }
        const Id& b = at(nx, ny);
        const float za = frames.depth.get(x, y, 0);
        const float zb = frames.depth.get(nx, ny, 0);
        std::uint8_t k = kNone;
        if (b.instance < 0 || a.instance < 0 || std::abs(za - zb) > 0.02f * std::min(za, zb)) {
          k = kSilhouette;
        } else if (b.instance != a.instance) {
          k = onRim(a.instance, b.instance) ? kRim : kSilhouette;
        } else if (b.quad != a.quad || b.sub != a.sub) {
          k = kEdge;
        }
        kind = std::max(kind, k);
      }
      border[static_cast<std::size_t>(y * width + x)] = kind;
    }
  }
  // Whether a border of `kind` lies within 2 pixels (chessboard) of each pixel.
  auto near = [&](std::uint8_t kind) {
    std::vector<bool> out(id.size(), false);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        for (int v = std::max(0, y - 2); v <= std::min(height - 1, y + 2); ++v) {
          for (int u = std::max(0, x - 2); u <= std::min(width - 1, x + 2); ++u) {
            if (border[static_cast<std::size_t>(v * width + u)] == kind) {
              out[static_cast<std::size_t>(y * width + x)] = true;
            }
          }
        }
      }
    }
    return out;
  };
  const std::vector<bool> nearEdge = near(kEdge);
  const std::vector<bool> nearRim = near(kRim);
  const std::vector<bool> nearSilhouette = near(kSilhouette);
  // The bark's own luminance: textured over grey (albedo 0.5), sRGB-encoded.
  auto bark = [&](int x, int y) {
    const double ratio =
        0.5 * linearLuminance(frames.textured, x, y) / std::max(linearLuminance(frames.grey, x, y), 1e-6);
    const double c = ratio <= 0.0031308 ? 12.92 * ratio : 1.055 * std::pow(ratio, 1.0 / 2.4) - 0.055;
    return 255.0 * c;
  };
  LuminanceSteps steps;
  std::array<std::size_t, 4> pairs{};
  for (int y = 0; y + 1 < height; ++y) {
    for (int x = 0; x + 1 < width; ++x) {
      const auto i = static_cast<std::size_t>(y * width + x);
      for (const glm::ivec2 n : {glm::ivec2(x + 1, y), glm::ivec2(x, y + 1)}) {
        const auto j = static_cast<std::size_t>(n.y * width + n.x);
        if (nearSilhouette[i] || nearSilhouette[j]) {
          continue;
        }
        const double step = std::abs(bark(x, y) - bark(n.x, n.y));
        const Id& a = id[i];
        const Id& b = id[j];
        if (a.instance != b.instance) {
          steps.acrossRims += step;
          ++pairs[0];
        } else if (a.quad != b.quad || a.sub != b.sub) {
          steps.acrossEdges += step;
          ++pairs[1];
        } else if (border[i] == kRim || border[j] == kRim) {
          steps.nextToRims += step;
          ++pairs[2];
        } else if (border[i] == kEdge || border[j] == kEdge) {
          steps.nextToEdges += step;
          ++pairs[3];
        } else if (!nearEdge[i] && !nearEdge[j] && !nearRim[i] && !nearRim[j]) {
          steps.inside += step;
          ++steps.insidePairs;
        }
      }
    }
  }
  auto mean = [](double& sum, std::size_t n) { sum /= static_cast<double>(std::max<std::size_t>(n, 1)); };
  mean(steps.inside, steps.insidePairs);
  mean(steps.acrossRims, pairs[0]);
  mean(steps.acrossEdges, pairs[1]);
  mean(steps.nextToRims, pairs[2]);
  mean(steps.nextToEdges, pairs[3]);
  steps.rimPairs = std::min(pairs[0], pairs[2]);
  steps.edgePairs = std::min(pairs[1], pairs[3]);
  return steps;
}

/** The luminance steps of an oak's trunk and first fork, close, with `set` as its bark. */
LuminanceSteps oakTrunkSteps(const shader::Library& library, const BarkSet& set) {
  auto forest = std::make_shared<Forest>(gridForest({"california-black-oak"}, 1, 1.0f, 4));
  TreeRenderer renderer(library, forest);
  render::Camera camera = barkCloseUp({1.6f, 4.2f, 2.2f}, {0.0f, 4.4f, 0.0f});
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 0.05f;
  const int width = 320;
  const int height = 480;
  render::RenderTarget target(width, height);
  const TreeLod lod;
  auto draw = [&](TreeView view) {
    target.begin(glm::vec4(0.0f));
    renderer.cull(camera, target.aspect(), lod);
    TreeDrawOptions options;
    options.view = view;
    renderer.draw(camera, width, height, 0.0, lod, nullptr, options);
    return target.readColor();
  };
  BarkFrames frames;
  renderer.setBark(std::vector<BarkSet>{set});
  frames.textured = draw(TreeView::Shaded);
  const Image depth = target.readDepth();
  frames.depth = Image(width, height, 1, PixelType::F32);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Window depth to metres (perspective, depth range 0 … 1).
      const float ndc = 2.0f * depth.get(x, y, 0) - 1.0f;
      const float n = camera.nearPlane;
      const float f = camera.farPlane;
      frames.depth.set(x, y, 0, 2.0f * n * f / (f + n - ndc * (f - n)));
    }
  }
  BarkSet grey = set;
  grey.normal.clear();
  for (Image& tile : grey.colour) {
    for (int y = 0; y < tile.height(); ++y) {
      for (int x = 0; x < tile.width(); ++x) {
        for (int c = 0; c < 3; ++c) {
          tile.set(x, y, c, 0.5f);
        }
      }
    }
  }
  renderer.setBark(std::vector<BarkSet>{grey});
  frames.grey = draw(TreeView::Shaded);
  frames.ids = draw(TreeView::Tiles);
  return luminanceSteps(frames, *forest, renderer.instances());
}

TEST_F(BarkTilesTest, NoSeamShowsAtRimsOrTileEdges) {
  // Bark without seams (issue 29): the bark's luminance steps between neighbouring pixels across or next to
  // a rim or a tile edge are no larger than between neighbours inside one tile. The control brightens every
  // tile's outermost texels (a frame that shows): the same measure finds it at both.
  BarkSources sources;
  sources.mode = "procedural";
  const Forest probe = gridForest({"california-black-oak"}, 1, 1.0f, 4);
  std::vector<int> speciesSet;
  const BarkSet set = barkSetsFor(probe, sources, speciesSet).at(0);
  const LuminanceSteps clean = oakTrunkSteps(shaders(), set);
  std::cout << "procedural bark, mean luminance steps: " << clean << "\n";
  EXPECT_GT(clean.insidePairs, 20000u);
  EXPECT_GT(clean.edgePairs, 2000u);
  EXPECT_GT(clean.rimPairs, 100u);
  EXPECT_LT(clean.worstRatio(), 1.2) << clean;

  BarkSet framed = set;
  for (Image& tile : framed.colour) {
    const int last = tile.width() - 1;
    for (int i = 0; i <= last; ++i) {
      for (const glm::ivec2 t :
           {glm::ivec2(i, 0), glm::ivec2(i, last), glm::ivec2(0, i), glm::ivec2(last, i)}) {
        for (int c = 0; c < 3; ++c) {
          tile.set(t.x, t.y, c, std::min(1.0f, tile.get(t.x, t.y, c) + 0.3f));
        }
      }
    }
  }
  const LuminanceSteps seams = oakTrunkSteps(shaders(), framed);
  std::cout << "with a bright frame: " << seams << "\n";
  EXPECT_GT(seams.nextToEdges, 1.4 * seams.inside) << seams;
  EXPECT_GT(seams.nextToRims, 1.4 * seams.inside) << seams;
}

TEST_F(BarkTilesTest, PhotoBarkFramesStayFaint) {
  // The same measure on bark synthesised from ez-tree's oak photo: its tiles' frames (the mirrored bands of
  // the symmetric edge colours) show a little next to tile edges (1.21 × the steps inside at this commit).
  // The bound keeps that from growing.
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("ez-tree/bark/oak_color_1k.jpg"));
  BarkSources sources;
  sources.photoDir = test::externalData("ez-tree/bark/oak_color_1k.jpg").parent_path();
  const Forest probe = gridForest({"california-black-oak"}, 1, 1.0f, 4);
  std::vector<int> speciesSet;
  const std::vector<BarkSet> sets = barkSetsFor(probe, sources, speciesSet);
  ASSERT_EQ(sets.at(0).name, "oak");
  const LuminanceSteps steps = oakTrunkSteps(shaders(), sets[0]);
  std::cout << "oak photo bark, mean luminance steps: " << steps << "\n";
  EXPECT_GT(steps.edgePairs, 2000u);
  EXPECT_GT(steps.rimPairs, 100u);
  EXPECT_LT(steps.worstRatio(), 1.3) << steps;
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
