// Edge-constrained tiles: shared edge lines (Wang and bark sets, before and after an 8-bit PNG round trip),
// symmetric palindromes, seamless grid tilings, closed rings, determinism, errors, save/load.
#include "TempDir.hpp"
#include "TestUtil.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/texsynth/Procedural.hpp>
#include <sylva/texsynth/TileSet.hpp>
#include <sylva/texsynth/TileSetIo.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <vector>

namespace sylva::texsynth {
namespace {

namespace fs = std::filesystem;
using testing::HasSubstr;

constexpr int kTile = 32;

TileSettings smallSettings(std::uint64_t seed = 7) {
  TileSettings s;
  s.tileSize = kTile;
  s.seed = seed;
  s.maxCandidates = 256;
  return s;
}

const Texture& wangPhoto();

const TileSet& wangSet() {
  static const TileSet set = [] { return wangTileSet(wangPhoto(), 2, 2, smallSettings()); }();
  return set;
}

const TileSet& barkSet() {
  static const TileSet set = [] {
    Texture a = proceduralBark(128, 31);
    a.name = "a.png";
    Texture b = proceduralBark(96, 32);
    b.name = "b.png";
    return barkTileSet({a, b}, 3, smallSettings());
  }();
  return set;
}

/** The colour channels of a line. */
std::vector<float> colourOf(const std::vector<float>& line, int channels) {
  std::vector<float> colour;
  for (std::size_t i = 0; i < line.size(); i += static_cast<std::size_t>(channels)) {
    colour.insert(colour.end(), line.begin() + static_cast<std::ptrdiff_t>(i),
                  line.begin() + static_cast<std::ptrdiff_t>(i) + 3);
  }
  return colour;
}

/** The normal of each line texel in the edge's frame: (along the reading direction, inward, z). */
std::vector<float> edgeFrameNormals(const std::vector<float>& line, int edge) {
  // Reading direction and inward direction in tile (x, y) for edges 0..3.
  static const int along[4][2] = {{1, 0}, {0, 1}, {1, 0}, {0, 1}};
  static const int inward[4][2] = {{0, 1}, {-1, 0}, {0, -1}, {1, 0}};
  std::vector<float> normals;
  for (std::size_t i = 0; i < line.size(); i += 6) {
    const float x = line[i + 3];
    const float y = line[i + 4];
    normals.push_back(x * along[edge][0] + y * along[edge][1]);
    normals.push_back(x * inward[edge][0] + y * inward[edge][1]);
    normals.push_back(line[i + 5]);
  }
  return normals;
}

/** Every pair of tiles that may meet on a grid: A.edge1 vs B.edge3 and A.edge2 vs C.edge0 when colours match.
 */
void expectWangEdgesShared(const TileSet& set) {
  const int n = static_cast<int>(set.tiles.size());
  int matches = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (const auto& [ea, eb] : {std::pair{kEdgeRight, kEdgeLeft}, std::pair{kEdgeTop, kEdgeBottom}}) {
        const auto la = edgeLine(set.tiles[static_cast<std::size_t>(a)], ea);
        const auto lb = edgeLine(set.tiles[static_cast<std::size_t>(b)], eb);
        if (set.edgeColour(a, ea) == set.edgeColour(b, eb)) {
          ++matches;
          ASSERT_EQ(la, lb) << "tiles " << a << " and " << b << ", edges " << ea << "/" << eb;
        } else {
          EXPECT_NE(colourOf(la, set.channels), colourOf(lb, set.channels))
              << "different colours should differ: tiles " << a << ", " << b;
        }
      }
    }
  }
  EXPECT_GT(matches, n);
}

TEST(WangTiles, CompleteSetHasEveryEdgeCombination) {
  const TileSet& set = wangSet();
  ASSERT_EQ(set.colours.size(), 2u);
  ASSERT_EQ(set.classes.size(), 16u);
  ASSERT_EQ(set.tiles.size(), 32u);
  std::set<std::array<int, 4>> combos;
  for (std::size_t c = 0; c < set.classes.size(); ++c) {
    combos.insert(set.classes[c].edges);
    EXPECT_EQ(set.firstTile(static_cast<int>(c)), 2 * static_cast<int>(c));
    EXPECT_EQ(set.tileCount(static_cast<int>(c)), 2);
    EXPECT_FALSE(set.colours[static_cast<std::size_t>(set.classes[c].edges[0])].symmetric);
  }
  EXPECT_EQ(combos.size(), 16u);
  EXPECT_EQ(set.classOf(5), 2);
  EXPECT_THROW(set.classOf(32), Error);
}

TEST(WangTiles, MatchingEdgesAreBitIdentical) {
  expectWangEdgesShared(wangSet());
}

/** The photo the Wang set is built from. */
const Texture& wangPhoto() {
  static const Texture photo = [] {
    Texture t = proceduralBark(128, 21);
    t.name = "bark.png";
    return t;
  }();
  return photo;
}

/** Whether a w × h block of `texels(x, y)` occurs somewhere in the photo (colour channels, exactly). */
bool occursInPhoto(int w, int h, const std::function<const float*(int, int)>& texels) {
  const Texture& photo = wangPhoto();
  for (int sy = 0; sy + h <= photo.height; ++sy) {
    for (int sx = 0; sx + w <= photo.width; ++sx) {
      bool all = true;
      for (int y = 0; y < h && all; ++y) {
        for (int x = 0; x < w && all; ++x) {
          all = std::equal(texels(x, y), texels(x, y) + 3, photo.at(sx + x, sy + y));
        }
      }
      if (all) {
        return true;
      }
    }
  }
  return false;
}

TEST(WangTiles, BandsContinueTheSourceAcrossTheEdge) {
  // Two tiles meeting along an oriented colour: the band below the line (tile A), the shared line and the
  // band above it (tile C, from its row 1) form one unbroken block of the photo; likewise left and right.
  // Only columns (rows) away from the corner squares, which hold pure strip texels.
  const TileSet& set = wangSet();
  const int b = set.band;
  const int d = set.band + set.overlap;
  const int span = kTile - 2 * d;
  for (int a = 0; a < static_cast<int>(set.tiles.size()); a += 5) {
    for (int c = 0; c < static_cast<int>(set.tiles.size()); c += 3) {
      const Texture& ta = set.tiles[static_cast<std::size_t>(a)];
      const Texture& tc = set.tiles[static_cast<std::size_t>(c)];
      if (set.edgeColour(a, kEdgeTop) == set.edgeColour(c, kEdgeBottom)) {
        EXPECT_TRUE(occursInPhoto(
            span, 2 * b - 1,
            [&](int x, int y) { return y < b ? ta.at(d + x, kTile - b + y) : tc.at(d + x, y - (b - 1)); }))
            << "tiles " << a << " below " << c;
      }
      if (set.edgeColour(a, kEdgeRight) == set.edgeColour(c, kEdgeLeft)) {
        EXPECT_TRUE(occursInPhoto(
            2 * b - 1, span,
            [&](int x, int y) { return x < b ? ta.at(kTile - b + x, d + y) : tc.at(x - (b - 1), d + y); }))
            << "tiles " << a << " left of " << c;
      }
    }
  }
  // And a block that crosses a line between different colours does not (the test can fail).
  const int other = set.firstTile(1); // class 1: edge 0 has colour 1, tile 0's edge 2 colour 0
  ASSERT_NE(set.edgeColour(0, kEdgeTop), set.edgeColour(other, kEdgeBottom));
  EXPECT_FALSE(occursInPhoto(span, 2 * b - 1, [&](int x, int y) {
    return y < b ? set.tiles[0].at(d + x, kTile - b + y)
                 : set.tiles[static_cast<std::size_t>(other)].at(d + x, y - (b - 1));
  }));
}

TEST(WangTiles, VariantsShareTheFrameAndDifferInside) {
  const TileSet& set = wangSet();
  const int band = set.band;
  for (int cls = 0; cls < 16; ++cls) {
    const Texture& a = set.tiles[static_cast<std::size_t>(set.firstTile(cls))];
    const Texture& b = set.tiles[static_cast<std::size_t>(set.firstTile(cls) + 1)];
    int insideDiffers = 0;
    for (int y = 0; y < kTile; ++y) {
      for (int x = 0; x < kTile; ++x) {
        const int distance = std::min({x, y, kTile - 1 - x, kTile - 1 - y});
        const bool same = std::equal(a.at(x, y), a.at(x, y) + set.channels, b.at(x, y));
        if (distance < band) {
          ASSERT_TRUE(same) << "class " << cls << " texel " << x << "," << y;
        } else {
          insideDiffers += same ? 0 : 1;
        }
      }
    }
    EXPECT_GT(insideDiffers, 0) << "class " << cls;
  }
}

TEST(WangTiles, RandomGridTilingIsSeamless) {
  const TileSet& set = wangSet();
  const int w = 7;
  const int h = 5;
  const std::vector<int> grid = tileGrid(set, w, h, 99);
  ASSERT_EQ(grid.size(), static_cast<std::size_t>(w * h));
  std::set<int> used(grid.begin(), grid.end());
  EXPECT_GT(used.size(), 8u) << "a stochastic tiling uses many tiles";
  const Texture preview = tilingPreview(set, grid, w, h);
  for (int gy = 0; gy < h; ++gy) {
    for (int gx = 0; gx < w; ++gx) {
      const int tile = grid[static_cast<std::size_t>(gy * w + gx)];
      if (gx > 0) {
        const int left = grid[static_cast<std::size_t>(gy * w + gx - 1)];
        ASSERT_EQ(set.edgeColour(left, kEdgeRight), set.edgeColour(tile, kEdgeLeft));
        for (int y = 0; y < kTile; ++y) {
          ASSERT_TRUE(std::equal(preview.at(gx * kTile - 1, gy * kTile + y),
                                 preview.at(gx * kTile - 1, gy * kTile + y) + set.channels,
                                 preview.at(gx * kTile, gy * kTile + y)));
        }
      }
      if (gy > 0) {
        const int below = grid[static_cast<std::size_t>((gy - 1) * w + gx)];
        ASSERT_EQ(set.edgeColour(below, kEdgeTop), set.edgeColour(tile, kEdgeBottom));
        ASSERT_TRUE(std::equal(preview.at(gx * kTile, gy * kTile - 1),
                               preview.at(gx * kTile, gy * kTile - 1) + kTile * set.channels,
                               preview.at(gx * kTile, gy * kTile)));
      }
    }
  }
  EXPECT_EQ(tileGrid(set, w, h, 99), grid);
  EXPECT_NE(tileGrid(set, w, h, 100), grid);
}

TEST(WangTiles, RingOfSixCloses) {
  const TileSet& set = wangSet();
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const std::vector<int> ring = tileRing(set, 6, seed);
    ASSERT_EQ(ring.size(), 6u);
    for (int j = 0; j < 6; ++j) {
      const int a = ring[static_cast<std::size_t>(j)];
      const int b = ring[static_cast<std::size_t>((j + 1) % 6)];
      ASSERT_EQ(set.edgeColour(a, kEdgeRight), set.edgeColour(b, kEdgeLeft)) << "seam " << j;
      ASSERT_EQ(edgeLine(set.tiles[static_cast<std::size_t>(a)], kEdgeRight),
                edgeLine(set.tiles[static_cast<std::size_t>(b)], kEdgeLeft));
    }
  }
}

TEST(WangTiles, IncompleteSetsFailToTile) {
  TileSet set = wangSet();
  // Keep only classes whose left edge is colour 0 and right edge colour 1: nothing can follow them.
  std::vector<TileClass> classes;
  std::vector<Texture> tiles;
  for (std::size_t c = 0; c < set.classes.size(); ++c) {
    if (set.classes[c].edges[kEdgeLeft] == 0 && set.classes[c].edges[kEdgeRight] == 1) {
      classes.push_back(set.classes[c]);
      for (int v = 0; v < set.classes[c].tileCount; ++v) {
        tiles.push_back(set.tiles[static_cast<std::size_t>(set.firstTile(static_cast<int>(c)) + v)]);
      }
    }
  }
  set.classes = classes;
  set.tiles = tiles;
  EXPECT_THROW(tileGrid(set, 3, 1, 1), Error);
  EXPECT_THROW(tileRing(set, 6, 1), Error);
}

TEST(BarkTiles, OneSymmetricColourThreeClasses) {
  const TileSet& set = barkSet();
  ASSERT_EQ(set.colours.size(), 1u);
  EXPECT_TRUE(set.colours[0].symmetric);
  ASSERT_EQ(set.classes.size(), 3u);
  EXPECT_EQ(set.classes[kBarkPlain].name, "plain");
  EXPECT_EQ(set.classes[kBarkFork].name, "fork");
  EXPECT_EQ(set.classes[kBarkCrotch].name, "crotch");
  EXPECT_EQ(set.firstTile(kBarkCrotch), 6);
  EXPECT_EQ(set.tiles.size(), 9u);
  EXPECT_EQ(set.channels, 6);
}

/** Symmetric lines: colour palindromes, the same colours on all 4 edges of all tiles, normals in edge frame.
 */
void expectSymmetricEdges(const TileSet& set, float normalTolerance) {
  const std::vector<float> reference = colourOf(edgeLine(set.tiles[0], kEdgeBottom), set.channels);
  const std::vector<float> referenceNormals = edgeFrameNormals(edgeLine(set.tiles[0], kEdgeBottom), 0);
  const int t = set.tileSize;
  for (std::size_t i = 0; i < set.tiles.size(); ++i) {
    for (int edge = 0; edge < 4; ++edge) {
      const std::vector<float> line = edgeLine(set.tiles[i], edge);
      const std::vector<float> colour = colourOf(line, set.channels);
      ASSERT_EQ(colour, reference) << "tile " << i << " edge " << edge;
      for (int k = 0; k < t; ++k) {
        for (int c = 0; c < 3; ++c) {
          ASSERT_EQ(colour[static_cast<std::size_t>(3 * k + c)],
                    colour[static_cast<std::size_t>(3 * (t - 1 - k) + c)])
              << "palindrome, texel " << k;
        }
      }
      const std::vector<float> normals = edgeFrameNormals(line, edge);
      for (int k = 0; k < t; ++k) {
        const auto n = [&](int texel, int c) { return normals[static_cast<std::size_t>(3 * texel + c)]; };
        EXPECT_NEAR(n(k, 0), referenceNormals[static_cast<std::size_t>(3 * k)], normalTolerance);
        EXPECT_NEAR(n(k, 1), 0.0f, normalTolerance) << "no slope across a symmetric line";
        EXPECT_NEAR(n(k, 0), -n(t - 1 - k, 0), normalTolerance) << "mirrored along the line";
        EXPECT_NEAR(n(k, 2), n(t - 1 - k, 2), normalTolerance);
      }
    }
  }
}

TEST(BarkTiles, SymmetricEdgesArePalindromesOnAllFourSides) {
  expectSymmetricEdges(barkSet(), 0.0f);
}

TEST(BarkTiles, TwoColoursCoverEveryEdgeColouringWithOneLinePerColour) {
  const TileSet set = barkTileSet({proceduralBark(128, 33)}, 1, smallSettings(), nullptr, 2);
  ASSERT_EQ(set.colours.size(), 2u);
  ASSERT_EQ(set.classes.size(), 48u) << "3 kinds x 2^4 edge colourings";
  ASSERT_EQ(set.tiles.size(), 48u);
  // The line of each colour, from the first tile that has it on its bottom edge.
  std::array<std::vector<float>, 2> lines;
  for (std::size_t c = 0; c < set.classes.size(); ++c) {
    const std::array<int, 4>& e = set.classes[c].edges;
    const int combo = static_cast<int>(c % 16);
    EXPECT_EQ(e, (std::array<int, 4>{combo % 2, combo / 2 % 2, combo / 4 % 2, combo / 8 % 2})) << c;
  }
  for (std::size_t i = 0; i < set.tiles.size(); ++i) {
    for (int edge = 0; edge < 4; ++edge) {
      const int colour = set.edgeColour(static_cast<int>(i), edge);
      const std::vector<float> line = colourOf(edgeLine(set.tiles[i], edge), set.channels);
      auto& reference = lines[static_cast<std::size_t>(colour)];
      if (reference.empty()) {
        reference = line;
      }
      ASSERT_EQ(line, reference) << "tile " << i << " edge " << edge << " colour " << colour;
      for (int k = 0; k < kTile; ++k) {
        ASSERT_EQ(line[static_cast<std::size_t>(3 * k)], line[static_cast<std::size_t>(3 * (kTile - 1 - k))])
            << "palindrome";
      }
    }
  }
  EXPECT_NE(lines[0], lines[1]) << "two colours, two lines";
  // They share the corner texel (tile corners are shared by up to four tiles of any colours).
  EXPECT_EQ(std::vector<float>(lines[0].begin(), lines[0].begin() + 3),
            std::vector<float>(lines[1].begin(), lines[1].begin() + 3));
}

TEST(BarkTiles, EveryTileHasTheSameBorderAndClassesDifferInside) {
  const TileSet& set = barkSet();
  const Texture& first = set.tiles[0];
  for (std::size_t i = 1; i < set.tiles.size(); ++i) {
    int insideDiffers = 0;
    for (int y = 0; y < kTile; ++y) {
      for (int x = 0; x < kTile; ++x) {
        const int distance = std::min({x, y, kTile - 1 - x, kTile - 1 - y});
        const bool same = std::equal(first.at(x, y), first.at(x, y) + set.channels, set.tiles[i].at(x, y));
        if (distance < set.band) {
          ASSERT_TRUE(same) << "tile " << i << " texel " << x << "," << y;
        } else {
          insideDiffers += same ? 0 : 1;
        }
      }
    }
    EXPECT_GT(insideDiffers, 0) << "tile " << i;
  }
}

TEST(BarkTiles, TextureContinuesAcrossEdgesAsAReflection) {
  // Two bark tiles meet edge 2 to edge 0 (both upright): tile A's row T−1−k and tile C's row k are mirror
  // images across the shared line, in colour, away from the corner squares. Every tile has the same border,
  // so this is a property of each tile's own top and bottom bands (and left and right ones).
  const TileSet& set = barkSet();
  const int d = set.band + set.overlap;
  for (const Texture& tile : set.tiles) {
    for (int k = 0; k < set.band; ++k) {
      for (int i = d; i < kTile - d; ++i) {
        ASSERT_TRUE(std::equal(tile.at(i, kTile - 1 - k), tile.at(i, kTile - 1 - k) + 3, tile.at(i, k)));
        ASSERT_TRUE(std::equal(tile.at(kTile - 1 - k, i), tile.at(kTile - 1 - k, i) + 3, tile.at(k, i)));
      }
    }
  }
  // The bands are not flat: the reflection is of real texture.
  const Texture& tile = set.tiles[0];
  EXPECT_NE(tile.at(d, 1)[0], tile.at(d, 3)[0]);
}

TEST(BarkTiles, EdgesMatchUnderEveryRotation) {
  // Rotating a tile by quarter turns moves edge e to edge e + turns; the line read in the edge's direction
  // must be the same colour sequence whichever edge of whichever tile meets it, in either direction.
  const TileSet& set = barkSet();
  for (std::size_t a = 0; a < set.tiles.size(); ++a) {
    for (std::size_t b = 0; b < set.tiles.size(); ++b) {
      for (int ea = 0; ea < 4; ++ea) {
        for (int eb = 0; eb < 4; ++eb) {
          std::vector<float> la = colourOf(edgeLine(set.tiles[a], ea), set.channels);
          std::vector<float> lb = colourOf(edgeLine(set.tiles[b], eb), set.channels);
          ASSERT_EQ(la, lb);
          std::vector<float> reversed;
          for (int k = kTile - 1; k >= 0; --k) {
            reversed.insert(reversed.end(), lb.begin() + 3 * k, lb.begin() + 3 * k + 3);
          }
          ASSERT_EQ(la, reversed);
        }
      }
    }
  }
  const std::vector<int> ring = tileRing(set, 6, 3);
  EXPECT_EQ(ring.size(), 6u);
}

TEST(TileSets, SameSeedSameSetOtherSeedOtherSet) {
  Texture photo = proceduralBark(96, 5);
  const TileSet a = barkTileSet({photo}, 2, smallSettings(1));
  const TileSet b = barkTileSet({photo}, 2, smallSettings(1));
  const TileSet c = barkTileSet({photo}, 2, smallSettings(2));
  ASSERT_EQ(a.tiles.size(), b.tiles.size());
  for (std::size_t i = 0; i < a.tiles.size(); ++i) {
    EXPECT_EQ(a.tiles[i].texels, b.tiles[i].texels) << i;
  }
  EXPECT_NE(a.tiles[0].texels, c.tiles[0].texels);
  const TileSet w1 = wangTileSet(photo, 1, 1, smallSettings(4));
  const TileSet w2 = wangTileSet(photo, 1, 1, smallSettings(4));
  EXPECT_EQ(w1.tiles[0].texels, w2.tiles[0].texels);
}

using test::errorOf;

TEST(TileSets, BadInputsAreOneLineErrors) {
  Texture small = proceduralBark(24, 1);
  small.name = "tiny.jpg";
  EXPECT_THAT(errorOf([&] { barkTileSet({small}, 2, smallSettings()); }),
              HasSubstr("tiny.jpg: the photo is 24x24, smaller than the 32x32 tile"));
  const Texture photo = proceduralBark(64, 1);
  TileSettings s = smallSettings();
  s.tolerance = std::nan("");
  EXPECT_THAT(errorOf([&] { barkTileSet({photo}, 2, s); }), HasSubstr("tolerance"));
  s = smallSettings();
  s.band = 10;
  s.overlap = 10;
  EXPECT_THAT(errorOf([&] { barkTileSet({photo}, 2, s); }), HasSubstr("band"));
  s = smallSettings();
  s.tileSize = 100000;
  EXPECT_THAT(errorOf([&] { barkTileSet({photo}, 2, s); }), HasSubstr("tileSize"));
  EXPECT_THAT(errorOf([&] { barkTileSet({photo}, 0, smallSettings()); }), HasSubstr("variants"));
  EXPECT_THAT(errorOf([&] { barkTileSet({}, 1, smallSettings()); }), HasSubstr("photos"));
  EXPECT_THAT(errorOf([&] { wangTileSet(photo, 4, 1, smallSettings()); }), HasSubstr("colours"));
  Texture empty;
  empty.name = "empty.png";
  EXPECT_THAT(errorOf([&] { barkTileSet({empty}, 1, smallSettings()); }), HasSubstr("empty.png"));
  Texture colourOnly = Texture::blank(64, 64, 3, "colour.png");
  EXPECT_THAT(errorOf([&] {
                barkTileSet({photo, colourOnly}, 1, smallSettings());
              }),
              HasSubstr("colour.png"));
}

/** Colour texels equal to 8-bit quantisation of the originals. */
void expectQuantisedEqual(const TileSet& original, const TileSet& loaded) {
  ASSERT_EQ(original.tiles.size(), loaded.tiles.size());
  for (std::size_t i = 0; i < original.tiles.size(); ++i) {
    const Texture& a = original.tiles[i];
    const Texture& b = loaded.tiles[i];
    ASSERT_EQ(a.channels, b.channels);
    for (std::size_t k = 0; k < a.texels.size(); ++k) {
      const float tolerance = (k % static_cast<std::size_t>(a.channels)) < 3 ? 0.5f / 255 : 1.0f / 255;
      ASSERT_NEAR(a.texels[k], b.texels[k], tolerance + 1e-6f) << "tile " << i << " value " << k;
    }
  }
}

TEST(TileSetFiles, RoundTripKeepsEdgesShared) {
  const test::TempDir dir;
  saveTileSet(dir / "wang", wangSet());
  saveTileSet(dir / "bark", barkSet());
  EXPECT_TRUE(fs::exists(dir / "wang" / "color.png"));
  EXPECT_TRUE(fs::exists(dir / "wang" / "normal.png")) << "procedural bark has normals";
  const TileSet wang = loadTileSet(dir / "wang");
  const TileSet bark = loadTileSet(dir / "bark");
  EXPECT_EQ(wang.classes, wangSet().classes);
  EXPECT_EQ(wang.colours, wangSet().colours);
  EXPECT_EQ(bark.classes, barkSet().classes);
  EXPECT_EQ(bark.band, barkSet().band);
  expectQuantisedEqual(wangSet(), wang);
  expectQuantisedEqual(barkSet(), bark);
  expectWangEdgesShared(wang);
  expectSymmetricEdges(bark, 2.5f / 255);
  // Saving again replaces the directory in place.
  saveTileSet(dir / "bark", barkSet());
  EXPECT_EQ(loadTileSet(dir / "bark").tiles.size(), barkSet().tiles.size());
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.path())) {
    ++entries;
  }
  EXPECT_EQ(entries, 2u) << "no temporary directories left";
}

TEST(TileSetFiles, StrictJsonErrorsNameFileAndField) {
  const test::TempDir dir;
  saveTileSet(dir / "set", barkSet());
  const fs::path json = dir / "set" / "tileset.json";
  const nlohmann::json good = loadJsonFile(json);
  const auto errorWith = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json changed = good;
    edit(changed);
    saveJsonFile(json, changed);
    return errorOf([&] { loadTileSet(dir / "set"); });
  };
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["extra"] = 1; }), HasSubstr("/extra: unknown field"));
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["tileSize"] = "big"; }), HasSubstr("tileSize"));
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["version"] = 2; }), HasSubstr("version"));
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["classes"][0]["tiles"] = 30; }),
              HasSubstr("/atlas/rows: a 3x3 atlas grid"));
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["classes"][1]["edges"][2] = 1; }),
              HasSubstr("/classes/1/edges/2: 1 is more than 0"));
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["atlas"]["color"] = "../x.png"; }),
              HasSubstr("/atlas/color: '../x.png' must be a plain"));
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["atlas"].erase("normal"); }), HasSubstr("atlas"));
  EXPECT_THAT(errorWith([](nlohmann::json& j) { j["tileSize"] = 64; }), HasSubstr("color.png: the atlas is"));
  EXPECT_THAT(errorWith([](nlohmann::json&) {}), HasSubstr("(no error)"));
  EXPECT_THAT(errorWith([](nlohmann::json&) {}), HasSubstr("(no error)"));
  // A smaller atlas than tileset.json promises.
  saveImage(dir / "set" / "normal.png", Image(8, 8, 3, PixelType::U8));
  EXPECT_THAT(errorOf([&] { loadTileSet(dir / "set"); }), HasSubstr("normal.png: the atlas is 8x8"));
  fs::remove(dir / "set" / "color.png");
  EXPECT_THAT(errorOf([&] { loadTileSet(dir / "set"); }), HasSubstr("color.png"));
  EXPECT_THAT(errorOf([&] { loadTileSet(dir / "absent"); }), HasSubstr("tileset.json"));
}

TEST(TileSetFiles, FailedSaveLeavesNothing) {
  const test::TempDir dir;
  writeTextFile(dir / "file", "not a directory");
  EXPECT_THROW(saveTileSet(dir / "file" / "set", barkSet()), Error);
  TileSet broken = barkSet();
  broken.tiles.pop_back();
  EXPECT_THAT(errorOf([&] { saveTileSet(dir / "set", broken); }), HasSubstr("classes count"));
  EXPECT_FALSE(fs::exists(dir / "set"));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.path())) {
    ++entries;
  }
  EXPECT_EQ(entries, 1u);
}

} // namespace
} // namespace sylva::texsynth
