#include <sylva/terrain/Quadtree.hpp>

#include <sylva/terrain/Geomorph.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/ScreenError.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include "TestUtil.hpp"

namespace sylva::terrain {
namespace {

using test::kNaN;

// A non-square, non-power-of-two field (301×187 samples, 1.5 m × 2 m spacing → 450 m × 372 m) of rolling
// hills in [~5, ~125] m with a round hole of absent samples (nodata) near the north-east corner.
HeightField rollingField() {
  HeightField f(301, 187, 1.5f, 2.0f);
  Rng rng(77);
  for (int j = 0; j < f.height(); ++j) {
    for (int i = 0; i < f.width(); ++i) {
      const float x = static_cast<float>(i) * f.spacingX();
      const float z = static_cast<float>(j) * f.spacingZ();
      const bool hole = (i - 250) * (i - 250) + (j - 30) * (j - 30) < 28 * 28;
      f.at(i, j) = hole ? kNaN
                        : 65.0f + 40.0f * std::sin(0.03f * x) * std::cos(0.02f * z) +
                              15.0f * std::sin(0.11f * x + 0.07f * z) + rng.uniform(-2.0f, 2.0f);
    }
  }
  return f;
}

QuadtreeConfig rollingConfig() {
  QuadtreeConfig c;
  c.rootSize = 64.0f; // 8×6 roots derived from the 450×372 m extent, covering 512×384 m
  c.maxDepth = 4;     // leaves down to 4 m
  c.lodDistanceFactor = 2.0f;
  c.patchTessLevel = 8;
  return c;
}

struct Camera {
  glm::vec3 position{0.0f};
  Frustum frustum;
};

Camera randomCamera(Rng& rng, float extentX, float extentZ, float minY, float maxY) {
  Camera c;
  c.position = glm::vec3(rng.uniform(-0.2f * extentX, 1.2f * extentX), rng.uniform(minY, maxY),
                         rng.uniform(-0.2f * extentZ, 1.2f * extentZ));
  const float yaw = rng.uniform(0.0f, 6.2831853f);
  const float pitch = rng.uniform(-1.2f, 0.3f);
  const glm::vec3 dir(std::cos(pitch) * std::cos(yaw), std::sin(pitch), std::cos(pitch) * std::sin(yaw));
  c.frustum = Frustum(glm::perspective(glm::radians(60.0f), 16.0f / 9.0f, 0.5f, 3000.0f) *
                      glm::lookAt(c.position, c.position + dir, glm::vec3(0, 1, 0)));
  return c;
}

// Integer geometry of a node in units of the deepest node size.
struct IntNode {
  long long x0;
  long long z0;
  long long size;
};

IntNode intNode(const Quadtree& qt, int level, int gridX, int gridZ) {
  const long long s = 1LL << (qt.config().maxDepth - level);
  return IntNode{gridX * s, gridZ * s, s};
}

// Exact positions (reduced fractions, deepest-node units) of the vertices a patch edge of integer start
// `start`, length `len` and outer level `n` places inside [lo, hi].
std::vector<std::pair<long long, long long>> edgeVertices(long long start, long long len, long long n,
                                                          long long lo, long long hi) {
  std::vector<std::pair<long long, long long>> out;
  for (long long k = 0; k <= n; ++k) {
    const long long num = start * n + k * len;
    if (num >= lo * n && num <= hi * n) {
      const long long g = std::gcd(num, n);
      out.emplace_back(num / g, n / g);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct EdgeReport {
  int pairs = 0;                 // (leaf, edge, neighbour leaf) incidences with a shared segment
  int levelJumps = 0;            // of which the neighbours differ by exactly one depth
  int restrictionViolations = 0; // of which they differ by more than one depth
  int crackedEdges = 0;          // of which the vertex sets on the shared segment differ
  int overlaps = 0;              // deepest-node cells covered by more than one leaf
  int badLevels = 0;             // outer/inner levels outside 1..64 or not integral
};

// The crack-freedom property: for every pair of edge-adjacent selected leaves, the vertex positions each side
// places on their shared segment (corner + k·size/outerLevel) are the same set.
EdgeReport analyse(const Quadtree& qt, const std::vector<SelectedNode>& nodes) {
  EdgeReport r;
  const int depth = qt.config().maxDepth;
  const int w = qt.gridWidth(depth);
  const int h = qt.gridHeight(depth);
  std::vector<int> owner(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), -1);
  const auto cell = [&](long long x, long long z) -> int& {
    return owner[static_cast<std::size_t>(z) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
  };
  std::vector<IntNode> geo;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const SelectedNode& n = nodes[i];
    geo.push_back(intNode(qt, n.level, n.gridX, n.gridZ));
    for (int e = 0; e < 4; ++e) {
      const float t = n.tessOuter[static_cast<std::size_t>(e)];
      r.badLevels += (t < 1.0f || t > 64.0f || t != std::floor(t)) ? 1 : 0;
    }
    r.badLevels += (n.tessInner < 1.0f || n.tessInner > 32.0f) ? 1 : 0;
    const IntNode& g = geo.back();
    for (long long z = g.z0; z < g.z0 + g.size; ++z) {
      for (long long x = g.x0; x < g.x0 + g.size; ++x) {
        r.overlaps += cell(x, z) >= 0 ? 1 : 0;
        cell(x, z) = static_cast<int>(i);
      }
    }
  }
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    const IntNode& ga = geo[a];
    for (int e = 0; e < 4; ++e) {
      int last = -1;
      for (long long t = 0; t < ga.size; ++t) {
        long long cx = 0;
        long long cz = 0;
        switch (e) {
        case kEdgeWest:
          cx = ga.x0 - 1;
          cz = ga.z0 + t;
          break;
        case kEdgeNorth:
          cx = ga.x0 + t;
          cz = ga.z0 - 1;
          break;
        case kEdgeEast:
          cx = ga.x0 + ga.size;
          cz = ga.z0 + t;
          break;
        default:
          cx = ga.x0 + t;
          cz = ga.z0 + ga.size;
          break;
        }
        if (cx < 0 || cz < 0 || cx >= w || cz >= h) {
          continue;
        }
        const int b = cell(cx, cz);
        if (b < 0 || b == last) {
          continue;
        }
        last = b;
        const IntNode& gb = geo[static_cast<std::size_t>(b)];
        const bool alongZ = e == kEdgeWest || e == kEdgeEast;
        const long long a0 = alongZ ? ga.z0 : ga.x0;
        const long long b0 = alongZ ? gb.z0 : gb.x0;
        const long long lo = std::max(a0, b0);
        const long long hi = std::min(a0 + ga.size, b0 + gb.size);
        if (hi <= lo) {
          continue;
        }
        ++r.pairs;
        const int jump = std::abs(nodes[a].level - nodes[static_cast<std::size_t>(b)].level);
        r.levelJumps += jump == 1 ? 1 : 0;
        r.restrictionViolations += jump > 1 ? 1 : 0;
        const auto na = static_cast<long long>(nodes[a].tessOuter[static_cast<std::size_t>(e)]);
        const auto nb = static_cast<long long>(
            nodes[static_cast<std::size_t>(b)].tessOuter[static_cast<std::size_t>((e + 2) % 4)]);
        if (edgeVertices(a0, ga.size, na, lo, hi) != edgeVertices(b0, gb.size, nb, lo, hi)) {
          ++r.crackedEdges;
        }
      }
    }
  }
  return r;
}

QuadtreeConfig withPolicy(QuadtreeConfig c, CrackMethod method, int tess, float factor, bool cull) {
  c.method = method;
  c.patchTessLevel = tess;
  c.lodDistanceFactor = factor;
  c.frustumCull = cull;
  return c;
}

TEST(QuadtreeTest, SharedEdgesHaveIdenticalVerticesFromBothSides) {
  const HeightField field = rollingField();
  Quadtree qt(rollingConfig(), field);
  ASSERT_EQ(qt.config().rootsX, 8);
  ASSERT_EQ(qt.config().rootsZ, 6);
  Rng rng(2024);
  long long jumps = 0;
  long long doubled = 0;
  for (int cam = 0; cam < 200; ++cam) {
    const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), -10.0f, 250.0f);
    const float factor = cam % 5 == 0 ? kMinRestrictedLodFactor : rng.uniform(kMinRestrictedLodFactor, 3.0f);
    const bool cull = cam % 2 == 0;
    for (const CrackMethod method : {CrackMethod::PaperSearch, CrackMethod::RestrictedLevelMap}) {
      for (int tess = 1; tess <= kMaxPatchTessLevel; ++tess) {
        qt.setConfig(withPolicy(qt.config(), method, tess, factor, cull));
        const QuadtreeSelection sel = qt.select(c.position, &c.frustum);
        const EdgeReport r = analyse(qt, sel.nodes);
        ASSERT_EQ(r.crackedEdges, 0) << "camera " << cam << " " << crackMethodName(method) << " tess "
                                     << tess;
        ASSERT_EQ(r.restrictionViolations, 0) << "camera " << cam;
        ASSERT_EQ(r.overlaps, 0) << "camera " << cam;
        ASSERT_EQ(r.badLevels, 0) << "camera " << cam;
        jumps += r.levelJumps;
        doubled += sel.stats.doubledEdges;
      }
    }
  }
  // The property must not hold vacuously: many edges join leaves of different depth.
  EXPECT_GT(jumps, 10000);
  EXPECT_GT(doubled, 5000);
}

TEST(QuadtreeTest, CrackCheckDetectsCracksWithoutStitching) {
  const HeightField field = rollingField();
  Quadtree qt(rollingConfig(), field);
  Rng rng(2024);
  int crackedSelections = 0;
  int selectionsWithJumps = 0;
  for (int cam = 0; cam < 200; ++cam) {
    const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), -10.0f, 250.0f);
    for (const int tess : {1, 7, 32}) {
      qt.setConfig(withPolicy(qt.config(), CrackMethod::None, tess, 2.0f, cam % 2 == 0));
      const QuadtreeSelection sel = qt.select(c.position, &c.frustum);
      const EdgeReport r = analyse(qt, sel.nodes);
      EXPECT_EQ(sel.stats.doubledEdges, 0);
      if (r.levelJumps > 0) {
        ++selectionsWithJumps;
        // Every depth change is a T-junction when nothing is stitched.
        EXPECT_EQ(r.crackedEdges, r.levelJumps) << "camera " << cam;
      }
      crackedSelections += r.crackedEdges > 0 ? 1 : 0;
    }
  }
  EXPECT_GT(selectionsWithJumps, 300);
  EXPECT_EQ(crackedSelections, selectionsWithJumps);
}

// Split nodes are exactly the strict ancestors of selected leaves and culled nodes; an edge is doubled iff
// the same-depth square across it was split. This reference walks no tree and builds no map.
std::vector<std::uint32_t> referenceEdgeFlags(const Quadtree& qt, const QuadtreeSelection& sel) {
  std::set<std::tuple<int, int, int>> split;
  const auto addAncestors = [&](int level, int x, int z) {
    for (int l = level - 1; l >= 0; --l) {
      x >>= 1;
      z >>= 1;
      split.emplace(l, x, z);
    }
  };
  for (const SelectedNode& n : sel.nodes) {
    addAncestors(n.level, n.gridX, n.gridZ);
  }
  for (const NodeId& n : sel.culled) {
    addAncestors(n.level, n.gridX, n.gridZ);
  }
  std::vector<std::uint32_t> flags;
  const int dx[] = {-1, 0, 1, 0};
  const int dz[] = {0, -1, 0, 1};
  for (const SelectedNode& n : sel.nodes) {
    std::uint32_t f = 0;
    for (int e = 0; e < 4; ++e) {
      const int x = n.gridX + dx[e];
      const int z = n.gridZ + dz[e];
      if (x >= 0 && z >= 0 && x < qt.gridWidth(n.level) && z < qt.gridHeight(n.level) &&
          split.count({n.level, x, z}) > 0) {
        f |= 1u << e;
      }
    }
    flags.push_back(f);
  }
  return flags;
}

TEST(QuadtreeTest, BothMethodsProduceIdenticalTessFactors) {
  const HeightField field = rollingField();
  Quadtree qt(rollingConfig(), field);
  Rng rng(99);
  long long paperSteps = 0;
  long long mapSteps = 0;
  for (int cam = 0; cam < 500; ++cam) {
    const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), -10.0f, 400.0f);
    const float factor = rng.uniform(kMinRestrictedLodFactor, 4.0f);
    const int tess = 1 + static_cast<int>(rng.below(32));
    const bool cull = cam % 3 != 0;
    qt.setConfig(withPolicy(qt.config(), CrackMethod::PaperSearch, tess, factor, cull));
    const QuadtreeSelection paper = qt.select(c.position, &c.frustum);
    qt.setConfig(withPolicy(qt.config(), CrackMethod::RestrictedLevelMap, tess, factor, cull));
    const QuadtreeSelection map = qt.select(c.position, &c.frustum);
    ASSERT_EQ(paper.nodes.size(), map.nodes.size()) << "camera " << cam;
    const std::vector<std::uint32_t> reference = referenceEdgeFlags(qt, map);
    for (std::size_t i = 0; i < paper.nodes.size(); ++i) {
      const SelectedNode& a = paper.nodes[i];
      const SelectedNode& b = map.nodes[i];
      ASSERT_EQ(std::tie(a.level, a.gridX, a.gridZ), std::tie(b.level, b.gridX, b.gridZ)) << "camera " << cam;
      ASSERT_EQ(a.edgeFlags, b.edgeFlags) << "camera " << cam << " node " << i;
      ASSERT_EQ(a.edgeFlags, reference[i]) << "camera " << cam << " node " << i;
      ASSERT_EQ(a.tessOuter, b.tessOuter) << "camera " << cam << " node " << i;
      ASSERT_EQ(a.tessInner, b.tessInner);
      ASSERT_EQ(a.x, b.x);
      ASSERT_EQ(a.z, b.z);
      ASSERT_EQ(a.size, b.size);
    }
    paperSteps += paper.stats.neighbourSteps;
    mapSteps += map.stats.neighbourSteps;
  }
  // The search walks the tree; the map reads about one slot per edge.
  EXPECT_GT(paperSteps, mapSteps);
}

// A flat field with one narrow 800 m needle: plain CDLOD box distances split the boxes that reach the
// needle's height and leave flat neighbours coarse, two or more depths apart.
HeightField needleField() {
  HeightField f(257, 257, 4.0f, 4.0f, 0.0f);
  for (int j = 0; j < f.height(); ++j) {
    for (int i = 0; i < f.width(); ++i) {
      const float d2 = static_cast<float>((i - 150) * (i - 150) + (j - 150) * (j - 150));
      f.at(i, j) = 800.0f * std::exp(-d2 / 2.0f);
    }
  }
  return f;
}

TEST(QuadtreeTest, UnrestrictedSelectionBreaksTheDoublingRuleAndRestrictionFixesIt) {
  const HeightField field = needleField();
  QuadtreeConfig config;
  config.rootSize = 256.0f;
  config.maxDepth = 5;
  config.patchTessLevel = 4;
  config.lodDistanceFactor = 2.0f;
  config.frustumCull = false;
  config.restrictSelection = false;
  config.method = CrackMethod::PaperSearch;
  Quadtree plain(config, field);
  config.restrictSelection = true;
  Quadtree restricted(config, field);
  Rng rng(5);
  int violatingViews = 0;
  int crackedViews = 0;
  for (int cam = 0; cam < 100; ++cam) {
    const glm::vec3 pos(rng.uniform(560.0f, 640.0f), rng.uniform(780.0f, 900.0f),
                        rng.uniform(560.0f, 640.0f));
    for (const CrackMethod method : {CrackMethod::PaperSearch, CrackMethod::RestrictedLevelMap}) {
      QuadtreeConfig c = plain.config();
      c.method = method;
      plain.setConfig(c);
      const EdgeReport bad = analyse(plain, plain.select(pos, nullptr).nodes);
      violatingViews += bad.restrictionViolations > 0 ? 1 : 0;
      crackedViews += bad.crackedEdges > 0 ? 1 : 0;
      c.restrictSelection = true;
      restricted.setConfig(c);
      const EdgeReport good = analyse(restricted, restricted.select(pos, nullptr).nodes);
      ASSERT_EQ(good.restrictionViolations, 0) << "camera " << cam;
      ASSERT_EQ(good.crackedEdges, 0) << "camera " << cam;
    }
  }
  EXPECT_GT(violatingViews, 50);
  EXPECT_GT(crackedViews, 50) << "doubling alone cannot stitch leaves two depths apart";
}

TEST(QuadtreeTest, SelectionIsRestrictedForManyFactorsAndCameras) {
  const HeightField rolling = rollingField();
  const HeightField needle = needleField();
  Rng rng(31);
  for (const HeightField* field : {&rolling, &needle}) {
    QuadtreeConfig config = rollingConfig();
    config.rootSize = field == &needle ? 128.0f : 64.0f;
    config.maxDepth = 5;
    Quadtree qt(config, *field);
    for (int cam = 0; cam < 300; ++cam) {
      const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), -50.0f, 900.0f);
      const float factor = cam < 50 ? kMinRestrictedLodFactor : rng.uniform(kMinRestrictedLodFactor, 6.0f);
      qt.setConfig(withPolicy(qt.config(), CrackMethod::RestrictedLevelMap, 5, factor, cam % 2 == 0));
      const EdgeReport r = analyse(qt, qt.select(c.position, &c.frustum).nodes);
      ASSERT_EQ(r.restrictionViolations, 0) << "camera " << cam << " factor " << factor;
      ASSERT_EQ(r.crackedEdges, 0) << "camera " << cam;
    }
  }
}

// Deepest-node cells whose own footprint has data: exactly these must be covered by the leaves.
TEST(QuadtreeTest, LeavesTileTheValidAreaExactlyWithoutCulling) {
  const HeightField field = rollingField();
  Quadtree qt(rollingConfig(), field);
  const int depth = qt.config().maxDepth;
  Rng rng(8);
  for (int cam = 0; cam < 100; ++cam) {
    const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), 0.0f, 300.0f);
    qt.setConfig(
        withPolicy(qt.config(), CrackMethod::RestrictedLevelMap, 8, rng.uniform(1.05f, 3.0f), false));
    const QuadtreeSelection sel = qt.select(c.position, &c.frustum);
    EXPECT_EQ(sel.stats.nodesCulled, 0);
    std::vector<int> count(static_cast<std::size_t>(qt.gridWidth(depth) * qt.gridHeight(depth)), 0);
    for (const SelectedNode& n : sel.nodes) {
      ASSERT_TRUE(qt.nodeRange({n.level, n.gridX, n.gridZ}).present());
      const IntNode g = intNode(qt, n.level, n.gridX, n.gridZ);
      for (long long z = g.z0; z < g.z0 + g.size; ++z) {
        for (long long x = g.x0; x < g.x0 + g.size; ++x) {
          ++count[static_cast<std::size_t>(z * qt.gridWidth(depth) + x)];
        }
      }
    }
    int covered = 0;
    for (int z = 0; z < qt.gridHeight(depth); ++z) {
      for (int x = 0; x < qt.gridWidth(depth); ++x) {
        const int n = count[static_cast<std::size_t>(z * qt.gridWidth(depth) + x)];
        ASSERT_LE(n, 1) << "overlap at cell " << x << "," << z;
        if (qt.nodeRange({depth, x, z}).present()) {
          ASSERT_EQ(n, 1) << "hole at cell " << x << "," << z;
        }
        covered += n;
      }
    }
    EXPECT_GT(covered, 0);
  }
}

TEST(QuadtreeTest, FrustumCullingDropsExactlyTheNodesOutside) {
  const HeightField field = rollingField();
  Quadtree qt(rollingConfig(), field);
  const int depth = qt.config().maxDepth;
  Rng rng(12);
  int culledTotal = 0;
  for (int cam = 0; cam < 200; ++cam) {
    const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), 0.0f, 300.0f);
    qt.setConfig(withPolicy(qt.config(), CrackMethod::PaperSearch, 8, rng.uniform(1.05f, 3.0f), true));
    const QuadtreeSelection sel = qt.select(c.position, &c.frustum);
    ASSERT_EQ(static_cast<int>(sel.culled.size()), sel.stats.nodesCulled);
    culledTotal += sel.stats.nodesCulled;
    std::vector<int> count(static_cast<std::size_t>(qt.gridWidth(depth) * qt.gridHeight(depth)), 0);
    const auto cover = [&](const NodeId& id) {
      const IntNode g = intNode(qt, id.level, id.gridX, id.gridZ);
      for (long long z = g.z0; z < g.z0 + g.size; ++z) {
        for (long long x = g.x0; x < g.x0 + g.size; ++x) {
          ++count[static_cast<std::size_t>(z * qt.gridWidth(depth) + x)];
        }
      }
    };
    for (const NodeId& id : sel.culled) {
      ASSERT_EQ(c.frustum.test(qt.nodeBounds(id)), Containment::Outside) << "camera " << cam;
      cover(id);
    }
    for (const SelectedNode& n : sel.nodes) {
      const Aabb box = qt.nodeBounds({n.level, n.gridX, n.gridZ});
      ASSERT_TRUE(c.frustum.intersects(box)) << "camera " << cam;
      ASSERT_EQ(box.min.y, n.minY);
      ASSERT_EQ(box.max.y, n.maxY);
      cover({n.level, n.gridX, n.gridZ});
    }
    // Selected ∪ culled tile the valid area: no node that intersects the frustum was dropped.
    for (int z = 0; z < qt.gridHeight(depth); ++z) {
      for (int x = 0; x < qt.gridWidth(depth); ++x) {
        const int n = count[static_cast<std::size_t>(z * qt.gridWidth(depth) + x)];
        ASSERT_LE(n, 1);
        if (qt.nodeRange({depth, x, z}).present()) {
          ASSERT_EQ(n, 1) << "camera " << cam << " cell " << x << "," << z;
        }
      }
    }
  }
  EXPECT_GT(culledTotal, 500);
}

TEST(QuadtreeTest, LodDisabledSelectsEveryRootAtDepthZero) {
  // Square 512 m fields for 4, 16, 64 roots; 1024 m × 512 m for 32 (8×4 of 128 m): all roots hold data.
  const HeightField squareField(513, 513, 1.0f, 1.0f, 20.0f);
  const HeightField wideField(1025, 513, 1.0f, 1.0f, 20.0f);
  for (const int roots : {4, 16, 32, 64}) {
    const HeightField& field = roots == 32 ? wideField : squareField;
    QuadtreeConfig config = QuadtreeConfig::forRootCount(roots, field.extentX(), field.extentZ());
    config.lodEnabled = false;
    config.frustumCull = false;
    config.patchTessLevel = 32;
    config.maxDepth = 3;
    Quadtree qt(config, field);
    const QuadtreeSelection sel = qt.select(glm::vec3(10.0f, 21.0f, 10.0f), nullptr);
    EXPECT_EQ(qt.config().rootsX * qt.config().rootsZ, roots);
    ASSERT_EQ(static_cast<int>(sel.nodes.size()), roots);
    for (const SelectedNode& n : sel.nodes) {
      EXPECT_EQ(n.level, 0);
      EXPECT_EQ(n.edgeFlags, 0u);
      EXPECT_EQ(n.tessOuter, (std::array<float, 4>{32.0f, 32.0f, 32.0f, 32.0f}));
    }
    EXPECT_EQ(sel.stats.processedVertices, static_cast<std::uint64_t>(roots) * 33 * 33);
    EXPECT_EQ(sel.stats.controlPoints, static_cast<std::uint64_t>(roots) * 4);
  }
  EXPECT_EQ(QuadtreeConfig::forRootCount(32, 1024.0f, 512.0f).rootsX, 8);
  EXPECT_EQ(QuadtreeConfig::forRootCount(32, 1024.0f, 512.0f).rootsZ, 4);
  // 32 over a square: 8×4 roots of half the side; the half outside the data is dropped, never drawn at y = 0.
  const QuadtreeConfig square = QuadtreeConfig::forRootCount(32, 512.0f, 512.0f);
  EXPECT_EQ(square.rootsX, 8);
  EXPECT_EQ(square.rootsZ, 4);
  EXPECT_NEAR(square.rootSize, 128.0f, 0.01f);
  QuadtreeConfig c = square;
  c.lodEnabled = false;
  Quadtree qt(c, HeightField(513, 513, 1.0f, 1.0f, 20.0f));
  EXPECT_EQ(qt.select(glm::vec3(0.0f), nullptr).nodes.size(), 16u);
}

TEST(QuadtreeTest, TessConventionDoublesTheEdgeFacingTheFinerNeighbour) {
  // Three 100 m roots in a row along x; the camera over the east one splits the two eastern roots only.
  QuadtreeConfig config;
  config.rootSize = 100.0f;
  config.maxDepth = 1;
  config.lodDistanceFactor = 1.05f;
  config.patchTessLevel = 3;
  for (const CrackMethod method : {CrackMethod::PaperSearch, CrackMethod::RestrictedLevelMap}) {
    config.method = method;
    Quadtree alongX(config, HeightField(301, 101, 1.0f, 1.0f, 0.0f));
    const QuadtreeSelection x = alongX.select(glm::vec3(290.0f, 10.0f, 50.0f), nullptr);
    ASSERT_EQ(x.nodes.size(), 9u);
    EXPECT_EQ(x.nodes[0].level, 0);
    EXPECT_EQ(x.nodes[0].edgeFlags, 1u << kEdgeEast);
    EXPECT_EQ(x.nodes[0].tessOuter, (std::array<float, 4>{3.0f, 3.0f, 6.0f, 3.0f}));
    for (std::size_t i = 1; i < x.nodes.size(); ++i) {
      EXPECT_EQ(x.nodes[i].level, 1);
      EXPECT_EQ(x.nodes[i].edgeFlags, 0u);
    }
    // The same along z: the z-min root's z-max edge (v = 1, gl_TessLevelOuter[3]) is doubled.
    Quadtree alongZ(config, HeightField(101, 301, 1.0f, 1.0f, 0.0f));
    const QuadtreeSelection z = alongZ.select(glm::vec3(50.0f, 10.0f, 290.0f), nullptr);
    ASSERT_EQ(z.nodes.size(), 9u);
    EXPECT_EQ(z.nodes[0].gridZ, 0);
    EXPECT_EQ(z.nodes[0].tessOuter, (std::array<float, 4>{3.0f, 3.0f, 3.0f, 6.0f}));
    EXPECT_EQ(z.nodes[0].x, 0.0f);
    EXPECT_EQ(z.nodes[0].z, 0.0f);
    EXPECT_EQ(z.nodes[0].size, 100.0f);
    // And the mirror image doubles the west / north edges.
    Quadtree mirror(config, HeightField(301, 301, 1.0f, 1.0f, 0.0f));
    const QuadtreeSelection m = mirror.select(glm::vec3(10.0f, 10.0f, 10.0f), nullptr);
    for (const SelectedNode& n : m.nodes) {
      if (n.level == 0 && n.gridX == 2 && n.gridZ == 0) {
        EXPECT_EQ(n.edgeFlags, 1u << kEdgeWest);
      }
      if (n.level == 0 && n.gridX == 0 && n.gridZ == 2) {
        EXPECT_EQ(n.edgeFlags, 1u << kEdgeNorth);
      }
    }
  }
}

TEST(QuadtreeTest, NodeRangesCoverTheSamplesUnderTheFootprint) {
  const HeightField field = rollingField();
  const Quadtree qt(rollingConfig(), field);
  for (int level = 0; level <= qt.config().maxDepth; ++level) {
    const double size = qt.nodeSize(level);
    for (int gz = 0; gz < qt.gridHeight(level); ++gz) {
      for (int gx = 0; gx < qt.gridWidth(level); ++gx) {
        const double x0 = gx * size;
        const double z0 = gz * size;
        HeightRange expected;
        if (x0 < field.extentX() && z0 < field.extentZ()) {
          expected = scanRange(field, static_cast<int>(std::floor(x0 / field.spacingX())),
                               static_cast<int>(std::ceil((x0 + size) / field.spacingX())),
                               static_cast<int>(std::floor(z0 / field.spacingZ())),
                               static_cast<int>(std::ceil((z0 + size) / field.spacingZ())));
        }
        const HeightRange actual = qt.nodeRange({level, gx, gz});
        ASSERT_EQ(actual, expected) << level << " " << gx << " " << gz;
      }
    }
  }
}

TEST(QuadtreeTest, AbsentDataIsDroppedAndNeverTreatedAsZero) {
  // Heights in [100, 200] m over 300×200 m; roots cover 320×256 m; a band of nodata cuts the middle.
  HeightField field(301, 201, 1.0f, 1.0f);
  Rng rng(4);
  for (int j = 0; j < field.height(); ++j) {
    for (int i = 0; i < field.width(); ++i) {
      field.at(i, j) = (i >= 120 && i <= 170) ? kNaN : rng.uniform(100.0f, 200.0f);
    }
  }
  QuadtreeConfig config;
  config.rootSize = 64.0f;
  config.maxDepth = 4;
  config.frustumCull = false;
  Quadtree qt(config, field);
  EXPECT_EQ(qt.config().rootsX, 5);
  EXPECT_EQ(qt.config().rootsZ, 4);
  Rng camRng(6);
  int absent = 0;
  for (int cam = 0; cam < 50; ++cam) {
    const Camera c = randomCamera(camRng, 300.0f, 200.0f, 100.0f, 300.0f);
    const QuadtreeSelection sel = qt.select(c.position, nullptr);
    absent += sel.stats.nodesAbsent;
    for (const SelectedNode& n : sel.nodes) {
      ASSERT_GE(n.minY, 100.0f);
      ASSERT_LE(n.maxY, 200.0f);
      ASSERT_LT(n.x, 300.0f);
      ASSERT_LT(n.z, 200.0f);
      // Not wholly inside the nodata band: its samples [⌊x⌋, ⌈x + size⌉] reach outside [120, 170].
      ASSERT_TRUE(n.x < 120.0f || n.x + n.size > 170.0f) << n.x << " " << n.size;
    }
  }
  EXPECT_GT(absent, 50);
}

TEST(QuadtreeTest, StatsAreConsistentAndSelectionIsDeterministic) {
  const HeightField field = rollingField();
  Quadtree qt(rollingConfig(), field);
  Rng rng(1);
  for (int cam = 0; cam < 50; ++cam) {
    const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), 0.0f, 200.0f);
    const QuadtreeSelection a = qt.select(c.position, &c.frustum);
    QuadtreeSelection b;
    qt.select(c.position, &c.frustum, b);
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
      ASSERT_EQ(a.nodes[i].tessOuter, b.nodes[i].tessOuter);
      ASSERT_EQ(a.nodes[i].gridX, b.nodes[i].gridX);
    }
    const QuadtreeStats& s = a.stats;
    EXPECT_EQ(s.leaves, static_cast<int>(a.nodes.size()));
    EXPECT_EQ(s.nodesVisited, s.leaves + s.nodesSplit + s.nodesCulled);
    EXPECT_EQ(s.controlPoints, 4u * a.nodes.size());
    EXPECT_EQ(s.processedVertices, 81u * a.nodes.size());
    int doubled = 0;
    for (const SelectedNode& n : a.nodes) {
      doubled += std::popcount(n.edgeFlags);
      EXPECT_EQ(n.tessInner, 8.0f);
    }
    EXPECT_EQ(s.doubledEdges, doubled);
  }
}

TEST(QuadtreeTest, PrebuiltPyramidGivesTheSameSelection) {
  const HeightField field = rollingField();
  const QuadtreeConfig config = rollingConfig();
  Quadtree fromField(config, field);
  QuadtreeConfig resolved = fromField.config();
  const int depth = resolved.maxDepth;
  MinMaxPyramid pyramid =
      MinMaxPyramid::fromLeaves(fromField.gridWidth(depth), fromField.gridHeight(depth), [&](int x, int z) {
        return fromField.nodeRange({depth, x, z});
      });
  Quadtree prebuilt(resolved, field.extentX(), field.extentZ(), std::move(pyramid));
  EXPECT_EQ(prebuilt.memoryBytes(), fromField.memoryBytes());
  const glm::vec3 pos(100.0f, 90.0f, 150.0f);
  const QuadtreeSelection a = fromField.select(pos, nullptr);
  const QuadtreeSelection b = prebuilt.select(pos, nullptr);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].edgeFlags, b.nodes[i].edgeFlags);
    EXPECT_EQ(a.nodes[i].minY, b.nodes[i].minY);
  }
  // Wrong leaf grid: refused.
  MinMaxPyramid wrong = MinMaxPyramid::fromLeaves(3, 3, [](int, int) { return HeightRange{0.0f, 1.0f}; });
  EXPECT_THROW(Quadtree(resolved, field.extentX(), field.extentZ(), std::move(wrong)), sylva::Error);
}

TEST(QuadtreeTest, InvalidConfigsAreRejected) {
  const HeightField field(65, 65, 1.0f, 1.0f, 0.0f);
  const auto make = [&](auto mutate) {
    QuadtreeConfig c;
    c.rootSize = 32.0f;
    c.maxDepth = 2;
    mutate(c);
    return Quadtree(c, field);
  };
  EXPECT_NO_THROW(make([](QuadtreeConfig&) {}));
  EXPECT_THROW(make([](QuadtreeConfig& c) { c.patchTessLevel = 0; }), sylva::Error);
  EXPECT_THROW(make([](QuadtreeConfig& c) { c.patchTessLevel = 33; }), sylva::Error);
  EXPECT_THROW(make([](QuadtreeConfig& c) { c.lodDistanceFactor = 0.9f; }), sylva::Error);
  EXPECT_NO_THROW(make([](QuadtreeConfig& c) {
    c.lodDistanceFactor = 0.5f;
    c.restrictSelection = false;
  }));
  EXPECT_THROW(make([](QuadtreeConfig& c) { c.maxDepth = -1; }), sylva::Error);
  EXPECT_THROW(make([](QuadtreeConfig& c) { c.maxDepth = 20; }), sylva::Error); // 2^44 deepest nodes
  EXPECT_THROW(make([](QuadtreeConfig& c) { c.rootSize = 0.0f; }), sylva::Error);
  EXPECT_THROW(make([](QuadtreeConfig& c) { c.rootsX = 1; }), sylva::Error); // 32 m of 64 m covered
  EXPECT_THROW(Quadtree(QuadtreeConfig{}, HeightField(1, 5)), sylva::Error);
  EXPECT_THROW(QuadtreeConfig::forRootCount(0, 10.0f, 10.0f), sylva::Error);
  Quadtree qt = make([](QuadtreeConfig&) {});
  QuadtreeConfig changed = qt.config();
  changed.maxDepth = 3;
  EXPECT_THROW(qt.setConfig(changed), sylva::Error);
  changed = qt.config();
  changed.method = CrackMethod::None;
  EXPECT_NO_THROW(qt.setConfig(changed));
  EXPECT_EQ(qt.config().method, CrackMethod::None);
}

// ---------------------------------------------------------------------------------------------------------------
// Screen-space-error LOD (docs/terrain-lod.md, "Screen-space error")

QuadtreeConfig errorConfig(QuadtreeConfig c, float pixels, float pixelsPerRadian, int tess) {
  c.lodErrorPixels = pixels;
  c.pixelsPerRadian = pixelsPerRadian;
  c.patchTessLevel = tess;
  return c;
}

// The drawn patch is a triangulation of the lattice heights (spacing size / T); whichever diagonal the
// tessellator picks in a cell, the surface stays within nodeError of the surface the deepest patches draw
// (the finest lattice, triangulated either way). Checked densely for nodes of every depth.
TEST(QuadtreeTest, NodeErrorBoundsEveryTriangulationOfThePatch) {
  const HeightField field = rollingField();
  Rng rng(404);
  for (const int tess : {1, 3, 8}) {
    Quadtree qt(errorConfig(rollingConfig(), 1.0f, kDefaultPixelsPerRadian, tess), field);
    ASSERT_TRUE(qt.hasNodeErrors());
    ASSERT_EQ(qt.nodeErrorTessLevel(), tess);
    int checked = 0;
    for (int level = 0; level <= qt.config().maxDepth; ++level) {
      for (int k = 0; k < 12; ++k) {
        const NodeId id{level, static_cast<int>(rng.below(static_cast<std::uint32_t>(qt.gridWidth(level)))),
                        static_cast<int>(rng.below(static_cast<std::uint32_t>(qt.gridHeight(level))))};
        if (!qt.nodeRange(id).present()) {
          continue;
        }
        const float bound = qt.nodeError(id);
        const float size = qt.nodeSize(level);
        const float sigma = size / static_cast<float>(tess);
        const float x0 = static_cast<float>(id.gridX) * size;
        const float z0 = static_cast<float>(id.gridZ) * size;
        float worst = 0.0f;
        const int n = std::max(8, static_cast<int>(size / 0.5f)); // points every ≤ 0.5 m
        for (int b = 0; b <= n; ++b) {
          for (int a = 0; a <= n; ++a) {
            const float x = x0 + size * static_cast<float>(a) / static_cast<float>(n);
            const float z = z0 + size * static_cast<float>(b) / static_cast<float>(n);
            if (x > qt.extentX() || z > qt.extentZ()) {
              continue;
            }
            const int ca = std::min(static_cast<int>((x - x0) / sigma), tess - 1);
            const int cb = std::min(static_cast<int>((z - z0) / sigma), tess - 1);
            const float fx = (x - x0) / sigma - static_cast<float>(ca);
            const float fz = (z - z0) / sigma - static_cast<float>(cb);
            const auto h = [&](int i, int j) {
              return heightAt(field, x0 + static_cast<float>(ca + i) * sigma,
                              z0 + static_cast<float>(cb + j) * sigma);
            };
            const float h00 = h(0, 0);
            const float h10 = h(1, 0);
            const float h01 = h(0, 1);
            const float h11 = h(1, 1);
            // Diagonal 00–11 and diagonal 10–01.
            const float d1 = fz <= fx ? h00 + (h10 - h00) * fx + (h11 - h10) * fz
                                      : h00 + (h11 - h01) * fx + (h01 - h00) * fz;
            const float d2 = fx + fz <= 1.0f ? h00 + (h10 - h00) * fx + (h01 - h00) * fz
                                             : h11 + (h01 - h11) * (1.0f - fx) + (h10 - h11) * (1.0f - fz);
            if (std::isnan(h00) || std::isnan(h10) || std::isnan(h01) || std::isnan(h11)) {
              continue; // next to absent samples: the renderer fills them, the error covers valid cells
            }
            // The reference: the finest lattice triangulated either way (what the deepest patches draw).
            for (const float d : {d1, d2}) {
              const float gap = fullResolutionGap(field, {x, d, z}, qt.config().finestVertexSpacing());
              if (!std::isnan(gap)) {
                worst = std::max(worst, gap);
              }
            }
          }
        }
        ASSERT_LE(worst, bound + 1e-3f)
            << "tess " << tess << " node " << level << "/" << id.gridX << "/" << id.gridZ;
        ++checked;
        // Saturated: no child has a larger error.
        if (level < qt.config().maxDepth) {
          for (int c = 0; c < 4; ++c) {
            EXPECT_LE(qt.nodeError({level + 1, 2 * id.gridX + (c & 1), 2 * id.gridZ + (c >> 1)}), bound);
          }
        }
      }
    }
    EXPECT_GT(checked, 40);
  }
}

// A plane is drawn exactly by any patch: every error is ~0 and the selection keeps only the distance floor.
// A field whose deepest lattice is its sample grid has error 0 there (the patch is the full-resolution mesh).
TEST(QuadtreeTest, NodeErrorIsZeroWhereThePatchIsExact) {
  HeightField plane(129, 129, 1.0f, 1.0f);
  for (int j = 0; j < plane.height(); ++j) {
    for (int i = 0; i < plane.width(); ++i) {
      plane.at(i, j) = 3.0f + 0.25f * static_cast<float>(i) - 0.5f * static_cast<float>(j);
    }
  }
  QuadtreeConfig c;
  c.rootSize = 128.0f;
  c.maxDepth = 3; // leaves of 16 m with T = 16: the lattice is the 1 m sample grid
  c.patchTessLevel = 16;
  Quadtree flat(errorConfig(c, 1.0f, kDefaultPixelsPerRadian, 16), plane);
  for (int level = 0; level <= 3; ++level) {
    EXPECT_LE(flat.nodeError({level, 0, 0}), 1e-4f) << "level " << level;
  }
  const HeightField rough = rollingField();
  QuadtreeConfig r;
  r.rootSize = 48.0f; // the deepest lattice (12 m leaves, T = 8: 1.5 m) is not the 1.5 × 2 m sample grid
  r.maxDepth = 2;
  r.patchTessLevel = 8;
  Quadtree rolling(errorConfig(r, 1.0f, kDefaultPixelsPerRadian, 8), rough);
  EXPECT_GT(rolling.nodeError({1, 1, 1}), 0.0f);
  EXPECT_EQ(rolling.nodeError({2, 3, 3}), 0.0f); // the deepest level is the reference
  HeightField grid(65, 65, 2.0f, 2.0f);
  Rng rng(9);
  for (float& h : grid.samples()) {
    h = rng.uniform(0.0f, 10.0f);
  }
  QuadtreeConfig g;
  g.rootSize = 128.0f;
  g.maxDepth = 2; // 32 m leaves, T = 16: lattice spacing 2 m = the samples
  g.patchTessLevel = 16;
  Quadtree exact(errorConfig(g, 1.0f, kDefaultPixelsPerRadian, 16), grid);
  EXPECT_EQ(exact.nodeError({2, 1, 1}), 0.0f);
  EXPECT_GT(exact.nodeError({1, 0, 0}), 1.0f); // random heights: the coarser lattice misses them
}

// Every leaf the error rule keeps either projects its error to at most τ pixels from the camera (measured to
// its own box) or stops at the deepest level; the selection is restricted and crack-free for both methods,
// which select the same leaves, over random cameras, thresholds and projections.
TEST(QuadtreeTest, ScreenErrorSelectionMeetsItsThresholdAndStaysCrackFree) {
  const HeightField rolling = rollingField();
  const HeightField needle = needleField();
  Rng rng(2027);
  long long jumps = 0;
  long long finer = 0;
  for (const HeightField* field : {&rolling, &needle}) {
    QuadtreeConfig config = rollingConfig();
    config.rootSize = field == &needle ? 128.0f : 64.0f;
    config.maxDepth = 5;
    for (const int tess : {1, 4, 16}) {
      Quadtree qt(errorConfig(config, 1.0f, kDefaultPixelsPerRadian, tess), *field);
      for (int cam = 0; cam < 60; ++cam) {
        const Camera c = randomCamera(rng, qt.extentX(), qt.extentZ(), -50.0f, 900.0f);
        QuadtreeConfig policy = qt.config();
        policy.lodErrorPixels = rng.uniform(0.25f, 8.0f);
        policy.pixelsPerRadian = rng.uniform(200.0f, 2000.0f);
        policy.frustumCull = cam % 2 == 0;
        std::vector<SelectedNode> first;
        for (const CrackMethod method : {CrackMethod::PaperSearch, CrackMethod::RestrictedLevelMap}) {
          policy.method = method;
          qt.setConfig(policy);
          const QuadtreeSelection sel = qt.select(c.position, &c.frustum);
          const EdgeReport r = analyse(qt, sel.nodes);
          ASSERT_EQ(r.restrictionViolations, 0) << "camera " << cam << " tess " << tess;
          ASSERT_EQ(r.crackedEdges, 0) << "camera " << cam << " tess " << tess;
          jumps += r.levelJumps;
          for (const SelectedNode& n : sel.nodes) {
            if (n.level == qt.config().maxDepth) {
              continue;
            }
            const glm::vec3 lo(n.x, n.minY, n.z);
            const glm::vec3 hi(n.x + n.size, n.maxY, n.z + n.size);
            const float dist = glm::length(glm::max(glm::max(lo - c.position, c.position - hi), 0.0f));
            ASSERT_LE(policy.pixelsPerRadian * n.error, policy.lodErrorPixels * dist * 1.0001f + 1e-3f)
                << "camera " << cam << ": a leaf above the threshold was not split";
            ASSERT_GE(dist, kErrorLodDistanceFloor * n.size * 0.999f) << "camera " << cam;
            EXPECT_EQ(n.error, qt.nodeError({n.level, n.gridX, n.gridZ}));
          }
          if (method == CrackMethod::PaperSearch) {
            first = sel.nodes;
          } else {
            ASSERT_EQ(first.size(), sel.nodes.size()) << "camera " << cam;
            for (std::size_t i = 0; i < first.size(); ++i) {
              ASSERT_EQ(first[i].level, sel.nodes[i].level);
              ASSERT_EQ(first[i].gridX, sel.nodes[i].gridX);
              ASSERT_EQ(first[i].gridZ, sel.nodes[i].gridZ);
              ASSERT_EQ(first[i].tessOuter, sel.nodes[i].tessOuter);
            }
          }
        }
        // A stricter threshold never selects fewer leaves.
        QuadtreeConfig strict = policy;
        strict.lodErrorPixels = 0.5f * policy.lodErrorPixels;
        qt.setConfig(strict);
        const auto fine = qt.select(c.position, nullptr).nodes.size();
        qt.setConfig(policy);
        const auto coarse = qt.select(c.position, nullptr).nodes.size();
        EXPECT_GE(fine, coarse) << "camera " << cam;
        finer += fine > coarse ? 1 : 0;
      }
    }
  }
  EXPECT_GT(jumps, 2000) << "the property must not hold vacuously";
  EXPECT_GT(finer, 50) << "halving τ must refine many views";
}

// Flat ground needs no detail: at equal camera the error rule selects far fewer leaves than distance LOD.
// Geomorphing is off with it (a split changes at most τ pixels already).
TEST(QuadtreeTest, ScreenErrorSpendsLeavesWhereTheSurfaceNeedsThem) {
  HeightField field(513, 513, 2.0f, 2.0f);
  for (int j = 0; j < field.height(); ++j) {
    for (int i = 0; i < field.width(); ++i) {
      // Flat west half, rough east half.
      const float x = static_cast<float>(i) * 2.0f;
      const float z = static_cast<float>(j) * 2.0f;
      field.at(i, j) = i < 256 ? 10.0f : 10.0f + 8.0f * std::sin(0.21f * x) * std::cos(0.17f * z);
    }
  }
  QuadtreeConfig config;
  config.rootSize = 256.0f;
  config.maxDepth = 5;
  config.patchTessLevel = 8;
  config.lodDistanceFactor = 4.0f;
  config.frustumCull = false;
  Quadtree distance(config, field);
  Quadtree error(errorConfig(config, 1.0f, kDefaultPixelsPerRadian, 8), field);
  const glm::vec3 camera(150.0f, 30.0f, 512.0f); // over the flat half
  const QuadtreeSelection byDistance = distance.select(camera, nullptr);
  const QuadtreeSelection byError = error.select(camera, nullptr);
  int westDistance = 0;
  int westError = 0;
  // Leaves west of x = 384 m: their 3×3 neighbourhoods (the restriction's dilation) are flat too.
  for (const SelectedNode& n : byDistance.nodes) {
    westDistance += n.x + n.size <= 384.0f ? 1 : 0;
  }
  for (const SelectedNode& n : byError.nodes) {
    westError += n.x + n.size <= 384.0f ? 1 : 0;
  }
  int eastDistance = static_cast<int>(byDistance.nodes.size()) - westDistance;
  int eastError = static_cast<int>(byError.nodes.size()) - westError;
  EXPECT_GT(eastError, 0);
  EXPECT_GT(eastDistance, 0);
  EXPECT_LT(4 * westError, westDistance) << "flat half: " << westError << " vs " << westDistance;
  EXPECT_FALSE(GeomorphParams::of(error.config()).enabled);
  EXPECT_TRUE(GeomorphParams::of(distance.config()).enabled);
}

TEST(QuadtreeTest, PatchTrianglesFollowTheTessellatorsCount) {
  SelectedNode n;
  const auto levels = [&](float inner, std::array<float, 4> outer) {
    n.tessInner = inner;
    n.tessOuter = outer;
    return patchTriangles(n);
  };
  EXPECT_EQ(levels(1, {1, 1, 1, 1}), 2u);
  EXPECT_EQ(levels(1, {2, 1, 1, 1}), 5u);        // inner 1 becomes 2: a fan of 5 outer segments
  EXPECT_EQ(levels(2, {2, 2, 2, 2}), 8u);        // a 2×2 grid
  EXPECT_EQ(levels(16, {16, 16, 16, 16}), 512u); // 2·16²
  EXPECT_EQ(levels(16, {32, 16, 16, 16}), 528u); // a doubled edge adds its 16 extra segments
}

TEST(QuadtreeTest, ScreenErrorConfigsAreCheckedAndNeedErrors) {
  const HeightField field = rollingField();
  QuadtreeConfig c = rollingConfig();
  Quadtree plain(c, field);
  EXPECT_FALSE(plain.hasNodeErrors());
  EXPECT_EQ(plain.nodeError({0, 0, 0}), 0.0f);
  QuadtreeConfig e = errorConfig(plain.config(), 1.0f, kDefaultPixelsPerRadian, c.patchTessLevel);
  EXPECT_FALSE(plain.canSetConfig(e));
  EXPECT_THROW(plain.setConfig(e), sylva::Error);
  Quadtree withErrors(e, field);
  EXPECT_TRUE(withErrors.canSetConfig(e));
  QuadtreeConfig otherTess = e;
  otherTess.patchTessLevel = c.patchTessLevel + 1;
  EXPECT_FALSE(withErrors.canSetConfig(otherTess));
  EXPECT_THROW(withErrors.setConfig(otherTess), sylva::Error);
  QuadtreeConfig back = e;
  back.lodErrorPixels = 0.0f;
  back.patchTessLevel = 3;
  EXPECT_TRUE(withErrors.canSetConfig(back)); // distance LOD needs no errors
  for (const float bad : {-1.0f, 1001.0f, std::numeric_limits<float>::quiet_NaN()}) {
    QuadtreeConfig b = e;
    b.lodErrorPixels = bad;
    EXPECT_THROW(Quadtree(b, field), sylva::Error) << bad;
  }
  QuadtreeConfig noProjection = e;
  noProjection.pixelsPerRadian = 0.0f;
  EXPECT_THROW(Quadtree(noProjection, field), sylva::Error);
  EXPECT_NEAR(QuadtreeConfig::pixelsPerRadianFor(720.0f, glm::radians(50.0f)), kDefaultPixelsPerRadian, 0.5f);
  EXPECT_THROW(QuadtreeConfig::pixelsPerRadianFor(0.0f, 1.0f), sylva::Error);
  const MinMaxPyramid pyramid =
      MinMaxPyramid::fromLeaves(plain.gridWidth(c.maxDepth), plain.gridHeight(c.maxDepth), [](int, int) {
        return HeightRange{0.0f, 1.0f};
      });
  e.rootsX = plain.config().rootsX;
  e.rootsZ = plain.config().rootsZ;
  EXPECT_THROW(Quadtree(e, plain.extentX(), plain.extentZ(), pyramid), sylva::Error);
}

} // namespace
} // namespace sylva::terrain
