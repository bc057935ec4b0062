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
  const std::vector<std::uint32_t> table = quadTileTable(y);
  const std::vector<std::uint8_t> rotations = quadTileRotations(y);
  ASSERT_EQ(table.size(), y.quads.size());
  std::set<std::uint32_t> classes;
  for (std::size_t q = 0; q < table.size(); ++q) {
    EXPECT_EQ(table[q] & 255u, y.tileClass[q]);
    EXPECT_EQ(table[q] >> 8, rotations[q]);
    classes.insert(table[q] & 255u);
  }
  EXPECT_EQ(classes.size(), 3u) << "the fork has plain, fork and crotch quads";
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

/** The tiles a quad of class `c` may show (classes without tiles show class 0's, as the renderer does). */
std::vector<std::uint32_t> tilesOf(const BarkSet& set, std::uint32_t c) {
  c = std::min<std::uint32_t>(c, SYLVA_TREE_MAX_TILE_CLASSES - 1);
  if (set.classCount[c] == 0) {
    c = 0;
  }
  std::vector<std::uint32_t> out;
  for (std::uint32_t i = 0; i < set.classCount[c]; ++i) {
    out.push_back(set.classFirst[c] + i);
  }
  return out;
}

int cornerOf(const std::array<std::uint32_t, 4>& quad, std::uint32_t vertex) {
  for (int c = 0; c < 4; ++c) {
    if (quad[static_cast<std::size_t>(c)] == vertex) {
      return c;
    }
  }
  return -1;
}

/** The quad of `piece` with the edge (a, b) and the corner indices of a and b in it. */
std::tuple<std::size_t, int, int> quadWithEdge(const Piece& piece, std::uint32_t a, std::uint32_t b) {
  for (std::size_t q = 0; q < piece.quads.size(); ++q) {
    const int ca = cornerOf(piece.quads[q], a);
    const int cb = cornerOf(piece.quads[q], b);
    if (ca >= 0 && cb >= 0 && ((ca + 1) % 4 == cb || (cb + 1) % 4 == ca)) {
      return {q, ca, cb};
    }
  }
  ADD_FAILURE() << piece.name << ": no quad with edge " << a << "-" << b;
  return {0, 0, 1};
}

/** Shared edges whose texels differ, over every pair of tiles the two quads may show. */
struct SeamCount {
  std::size_t edges = 0;
  std::size_t comparisons = 0;
  std::size_t mismatches = 0;
};

void compareSeam(const BarkSet& set, const Piece& pa, std::size_t qa, int a0, int a1, const Piece& pb,
                 std::size_t qb, int b0, int b1, SeamCount& count) {
  const int ra = quadTileRotations(pa)[qa];
  const int rb = quadTileRotations(pb)[qb];
  ++count.edges;
  for (std::uint32_t ta : tilesOf(set, pa.tileClass[qa])) {
    for (std::uint32_t tb : tilesOf(set, pb.tileClass[qb])) {
      ++count.comparisons;
      if (edgeTexels(set.colour[ta], ra, a0, a1) != edgeTexels(set.colour[tb], rb, b0, b1)) {
        ++count.mismatches;
      }
    }
  }
}

/** Every shared edge inside every piece and across every rim (all six rotations of every child). */
SeamCount countSeams(const BarkSet& set) {
  SeamCount count;
  const PieceSet pieces = standardPieces();
  for (const Piece& piece : pieces.pieces) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> byEdge;
    for (std::size_t q = 0; q < piece.quads.size(); ++q) {
      for (std::size_t e = 0; e < 4; ++e) {
        const std::uint32_t a = piece.quads[q][e];
        const std::uint32_t b = piece.quads[q][(e + 1) % 4];
        byEdge[{std::min(a, b), std::max(a, b)}].push_back(q);
      }
    }
    for (const auto& [edge, quads] : byEdge) {
      if (quads.size() != 2) {
        continue; // rim edges: checked across pieces below
      }
      const auto& qa = piece.quads[quads[0]];
      const auto& qb = piece.quads[quads[1]];
      compareSeam(set, piece, quads[0], cornerOf(qa, edge.first), cornerOf(qa, edge.second), piece, quads[1],
                  cornerOf(qb, edge.first), cornerOf(qb, edge.second), count);
    }
  }
  for (const Piece& parent : pieces.pieces) {
    for (std::size_t rim = 1; rim < parent.rims.size(); ++rim) {
      for (const Piece& child : pieces.pieces) {
        for (int rot = 0; rot < kRimCorners; ++rot) {
          for (int k = 0; k < kRimCorners; ++k) {
            // Parent leaf corner k meets child root corner k − rot.
            const auto& pr = parent.rims[rim].vertices;
            const auto& cr = child.rims[0].vertices;
            const auto [qp, p0, p1] = quadWithEdge(parent, pr[static_cast<std::size_t>(k)],
                                                   pr[static_cast<std::size_t>((k + 1) % 6)]);
            const auto c0 = static_cast<std::size_t>((k - rot + 12) % 6);
            const auto c1 = static_cast<std::size_t>((k + 1 - rot + 12) % 6);
            const auto [qc, d0, d1] = quadWithEdge(child, cr[c0], cr[c1]);
            const bool aFirst =
                parent.quads[qp][static_cast<std::size_t>(p0)] == pr[static_cast<std::size_t>(k)];
            const bool bFirst = child.quads[qc][static_cast<std::size_t>(d0)] == cr[c0];
            // Read both from the vertex at corner k to the one at corner k + 1.
            compareSeam(set, parent, qp, aFirst ? p0 : p1, aFirst ? p1 : p0, child, qc, bFirst ? d0 : d1,
                        bFirst ? d1 : d0, count);
          }
        }
      }
    }
  }
  return count;
}

BarkSet synthesisedSet() {
  texsynth::TileSettings settings;
  settings.tileSize = 32;
  settings.seed = 7;
  const std::vector<texsynth::Texture> photos{texsynth::proceduralBark(128, 3)};
  return barkSetFromTiles(texsynth::barkTileSet(photos, 3, settings), "procedural");
}

TEST(BarkTest, AdjacentQuadsMeetTexelForTexelOnEveryPieceAndAcrossEveryRim) {
  const BarkSet set = synthesisedSet();
  ASSERT_EQ(set.colour.size(), 9u);
  ASSERT_EQ(set.normal.size(), 9u);
  const SeamCount count = countSeams(set);
  EXPECT_GT(count.edges, 1000u);
  EXPECT_GT(count.comparisons, 10000u);
  EXPECT_EQ(count.mismatches, 0u) << "of " << count.comparisons << " tile pairs on " << count.edges
                                  << " edges";
  // The tiles differ inside, or the set would be one repeated tile.
  EXPECT_FALSE(set.colour[0] == set.colour[1]);
}

TEST(BarkTest, TheSeamCheckFindsABrokenEdge) {
  BarkSet set = synthesisedSet();
  // One texel on tile 0's left edge (not a corner) changes: every seam that tile takes part in breaks.
  set.colour[0].set(0, set.tileSize / 3, 0, 1.0f - set.colour[0].get(0, set.tileSize / 3, 0));
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
  EXPECT_EQ(sets[0].colour.size(), 6u);
  sources.mode = "/nonexistent/tileset";
  EXPECT_THROW((void)barkSetsFor(forest, sources, speciesSet), Error);
}

} // namespace
} // namespace sylva::trees
