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
#include <functional>
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
    EXPECT_EQ((table[q].x >> 8) & 3u, tiling.rotation[q]);
    EXPECT_EQ((table[q].x >> 10) & 3u, tiling.sideFlip[q]);
    EXPECT_EQ((table[q].x >> 16) & 255u, tiling.repeat[q][0]);
    EXPECT_EQ(table[q].x >> 24, tiling.repeat[q][1]);
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

TEST(BarkTest, TilesStackAlongTheGrainAsPiecesStretch) {
  EXPECT_EQ(tileStretch(1.0f), 16u);
  EXPECT_EQ(tileStretch(0.5f), 8u);
  EXPECT_EQ(tileStretch(16.0f), 255u);
  EXPECT_EQ(tileStretch(0.0f), 1u);
  for (const Piece& piece : standardPieces().pieces) {
    const PieceTiling tiling = pieceTiling(piece);
    ASSERT_EQ(tiling.repeat.size(), piece.quads.size());
    ASSERT_EQ(tiling.sideFlip.size(), piece.quads.size());
    for (std::size_t q = 0; q < piece.quads.size(); ++q) {
      std::uint32_t previous = 1;
      for (std::uint32_t stretch = 8; stretch <= 255; ++stretch) {
        const std::uint32_t n = tileRepeat(tiling, q, stretch);
        ASSERT_GE(n, previous) << piece.name << " quad " << q << ": longer pieces never take fewer tiles";
        ASSERT_LE(n, kMaxTileRepeat);
        previous = n;
      }
    }
  }
  // The I piece: its quads are about 1.7 times as long as wide, each ring stretches with the piece.
  const Piece i = makeI();
  const PieceTiling tiling = pieceTiling(i);
  for (std::size_t q = 0; q < i.quads.size(); ++q) {
    EXPECT_EQ(tileRepeat(tiling, q, tileStretch(1.0f)), 2u) << q;
    EXPECT_GE(tileRepeat(tiling, q, tileStretch(5.0f)), 7u) << q;
    EXPECT_LE(tileRepeat(tiling, q, tileStretch(5.0f)), 12u) << q;
  }
  // A quad without a repeat (x = 16, y = 0) keeps one tile at any stretch.
  PieceTiling one = tiling;
  one.repeat[0] = {16, 0};
  EXPECT_EQ(tileRepeat(one, 0, 255), 1u);
  EXPECT_EQ(subTile(0.0f, 4).first, 0u);
  EXPECT_EQ(subTile(0.5f, 4).first, 2u);
  EXPECT_EQ(subTile(1.0f, 4).first, 3u) << "the last row belongs to the last sub-tile";
  EXPECT_FLOAT_EQ(subTile(1.0f, 4).second, 1.0f);
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

/** Shared edges compared, those whose texels differ, and the distinct edge lines seen. */
struct SeamCount {
  std::size_t edges = 0;
  /** Of them, edges between sub-tiles stacked along a quad's grain. */
  std::size_t inner = 0;
  std::size_t tileSize = 0;
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

/** One piece instance: the piece, its tiling, its root joint (the tile seed), its stretch (tileStretch). */
struct Instance {
  const Piece* piece;
  const PieceTiling* tiling;
  std::uint32_t rootJoint;
  std::uint32_t stretch = 16;
};

/** The colour texel (column, row) of sub-tile `sub` of quad `q` of `in`, 8-bit as uploaded. */
std::array<int, 3> subTileTexel(const BarkSet& set, const Instance& in, std::size_t q, std::uint32_t sub,
                                int column, int row) {
  const std::uint32_t repeat = tileRepeat(*in.tiling, q, in.stretch);
  const Image& tile = set.colour[barkTile(set, *in.piece, *in.tiling, in.rootJoint,
                                          static_cast<std::uint32_t>(q), sub, repeat)];
  return {static_cast<int>(std::lround(tile.get(column, row, 0) * 255.0f)),
          static_cast<int>(std::lround(tile.get(column, row, 1) * 255.0f)),
          static_cast<int>(std::lround(tile.get(column, row, 2) * 255.0f))};
}

/**
 * The texels along edge a → b (vertex ids) that quad `q` of instance `in` shows, at the edge's resolution: a
 * tile side along the grain crosses the quad's `repeat` sub-tiles ((T − 1) · repeat + 1 texels), the other
 * edges are one sub-tile's first or last row (T texels).
 */
std::vector<std::array<int, 3>> seamTexels(const BarkSet& set, const Instance& in, std::size_t q,
                                           std::uint32_t a, std::uint32_t b) {
  const auto& quad = in.piece->quads[q];
  const int r = in.tiling->rotation[q];
  const glm::vec2 from = tileCoord(kCorners[static_cast<std::size_t>(cornerOf(quad, a))], r);
  const glm::vec2 to = tileCoord(kCorners[static_cast<std::size_t>(cornerOf(quad, b))], r);
  const std::uint32_t repeat = tileRepeat(*in.tiling, q, in.stretch);
  const int last = set.tileSize - 1;
  std::vector<std::array<int, 3>> out;
  if (from.x == to.x) {
    // Along the grain: row `along` counted from the tile's y = 0 across all the sub-tiles.
    const int column = from.x > 0.5f ? last : 0;
    const int steps = last * static_cast<int>(repeat);
    for (int j = 0; j <= steps; ++j) {
      const int along = from.y < to.y ? j : steps - j;
      const auto sub = std::min(static_cast<std::uint32_t>(along / last), repeat - 1);
      out.push_back(subTileTexel(set, in, q, sub, column, along - static_cast<int>(sub) * last));
    }
  } else {
    const bool top = from.y > 0.5f;
    for (int j = 0; j <= last; ++j) {
      out.push_back(
          subTileTexel(set, in, q, top ? repeat - 1 : 0, from.x < to.x ? j : last - j, top ? last : 0));
    }
  }
  return out;
}

void compare(const std::vector<std::array<int, 3>>& a, const std::vector<std::array<int, 3>>& b,
             SeamCount& count) {
  ++count.edges;
  count.mismatches += a != b ? 1 : 0;
  // The lines of single tiles (a side along the grain of several tiles strings their lines together).
  if (a.size() == count.tileSize) {
    count.lines.insert(a);
  }
}

/** Stretches (tileStretch units) the proof's instances take in turn: unstretched, the presets' range, the
 * most. */
constexpr std::array<std::uint32_t, 6> kStretches{16, 24, 40, 77, 200, 255};

/**
 * Every shared edge inside every piece (16 instances of each, at every stretch of kStretches), the edges
 * between the sub-tiles stacked along a quad's grain, and every rim (every parent and child, all six
 * rotations, 3 parent × 3 child instances), each quad showing the tiles barkTile() picks for it.
 */
SeamCount countSeams(const BarkSet& set,
                     const std::function<void(std::vector<PieceTiling>&)>& tamper = nullptr) {
  SeamCount count;
  count.tileSize = static_cast<std::size_t>(set.tileSize);
  const PieceSet pieces = standardPieces();
  std::vector<PieceTiling> tilings;
  for (const Piece& piece : pieces.pieces) {
    tilings.push_back(pieceTiling(piece));
  }
  if (tamper) {
    tamper(tilings);
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
      const Instance in{&piece, &tilings[p], 1000 * static_cast<std::uint32_t>(p) + joint,
                        kStretches[joint % kStretches.size()]};
      for (const auto& [a, b] : edges) {
        const std::vector<std::size_t> both = quadsWithEdge(piece, a, b);
        if (both.size() == 2) {
          compare(seamTexels(set, in, both[0], a, b), seamTexels(set, in, both[1], a, b), count);
        }
      }
      for (std::size_t q = 0; q < piece.quads.size(); ++q) {
        const std::uint32_t repeat = tileRepeat(tilings[p], q, in.stretch);
        for (std::uint32_t sub = 1; sub < repeat; ++sub) {
          std::vector<std::array<int, 3>> below;
          std::vector<std::array<int, 3>> above;
          for (int x = 0; x < set.tileSize; ++x) {
            below.push_back(subTileTexel(set, in, q, sub - 1, x, set.tileSize - 1));
            above.push_back(subTileTexel(set, in, q, sub, x, 0));
          }
          compare(below, above, count);
          ++count.inner;
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
          const Instance a{&parent, &tilings[pp], 7 + seeds / 3, kStretches[seeds % kStretches.size()]};
          const Instance b{&child, &tilings[pc], 50 + seeds % 3, kStretches[(seeds + 3) % kStretches.size()]};
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
    EXPECT_GT(count.inner, 2000u);
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

TEST(BarkTest, TheSeamCheckFindsSubTilesThatDoNotLineUp) {
  // One quad of the I piece takes one more tile along its grain than its ring: its sides no longer meet its
  // neighbours' sub-tiles.
  const BarkSet set = synthesisedSet(2);
  const SeamCount count =
      countSeams(set, [](std::vector<PieceTiling>& tilings) { tilings[0].repeat[7][0] += 16; });
  EXPECT_GT(count.mismatches, 10u);
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
