// Bark tile placement rules (docs/trees.md "Bark"): tile rotations put the tile's y axis along the branch,
// tile coordinates map quad corners onto tile corners without mirroring, tile choice stays within the class.
#include <sylva/core/Error.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/Pieces.hpp>
#include <sylva/texsynth/Procedural.hpp>

#include <glm/common.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <set>

namespace sylva::trees {
namespace {

const std::array<glm::vec2, 4> kCorners{glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)};

TEST(BarkTest, TileCoordinatesPutTheRotationCornerAtTheOriginWithoutMirroring) {
  for (int r = 0; r < 4; ++r) {
    EXPECT_EQ(tileCoord(kCorners[static_cast<std::size_t>(r)], r), glm::vec2(0, 0)) << r;
    EXPECT_EQ(tileCoord(kCorners[static_cast<std::size_t>((r + 1) % 4)], r), glm::vec2(1, 0)) << r;
    EXPECT_EQ(tileCoord(kCorners[static_cast<std::size_t>((r + 2) % 4)], r), glm::vec2(1, 1)) << r;
    EXPECT_EQ(tileCoord(kCorners[static_cast<std::size_t>((r + 3) % 4)], r), glm::vec2(0, 1)) << r;
    // A rotation, not a reflection: the Jacobian's determinant is +1.
    const glm::vec2 o = tileCoord({0.5f, 0.5f}, r);
    const glm::vec2 du = tileCoord({0.75f, 0.5f}, r) - o;
    const glm::vec2 dv = tileCoord({0.5f, 0.75f}, r) - o;
    EXPECT_NEAR(du.x * dv.y - du.y * dv.x, 0.0625f, 1e-6f) << r;
  }
}

TEST(BarkTest, TileYAxesRunAlongTheBranch) {
  for (const Piece& piece : standardPieces().pieces) {
    const std::vector<std::uint8_t> rotations = quadTileRotations(piece);
    ASSERT_EQ(rotations.size(), piece.quads.size());
    int along = 0;
    for (std::size_t q = 0; q < piece.quads.size(); ++q) {
      const auto& quad = piece.quads[q];
      const int r = rotations[q];
      // The tile's y axis: corner r → corner r + 3, and corner r + 1 → corner r + 2.
      const glm::vec3 y = piece.vertices[quad[static_cast<std::size_t>((r + 3) % 4)]].position -
                          piece.vertices[quad[static_cast<std::size_t>(r)]].position +
                          piece.vertices[quad[static_cast<std::size_t>((r + 2) % 4)]].position -
                          piece.vertices[quad[static_cast<std::size_t>((r + 1) % 4)]].position;
      const glm::vec3 x = piece.vertices[quad[static_cast<std::size_t>((r + 1) % 4)]].position -
                          piece.vertices[quad[static_cast<std::size_t>(r)]].position;
      // Along the branch, the quad's long way up: in the straight I piece the y axis is +y exactly.
      if (piece.name == "I") {
        EXPECT_GT(y.y, 0.0f) << "quad " << q;
        EXPECT_NEAR(x.y, 0.0f, 1e-4f) << "quad " << q;
      }
      along += glm::length(y) > 0.0f ? 1 : 0;
    }
    EXPECT_EQ(along, static_cast<int>(piece.quads.size())) << piece.name;
  }
}

TEST(BarkTest, TileTexelsOfEdgesAreTheOutermostTexels) {
  EXPECT_EQ(tileTexel({0.0f, 0.0f}, 64), glm::ivec2(0, 0));
  EXPECT_EQ(tileTexel({1.0f, 0.5f}, 64), glm::ivec2(63, 32));
  EXPECT_EQ(tileTexel({0.25f, 1.0f}, 65), glm::ivec2(16, 64));
}

TEST(BarkTest, ChosenTilesStayInTheirClassAndVaryPerInstance) {
  std::map<std::uint32_t, int> histogram;
  int differ = 0;
  for (std::uint32_t joint = 0; joint < 200; ++joint) {
    for (std::uint32_t quad = 0; quad < 40; ++quad) {
      const std::uint32_t t = chooseTile(instanceTileSeed(joint), quad, 5, 7);
      ASSERT_GE(t, 5u);
      ASSERT_LT(t, 12u);
      ++histogram[t];
      differ += t != chooseTile(instanceTileSeed(joint + 1), quad, 5, 7) ? 1 : 0;
    }
  }
  EXPECT_EQ(histogram.size(), 7u);
  for (const auto& [tile, n] : histogram) {
    EXPECT_NEAR(n, 8000 / 7, 200) << "tile " << tile;
  }
  EXPECT_GT(differ, 8000 * 3 / 4);
}

TEST(BarkTest, QuadTablePacksClassAndRotation) {
  const Piece y = makeY();
  const std::vector<glm::uvec2> table = quadTileTable(y);
  const PieceTiling tiling = pieceTiling(y);
  ASSERT_EQ(table.size(), y.quads.size());
  std::set<std::uint32_t> classes;
  std::map<std::uint32_t, int> edgeUses;
  int rimEdges = 0;
  for (std::size_t q = 0; q < table.size(); ++q) {
    EXPECT_EQ(table[q].x & 255u, y.tileClass[q]);
    EXPECT_EQ(table[q].x >> 8, tiling.rotation[q]);
    classes.insert(table[q].x & 255u);
    for (std::uint32_t e = 0; e < 4; ++e) {
      const std::uint32_t id = (table[q].y >> (8 * e)) & 255u;
      EXPECT_EQ(id, tiling.edges[q][e]);
      if (id == kRimEdge) {
        ++rimEdges;
      } else {
        ++edgeUses[id];
      }
    }
  }
  EXPECT_EQ(classes.size(), 3u) << "the fork has plain, fork and crotch quads";
  // Every interior edge id is used by exactly two quads; the rim edges are those of its three rims.
  for (const auto& [id, n] : edgeUses) {
    EXPECT_EQ(n, 2) << "edge " << id;
  }
  EXPECT_EQ(rimEdges, 3 * kRimCorners);
}

TEST(BarkTest, ValidationNamesTheProblem) {
  BarkSet set;
  set.name = "x";
  set.tileSize = 8;
  EXPECT_THROW(validate(set, "bark"), Error);
  set.colour.assign(2, Image(8, 8, 3, PixelType::U8));
  set.classCount = {2, 0, 0, 0};
  EXPECT_NO_THROW(validate(set, "bark"));
  set.classFirst[1] = 1;
  set.classCount[1] = 2;
  try {
    validate(set, "bark 'x'");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bark 'x': class 1"), std::string::npos) << e.what();
  }
}

/** Colour texels of `tile` along the quad edge from corner `from` to corner `to` (adjacent), rotation `r`. */
std::vector<std::array<int, 3>> edgeTexels(const Image& tile, int r, int from, int to) {
  const int size = tile.width();
  std::vector<std::array<int, 3>> out;
  for (int j = 0; j < size; ++j) {
    const float s = static_cast<float>(j) / static_cast<float>(size - 1);
    const glm::vec2 uv =
        glm::mix(kCorners[static_cast<std::size_t>(from)], kCorners[static_cast<std::size_t>(to)], s);
    const glm::ivec2 t = tileTexel(tileCoord(uv, r), size);
    out.push_back({static_cast<int>(std::lround(tile.get(t.x, t.y, 0) * 255.0f)),
                   static_cast<int>(std::lround(tile.get(t.x, t.y, 1) * 255.0f)),
                   static_cast<int>(std::lround(tile.get(t.x, t.y, 2) * 255.0f))});
  }
  return out;
}

/** Shared edges compared, those whose texels differ, and the distinct edge lines seen. */
struct SeamCount {
  std::size_t edges = 0;
  std::size_t mismatches = 0;
  std::set<std::vector<std::array<int, 3>>> lines;
};

int cornerOf(const std::array<std::uint32_t, 4>& quad, std::uint32_t vertex) {
  for (int c = 0; c < 4; ++c) {
    if (quad[static_cast<std::size_t>(c)] == vertex) {
      return c;
    }
  }
  return -1;
}

/** The quads of `piece` with the edge (a, b). */
std::vector<std::size_t> quadsWithEdge(const Piece& piece, std::uint32_t a, std::uint32_t b) {
  std::vector<std::size_t> out;
  for (std::size_t q = 0; q < piece.quads.size(); ++q) {
    const int ca = cornerOf(piece.quads[q], a);
    const int cb = cornerOf(piece.quads[q], b);
    if (ca >= 0 && cb >= 0 && ((ca + 1) % 4 == cb || (cb + 1) % 4 == ca)) {
      out.push_back(q);
    }
  }
  return out;
}

/** One piece instance: the piece, its tiling, its root joint (the tile seed). */
struct Instance {
  const Piece* piece;
  const PieceTiling* tiling;
  std::uint32_t rootJoint;
};

/** The texels along edge a → b (vertex ids) in the tile quad `q` of instance `in` shows. */
std::vector<std::array<int, 3>> seamTexels(const BarkSet& set, const Instance& in, std::size_t q,
                                           std::uint32_t a, std::uint32_t b) {
  const std::uint32_t tile =
      barkTile(set, *in.piece, *in.tiling, in.rootJoint, static_cast<std::uint32_t>(q));
  const auto& quad = in.piece->quads[q];
  return edgeTexels(set.colour[tile], in.tiling->rotation[q], cornerOf(quad, a), cornerOf(quad, b));
}

void compare(const std::vector<std::array<int, 3>>& a, const std::vector<std::array<int, 3>>& b,
             SeamCount& count) {
  ++count.edges;
  count.mismatches += a != b ? 1 : 0;
  count.lines.insert(a);
}

/**
 * Every shared edge inside every piece (16 instances of each) and across every rim (every parent and child,
 * all six rotations, 3 parent × 3 child instances), each quad showing the tile barkTile() picks for it.
 */
SeamCount countSeams(const BarkSet& set) {
  SeamCount count;
  const PieceSet pieces = standardPieces();
  std::vector<PieceTiling> tilings;
  for (const Piece& piece : pieces.pieces) {
    tilings.push_back(pieceTiling(piece));
  }
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const Piece& piece = pieces[p];
    std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (const auto& q : piece.quads) {
      for (std::size_t e = 0; e < 4; ++e) {
        edges.insert({std::min(q[e], q[(e + 1) % 4]), std::max(q[e], q[(e + 1) % 4])});
      }
    }
    for (std::uint32_t joint = 0; joint < 16; ++joint) {
      const Instance in{&piece, &tilings[p], 1000 * static_cast<std::uint32_t>(p) + joint};
      for (const auto& [a, b] : edges) {
        const std::vector<std::size_t> both = quadsWithEdge(piece, a, b);
        if (both.size() == 2) {
          compare(seamTexels(set, in, both[0], a, b), seamTexels(set, in, both[1], a, b), count);
        }
      }
    }
  }
  for (std::size_t pp = 0; pp < pieces.size(); ++pp) {
    const Piece& parent = pieces[pp];
    for (std::size_t rim = 1; rim < parent.rims.size(); ++rim) {
      for (std::size_t pc = 0; pc < pieces.size(); ++pc) {
        const Piece& child = pieces[pc];
        // Only pieces whose root rim is open can sit on a rim (not the foot, closed below: the tree's base).
        const auto& root = child.rims[0].vertices;
        if (quadsWithEdge(child, root[0], root[1]).size() != 1) {
          continue;
        }
        for (std::uint32_t seeds = 0; seeds < 9; ++seeds) {
          const Instance a{&parent, &tilings[pp], 7 + seeds / 3};
          const Instance b{&child, &tilings[pc], 50 + seeds % 3};
          for (int rot = 0; rot < kRimCorners; ++rot) {
            for (int k = 0; k < kRimCorners; ++k) {
              // Parent leaf corner k meets child root corner k − rot; both read from corner k to k + 1.
              const auto& pr = parent.rims[rim].vertices;
              const auto& cr = child.rims[0].vertices;
              const std::uint32_t a0 = pr[static_cast<std::size_t>(k)];
              const std::uint32_t a1 = pr[static_cast<std::size_t>((k + 1) % 6)];
              const std::uint32_t b0 = cr[static_cast<std::size_t>((k - rot + 12) % 6)];
              const std::uint32_t b1 = cr[static_cast<std::size_t>((k + 1 - rot + 12) % 6)];
              const std::vector<std::size_t> qa = quadsWithEdge(parent, a0, a1);
              const std::vector<std::size_t> qb = quadsWithEdge(child, b0, b1);
              if (qa.size() != 1 || qb.size() != 1) {
                ADD_FAILURE() << "rim edge not on exactly one quad";
                continue;
              }
              compare(seamTexels(set, a, qa[0], a0, a1), seamTexels(set, b, qb[0], b0, b1), count);
            }
          }
        }
      }
    }
  }
  return count;
}

BarkSet synthesisedSet(int edgeColours) {
  texsynth::TileSettings settings;
  settings.tileSize = 32;
  settings.seed = 7;
  const std::vector<texsynth::Texture> photos{texsynth::proceduralBark(128, 3)};
  return barkSetFromTiles(
      texsynth::barkTileSet(photos, edgeColours == 1 ? 3 : 1, settings, nullptr, edgeColours), "procedural");
}

TEST(BarkTest, AdjacentQuadsMeetTexelForTexelOnEveryPieceAndAcrossEveryRim) {
  // One edge colour (the paper's one border) and two (Wang tiles: rims colour 0, interior edges by hash).
  for (const int colours : {1, 2}) {
    const BarkSet set = synthesisedSet(colours);
    ASSERT_EQ(set.colour.size(), colours == 1 ? 9u : 48u);
    ASSERT_EQ(set.normal.size(), set.colour.size());
    const SeamCount count = countSeams(set);
    EXPECT_GT(count.edges, 10000u);
    EXPECT_EQ(count.mismatches, 0u) << colours << " colours: of " << count.edges << " edges";
    // One border for all with one colour; with two, edges show both lines.
    EXPECT_EQ(count.lines.size(), static_cast<std::size_t>(colours)) << colours << " colours";
    EXPECT_FALSE(set.colour[0] == set.colour[1]);
  }
}

TEST(BarkTest, TheSeamCheckFindsABrokenEdge) {
  BarkSet set = synthesisedSet(2);
  // One texel on every tile's left edge (not a corner) changes: seams through a left edge break.
  for (Image& tile : set.colour) {
    tile.set(0, set.tileSize / 3, 0, 1.0f - tile.get(0, set.tileSize / 3, 0));
  }
  EXPECT_GT(countSeams(set).mismatches, 100u);
}

TEST(BarkTest, SpeciesShareOneSetPerBarkSourceAndMissingPhotosFallBackToProcedural) {
  Forest forest = gridForest({"almond", "silver-birch", "apple"}, 1, 5.0f, 1);
  ASSERT_EQ(forest.species.size(), 3u);
  BarkSources sources;
  sources.photoDir = "/nonexistent/bark";
  sources.tiles.tileSize = 16;
  sources.variants = 2;
  sources.photoSide = 64;
  std::vector<int> speciesSet;
  const std::vector<BarkSet> sets = barkSetsFor(forest, sources, speciesSet);
  // No photos: every species falls back to the one procedural set.
  ASSERT_EQ(sets.size(), 1u);
  EXPECT_EQ(sets[0].name, "procedural");
  EXPECT_EQ(speciesSet, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(sets[0].colour.size(), 96u) << "3 kinds x 16 edge colourings x 2 variants";
  sources.mode = "/nonexistent/tileset";
  EXPECT_THROW((void)barkSetsFor(forest, sources, speciesSet), Error);
}

} // namespace
} // namespace sylva::trees
