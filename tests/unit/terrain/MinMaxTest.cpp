#include <sylva/terrain/MinMax.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "TestUtil.hpp"

namespace sylva::terrain {
namespace {

using test::kNaN;

// Random heights in [-50, 450] m (negative: bathymetry) with a fraction of absent samples and one absent
// block.
HeightField randomField(int w, int h, std::uint64_t seed, float nanFraction) {
  HeightField f(w, h);
  Rng rng(seed);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      f.at(i, j) = rng.uniform() < nanFraction ? kNaN : rng.uniform(-50.0f, 450.0f);
    }
  }
  // A fully absent block so that all-absent queries happen.
  for (int j = h / 4; j < h / 2; ++j) {
    for (int i = w / 4; i < w / 2; ++i) {
      f.at(i, j) = kNaN;
    }
  }
  return f;
}

void expectSame(const HeightRange& actual, const HeightRange& expected, const char* what) {
  ASSERT_EQ(actual.present(), expected.present()) << what;
  if (expected.present()) {
    ASSERT_EQ(actual.min, expected.min) << what;
    ASSERT_EQ(actual.max, expected.max) << what;
  } else {
    ASSERT_TRUE(std::isnan(actual.min) && std::isnan(actual.max)) << what << ": absent must be a NaN pair";
  }
}

TEST(MinMaxTest, HeightRangeIgnoresNaNAndUnions) {
  HeightRange r;
  EXPECT_FALSE(r.present());
  r.include(kNaN);
  EXPECT_FALSE(r.present());
  r.include(3.0f);
  r.include(-2.0f);
  r.include(kNaN);
  EXPECT_TRUE(r.present());
  EXPECT_EQ(r.min, -2.0f);
  EXPECT_EQ(r.max, 3.0f);
  HeightRange other{5.0f, 7.0f};
  r.include(other);
  r.include(HeightRange::absent());
  EXPECT_EQ(r, (HeightRange{-2.0f, 7.0f}));
  EXPECT_EQ(HeightRange::absent(), HeightRange::absent());
}

TEST(MinMaxTest, RmqMatchesBruteForceOnRandomFieldsWithNaNs) {
  const int sizes[][2] = {{1, 1}, {1, 17}, {23, 1}, {37, 53}, {64, 64}, {129, 70}};
  std::uint64_t seed = 10;
  for (const auto& s : sizes) {
    const HeightField f = randomField(s[0], s[1], ++seed, 0.2f);
    const MinMaxRmq rmq(f);
    EXPECT_EQ(rmq.memoryBytes(), MinMaxRmq::requiredBytes(s[0], s[1]));
    Rng rng(seed * 7);
    for (int q = 0; q < 2000; ++q) {
      int i0 = static_cast<int>(rng.below(static_cast<std::uint32_t>(s[0])));
      int i1 = static_cast<int>(rng.below(static_cast<std::uint32_t>(s[0])));
      int j0 = static_cast<int>(rng.below(static_cast<std::uint32_t>(s[1])));
      int j1 = static_cast<int>(rng.below(static_cast<std::uint32_t>(s[1])));
      if (i0 > i1) {
        std::swap(i0, i1);
      }
      if (j0 > j1) {
        std::swap(j0, j1);
      }
      expectSame(rmq.query(i0, i1, j0, j1), scanRange(f, i0, i1, j0, j1), "rmq");
    }
  }
}

TEST(MinMaxTest, RmqReportsAbsentForAllNaNRectangle) {
  HeightField f(16, 16, 1.0f, 1.0f, 10.0f);
  for (int j = 2; j <= 9; ++j) {
    for (int i = 3; i <= 12; ++i) {
      f.at(i, j) = kNaN;
    }
  }
  const MinMaxRmq rmq(f);
  EXPECT_FALSE(rmq.query(3, 12, 2, 9).present());
  EXPECT_TRUE(std::isnan(rmq.query(4, 11, 3, 8).min));
  EXPECT_EQ(rmq.query(2, 12, 2, 9), (HeightRange{10.0f, 10.0f})); // one valid column
}

TEST(MinMaxTest, RmqRejectsAbsurdSizesAndBadQueries) {
  const HeightField f(300, 200);
  EXPECT_THROW(MinMaxRmq(f, 1 << 20), sylva::Error); // needs ~30 MiB
  EXPECT_THROW(MinMaxRmq{HeightField{}}, sylva::Error);
  // 65536² would need ~3.6·10^12 bytes: refused without allocating.
  EXPECT_GT(MinMaxRmq::requiredBytes(65536, 65536), std::size_t{1} << 40);
  const MinMaxRmq rmq(f);
  EXPECT_THROW(static_cast<void>(rmq.query(-1, 3, 0, 0)), sylva::Error);
  EXPECT_THROW(static_cast<void>(rmq.query(0, 300, 0, 0)), sylva::Error);
  EXPECT_THROW(static_cast<void>(rmq.query(5, 4, 0, 0)), sylva::Error);
}

TEST(MinMaxTest, RmqMemoryIsNLogSquaredN) {
  // Σ_k (n − 2^k + 1) per axis: 64 → 7·65 − 127 = 328 entries; 8 bytes per entry pair.
  EXPECT_EQ(MinMaxRmq::requiredBytes(64, 64), std::size_t{328} * 328 * 8);
  EXPECT_EQ(MinMaxRmq::requiredBytes(1, 1), std::size_t{8});
}

HeightRange pyramidBrute(const HeightField& f, int leaf, int level, int bx, int bz) {
  const int block = leaf << level;
  return scanRange(f, bx * block, bx * block + block, bz * block, bz * block + block);
}

TEST(MinMaxTest, PyramidNodesMatchBruteForce) {
  const int leaves[] = {1, 5, 8, 16};
  std::uint64_t seed = 100;
  for (const int leaf : leaves) {
    const HeightField f = randomField(203, 117, ++seed, 0.3f);
    const MinMaxPyramid p(f, leaf);
    EXPECT_EQ(p.leafSize(), leaf);
    EXPECT_EQ(p.blocksX(0), (203 - 1 + leaf - 1) / leaf);
    EXPECT_EQ(p.blocksZ(0), (117 - 1 + leaf - 1) / leaf);
    ASSERT_EQ(p.blocksX(p.levelCount() - 1), 1);
    ASSERT_EQ(p.blocksZ(p.levelCount() - 1), 1);
    int absent = 0;
    for (int level = 0; level < p.levelCount(); ++level) {
      for (int bz = 0; bz < p.blocksZ(level); ++bz) {
        for (int bx = 0; bx < p.blocksX(level); ++bx) {
          const HeightRange expected = pyramidBrute(f, leaf, level, bx, bz);
          absent += expected.present() ? 0 : 1;
          expectSame(p.node(level, bx, bz), expected, "pyramid node");
        }
      }
    }
    if (leaf <= 5) {
      EXPECT_GT(absent, 0) << "the absent block must produce absent nodes";
    }
    // Outside the grid: absent.
    EXPECT_FALSE(p.node(0, -1, 0).present());
    EXPECT_FALSE(p.node(0, p.blocksX(0), 0).present());
  }
}

TEST(MinMaxTest, PyramidBoundContainsExactRangeAndIsExactWhenAligned) {
  const HeightField f = randomField(150, 97, 7, 0.1f);
  const MinMaxPyramid p(f, 8);
  Rng rng(3);
  for (int q = 0; q < 5000; ++q) {
    int i0 = static_cast<int>(rng.below(150));
    int i1 = static_cast<int>(rng.below(150));
    int j0 = static_cast<int>(rng.below(97));
    int j1 = static_cast<int>(rng.below(97));
    if (i0 > i1) {
      std::swap(i0, i1);
    }
    if (j0 > j1) {
      std::swap(j0, j1);
    }
    const HeightRange exact = scanRange(f, i0, i1, j0, j1);
    const HeightRange b = p.bound(i0, i1, j0, j1);
    if (exact.present()) {
      ASSERT_TRUE(b.present()) << i0 << " " << i1 << " " << j0 << " " << j1;
      ASSERT_LE(b.min, exact.min);
      ASSERT_GE(b.max, exact.max);
    }
  }
  for (int level = 0; level < 3; ++level) {
    const int block = 8 << level;
    for (int bz = 0; bz * block < 96; ++bz) {
      for (int bx = 0; bx * block < 149; ++bx) {
        expectSame(p.bound(bx * block, std::min(bx * block + block, 149), bz * block,
                           std::min(bz * block + block, 96)),
                   p.node(level, bx, bz), "aligned bound");
      }
    }
  }
  EXPECT_THROW(static_cast<void>(p.bound(5, 4, 0, 0)), sylva::Error);
  const MinMaxPyramid noLeaf = MinMaxPyramid::fromLeaves(2, 2, [](int, int) {
    return HeightRange{0.0f, 1.0f};
  });
  EXPECT_THROW(static_cast<void>(noLeaf.bound(0, 1, 0, 1)), sylva::Error);
}

TEST(MinMaxTest, PyramidFromLeavesEqualsFieldPyramid) {
  const HeightField f = randomField(65, 33, 9, 0.2f);
  const MinMaxPyramid a(f, 4);
  const MinMaxPyramid b = MinMaxPyramid::fromLeaves(
      16, 8, [&](int x, int z) { return scanRange(f, 4 * x, 4 * x + 4, 4 * z, 4 * z + 4); }, 4);
  ASSERT_EQ(a.levelCount(), b.levelCount());
  for (int level = 0; level < a.levelCount(); ++level) {
    for (int z = 0; z < a.blocksZ(level); ++z) {
      for (int x = 0; x < a.blocksX(level); ++x) {
        expectSame(b.node(level, x, z), a.node(level, x, z), "fromLeaves");
      }
    }
  }
  EXPECT_EQ(a.memoryBytes(), b.memoryBytes());
}

TEST(MinMaxTest, PyramidMemoryIsAtMostOneSixteenthOfHeightmap) {
  const int sizes[][2] = {{1025, 1025}, {2049, 1000}, {513, 4097}, {1000, 999}};
  for (const auto& s : sizes) {
    const HeightField f(s[0], s[1], 1.0f, 1.0f, 5.0f);
    const std::size_t heightmapBytes = f.samples().size() * sizeof(float);
    for (const int leaf : {8, 16, 64}) {
      const MinMaxPyramid p(f, leaf);
      EXPECT_LE(p.memoryBytes() * 16, heightmapBytes) << s[0] << "×" << s[1] << " leaf " << leaf;
    }
  }
  // And the baseline does not fit that budget at all.
  EXPECT_GT(MinMaxRmq::requiredBytes(1025, 1025), std::size_t{1025} * 1025 * 4 * 16);
}

TEST(MinMaxTest, PyramidRejectsInvalidInput) {
  EXPECT_THROW(MinMaxPyramid(HeightField(4, 4), 0), sylva::Error);
  EXPECT_THROW((MinMaxPyramid{HeightField{}, 8}), sylva::Error);
  EXPECT_THROW(MinMaxPyramid::fromLeaves(0, 3, [](int, int) { return HeightRange{}; }), sylva::Error);
  EXPECT_THROW(MinMaxPyramid::fromLeaves(1 << 14, 1 << 14, [](int, int) { return HeightRange{}; }),
               sylva::Error);
}

} // namespace
} // namespace sylva::terrain
