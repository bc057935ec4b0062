#include <sylva/terrain/TileSelection.hpp>
#include <sylva/terrain/TileSource.hpp>
#include <sylva/terrain/TileStreamer.hpp>

#include <sylva/core/Error.hpp>

#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <vector>

namespace sylva::terrain {
namespace {

using test::sameBits;

ProceduralSpec worldSpec() {
  ProceduralSpec spec = defaultLandscapeSpec(7);
  spec.heightScale = 600.0f;
  return spec;
}

TEST(ProceduralWorld, CoarseTilesAreLevelZeroSamplesBitForBit) {
  const ProceduralWorld world(worldSpec(), 1025, 2.0f, 16);
  const PyramidInfo& info = world.layout();
  EXPECT_EQ(info.levels, 7);
  EXPECT_EQ(ProceduralWorld(worldSpec()).layout().levels, 15) << "2^20 samples in tiles of 64";
  std::mt19937 rng(1);
  for (int k = 0; k < 40; ++k) {
    const int level = 1 + static_cast<int>(rng() % 6);
    const PyramidLevel l = info.level(level);
    const TileKey key{level, static_cast<int>(rng() % static_cast<unsigned>(l.tilesX)),
                      static_cast<int>(rng() % static_cast<unsigned>(l.tilesY))};
    const auto tile = world.loadTile(key);
    for (int b = 0; b <= 16; b += 5) {
      for (int a = 0; a <= 16; a += 3) {
        const int i = (key.x * 16 + a) << level;
        const int j = (key.y * 16 + b) << level;
        const auto base = world.loadTile({0, std::min(i / 16, 63), std::min(j / 16, 63)});
        const float want = base->at(i - std::min(i / 16, 63) * 16, j - std::min(j / 16, 63) * 16);
        ASSERT_TRUE(sameBits(tile->at(a, b), want)) << level << " " << a << "," << b;
      }
    }
  }
  // The query is the bilinear surface of level 0.
  const auto tile = world.loadTile({0, 3, 5});
  EXPECT_EQ(world.heightAt(3 * 16 * 2.0 + 4.0, 5 * 16 * 2.0 + 6.0), tile->at(2, 3));
  EXPECT_THROW((void)ProceduralWorld(worldSpec(), 1025, 2.0f, 24), Error);
}

/** Leaf footprints in level-0 tile units, for coverage checks. */
struct Cover {
  int x0, y0, size, level;
};

/**
 * Checks the selection's invariants: leaves tile the level-0 tile grid exactly once (when nothing is culled),
 * every drawn tile is resident, neighbours differ by at most one level, and the coarser-edge flags say
 * exactly where the neighbour is coarser.
 */
void expectValid(const PyramidInfo& info, const TileSelection& selection,
                 const std::function<bool(const TileKey&)>& resident, bool full) {
  const PyramidLevel base = info.level(0);
  std::vector<int> owner(static_cast<std::size_t>(base.tilesX) * base.tilesY, -1);
  for (std::size_t n = 0; n < selection.tiles.size(); ++n) {
    const TileKey& key = selection.tiles[n].key;
    ASSERT_TRUE(resident(key)) << key.level << "/" << key.y << "/" << key.x;
    for (int y = key.y << key.level; y < std::min((key.y + 1) << key.level, base.tilesY); ++y) {
      for (int x = key.x << key.level; x < std::min((key.x + 1) << key.level, base.tilesX); ++x) {
        int& o = owner[static_cast<std::size_t>(y) * base.tilesX + x];
        ASSERT_EQ(o, -1) << "two tiles cover level-0 tile " << x << "," << y;
        o = static_cast<int>(n);
      }
    }
  }
  const auto levelAt = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= base.tilesX || y >= base.tilesY) {
      return -2;
    }
    const int o = owner[static_cast<std::size_t>(y) * base.tilesX + x];
    return o < 0 ? -1 : selection.tiles[static_cast<std::size_t>(o)].key.level;
  };
  for (const SelectedTile& t : selection.tiles) {
    const int L = t.key.level;
    const int x0 = t.key.x << L;
    const int y0 = t.key.y << L;
    const int span = 1 << L;
    // Level-0 cells just outside each edge (west, north, east, south).
    for (int e = 0; e < 4; ++e) {
      bool coarser = false;
      for (int k = 0; k < span; ++k) {
        const int x = e == 0 ? x0 - 1 : e == 2 ? x0 + span : x0 + k;
        const int y = e == 1 ? y0 - 1 : e == 3 ? y0 + span : y0 + k;
        const int n = levelAt(x, y);
        if (n < 0) {
          continue;
        }
        ASSERT_LE(std::abs(n - L), 1) << "tiles " << L << " and " << n << " meet";
        coarser = coarser || n == L + 1;
      }
      if (coarser) {
        EXPECT_TRUE(t.coarserEdges & (1u << e))
            << "edge " << e << " of " << L << "/" << t.key.y << "/" << t.key.x;
      } else if (full) {
        EXPECT_FALSE(t.coarserEdges & (1u << e))
            << "edge " << e << " of " << L << "/" << t.key.y << "/" << t.key.x;
      }
    }
  }
  if (full) {
    EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0) << "holes in the cover";
  }
}

TEST(TileSelection, CoversTheWorldOnceRestrictedWithResidentTilesOnly) {
  const ProceduralWorld world(worldSpec(), 4097, 1.0f, 16);
  const PyramidInfo& info = world.layout();
  const auto summary = [&](const TileKey& k) { return world.tileSummary(k); };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> pos(-200.0, 4300.0);
  std::uniform_real_distribution<double> alt(5.0, 2000.0);
  int withMissing = 0;
  int coarsened = 0;
  for (int view = 0; view < 150; ++view) {
    const glm::dvec3 camera(pos(rng), alt(rng), pos(rng));
    // Resident: everything, or a random third of the tiles below the top levels.
    const bool all = view % 3 == 0;
    const unsigned salt = rng();
    const auto resident = [&](const TileKey& k) {
      if (all || k.level >= info.levels - 2) {
        return true;
      }
      const unsigned h = static_cast<unsigned>(k.level * 73856093) ^ static_cast<unsigned>(k.x * 19349663) ^
                         static_cast<unsigned>(k.y * 83492791) ^ salt;
      return (h * 2654435761u >> 16) % 3 != 0;
    };
    TileLodConfig config;
    config.lodDistanceFactor = 1.0f + static_cast<float>(view % 4);
    const TileSelection selection = selectTiles(info, summary, resident, camera, nullptr, config);
    SCOPED_TRACE(testing::Message() << "view " << view);
    expectValid(info, selection, resident, true);
    if (all) {
      EXPECT_TRUE(selection.missing.empty());
    }
    withMissing += selection.missing.empty() ? 0 : 1;
    coarsened += selection.coarsened;
    for (const TileKey& m : selection.missing) {
      EXPECT_FALSE(resident(m));
    }
  }
  EXPECT_GT(withMissing, 50) << "stand-ins must be exercised";
  EXPECT_GT(coarsened, 0) << "the restriction pass must be exercised";
}

TEST(TileSelection, FrustumCullingKeepsTheVisiblePartRestricted) {
  const ProceduralWorld world(worldSpec(), 4097, 1.0f, 16);
  const PyramidInfo& info = world.layout();
  const auto summary = [&](const TileKey& k) { return world.tileSummary(k); };
  const auto resident = [](const TileKey&) { return true; };
  const glm::dvec3 camera(2000.0, 700.0, 2000.0);
  const glm::mat4 proj = glm::perspective(glm::radians(50.0f), 16.0f / 9.0f, 1.0f, 20000.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), glm::vec3(1.0f, -0.4f, 0.3f), glm::vec3(0, 1, 0));
  const Frustum frustum(proj * view);
  const TileSelection culled = selectTiles(info, summary, resident, camera, &frustum, {});
  const TileSelection whole = selectTiles(info, summary, resident, camera, nullptr, {});
  EXPECT_GT(culled.culled, 0);
  EXPECT_LT(culled.tiles.size(), whole.tiles.size());
  expectValid(info, culled, resident, false);
}

TEST(TileStreamer, StaysWithinItsBudgetAndKeepsPinnedTiles) {
  auto world = std::make_shared<ProceduralWorld>(worldSpec(), 4097, 1.0f, 16);
  const std::size_t tileBytes = 17 * 17 * sizeof(float) + sizeof(TileData);
  TileStreamer streamer(world, 200 * tileBytes, 2);
  EXPECT_LT(streamer.pinnedLevel(), world->layout().levels - 1);
  const StreamerStats start = streamer.stats();
  EXPECT_EQ(start.residentTiles, start.loaded);
  const TileKey kept{0, 5, 5};
  streamer.request(kept, 0.0f);
  streamer.waitIdle();
  ASSERT_TRUE(streamer.holds(kept));
  streamer.pin(kept);
  for (int round = 0; round < 4; ++round) {
    streamer.beginFrame();
    for (int k = 0; k < 150; ++k) {
      streamer.request({0, 10 + k % 50, round * 3 + k / 50}, static_cast<float>(k));
    }
    streamer.waitIdle();
    const StreamerStats s = streamer.stats();
    EXPECT_LE(s.residentBytes, 200 * tileBytes);
  }
  const StreamerStats end = streamer.stats();
  EXPECT_GT(end.evicted, 0u);
  EXPECT_TRUE(streamer.holds(kept)) << "a pinned tile is never dropped";
  EXPECT_TRUE(streamer.holds({world->layout().levels - 1, 0, 0}));
  const auto tile = streamer.get({0, 59, 11}); // the last request of the last round
  ASSERT_NE(tile, nullptr);
  EXPECT_EQ(tile->key, (TileKey{0, 59, 11}));
  EXPECT_EQ(tile->heights, world->loadTile({0, 59, 11})->heights);
  EXPECT_THROW(TileStreamer(world, 2 * tileBytes), Error);
}

} // namespace
} // namespace sylva::terrain
