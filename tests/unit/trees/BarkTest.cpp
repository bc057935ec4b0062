// Bark tile placement rules (docs/trees.md "Bark"): tile rotations put the tile's y axis along the branch,
// tile coordinates map quad corners onto tile corners without mirroring, tile choice stays within the class.
#include <sylva/core/Error.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/Pieces.hpp>

#include <gtest/gtest.h>

#include <map>
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

} // namespace
} // namespace sylva::trees
