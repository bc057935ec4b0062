// The far field's CPU twins: the hemi-octahedral mapping, the choice of baked views and their weights, the
// view frames, the far-tree lists.
#include <sylva/core/Error.hpp>
#include <sylva/trees/FarField.hpp>
#include <sylva/trees/ForestLook.hpp>
#include <sylva/trees/Forest.hpp>
#include <sylva/trees/Tree.hpp>
#include <sylva/wind/Wind.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <map>

namespace sylva::trees {
namespace {

glm::vec3 randomDirection(Rng& rng) {
  for (;;) {
    const glm::vec3 v(rng.uniform(-1.0f, 1.0f), rng.uniform(0.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
    const float l = glm::length(v);
    if (l > 0.05f && l <= 1.0f) {
      return v / l;
    }
  }
}

TEST(FarFieldTest, HemiOctahedralMappingRoundTrips) {
  Rng rng(7);
  for (int k = 0; k < 2000; ++k) {
    const glm::vec3 d = randomDirection(rng);
    const glm::vec2 uv = hemiOctEncode(d);
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LE(uv.x, 1.0f);
    ASSERT_GE(uv.y, 0.0f);
    ASSERT_LE(uv.y, 1.0f);
    EXPECT_LT(glm::length(hemiOctDecode(uv) - d), 1e-5f) << k;
    // And from the square: decode then encode.
    const glm::vec2 q(rng.uniform(), rng.uniform());
    EXPECT_LT(glm::length(hemiOctEncode(hemiOctDecode(q)) - q), 1e-5f);
  }
  // Landmarks: straight up is the centre, the horizon the square's edge.
  EXPECT_LT(glm::length(hemiOctEncode({0, 1, 0}) - glm::vec2(0.5f)), 1e-6f);
  EXPECT_LT(glm::length(hemiOctEncode({1, 0, 0}) - glm::vec2(1.0f, 1.0f)), 1e-6f);
  EXPECT_LT(glm::length(hemiOctEncode({0, 0, 1}) - glm::vec2(1.0f, 0.0f)), 1e-6f);
  // Below the horizon clamps onto it.
  EXPECT_LT(glm::length(hemiOctEncode(glm::normalize(glm::vec3(1, -0.5f, 0))) - glm::vec2(1.0f)), 1e-6f);
}

TEST(FarFieldTest, BakedViewsAreTheGridVertices) {
  const int views = 8;
  for (int j = 0; j < views; ++j) {
    for (int i = 0; i < views; ++i) {
      const glm::vec3 d = impostorViewDirection({i, j}, views);
      EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
      EXPECT_GE(d.y, 0.0f);
      // Looking from exactly a baked direction selects that view alone.
      const ImpostorViews v = impostorViews(d, views);
      float own = 0.0f;
      for (int k = 0; k < 3; ++k) {
        own += v.cells[static_cast<std::size_t>(k)] == glm::ivec2(i, j) ? v.weights[k] : 0.0f;
      }
      EXPECT_NEAR(own, 1.0f, 1e-4f) << i << "," << j;
    }
  }
}

/** The weight of `cell` in a selection (0 when not among the three). */
float weightOf(const ImpostorViews& v, glm::ivec2 cell) {
  float w = 0.0f;
  for (int k = 0; k < 3; ++k) {
    w += v.cells[static_cast<std::size_t>(k)] == cell ? v.weights[k] : 0.0f;
  }
  return w;
}

TEST(FarFieldTest, ViewWeightsSumToOneAndVaryContinuously) {
  const int views = 8;
  Rng rng(11);
  float worst = 0.0f;
  for (int k = 0; k < 3000; ++k) {
    const glm::vec3 d = randomDirection(rng);
    const ImpostorViews a = impostorViews(d, views);
    EXPECT_NEAR(a.weights.x + a.weights.y + a.weights.z, 1.0f, 1e-5f);
    EXPECT_GE(glm::min(a.weights.x, glm::min(a.weights.y, a.weights.z)), -1e-6f);
    // Continuity: a tiny turn changes every view's weight a little, even across triangle edges (the
    // weight of a view that drops out has fallen to ~0).
    const glm::vec3 e = glm::normalize(d + 1e-3f * randomDirection(rng));
    const ImpostorViews b = impostorViews(e, views);
    for (int m = 0; m < 3; ++m) {
      for (const ImpostorViews* s : {&a, &b}) {
        const glm::ivec2 cell = s->cells[static_cast<std::size_t>(m)];
        worst = std::max(worst, std::abs(weightOf(a, cell) - weightOf(b, cell)));
      }
    }
  }
  // 1e-3 rad moves the grid point by at most ~(views − 1) · 1e-3 · 2 cells: weights change by less than 0.03.
  EXPECT_LT(worst, 0.03f);
}

TEST(FarFieldTest, ViewBasesAreRightHandedAndOrthonormal) {
  for (int j = 0; j < 9; ++j) {
    for (int i = 0; i < 9; ++i) {
      const glm::vec3 f = impostorViewDirection({i, j}, 9);
      const ImpostorBasis b = impostorBasis(f);
      EXPECT_NEAR(glm::length(b.right), 1.0f, 1e-5f);
      EXPECT_NEAR(glm::length(b.up), 1.0f, 1e-5f);
      EXPECT_NEAR(glm::dot(b.right, b.up), 0.0f, 1e-5f);
      EXPECT_NEAR(glm::dot(b.right, f), 0.0f, 1e-5f);
      EXPECT_LT(glm::length(glm::cross(b.right, b.up) - f), 1e-5f);
      // Upright wherever the view is not straight down on the tree.
      if (f.y < 0.999f) {
        EXPECT_GT(b.up.y, 0.0f);
      }
    }
  }
  // Atlas pixels: the cell's centre and corners.
  const ImpostorLayout layout{4, 32};
  EXPECT_EQ(impostorAtlasPixel({2, 1}, {0, 0}, layout), glm::vec2(80.0f, 48.0f));
  EXPECT_EQ(impostorAtlasPixel({2, 1}, {-1, 1}, layout), glm::vec2(64.0f, 64.0f));
}

TEST(FarFieldTest, YawRotateTurnsLikeTheBaseFrame) {
  for (float yaw : {0.0f, 0.7f, 2.5f, -1.2f}) {
    const glm::mat4 base = baseFrame(glm::vec3(3, 1, 2), yaw, 1.0f);
    const glm::vec3 v(0.3f, 1.2f, -0.8f);
    EXPECT_LT(glm::length(glm::vec3(base * glm::vec4(v, 0.0f)) - yawRotate(v, yaw)), 1e-5f);
  }
}

TEST(FarFieldTest, FarTreesMatchTheForest) {
  const Forest forest = gridForest({"almond", "apple"}, 3, 5.0f, 3);
  const std::vector<FarTree> far = farTrees(forest);
  ASSERT_EQ(far.size(), forest.trees.size());
  for (std::size_t i = 0; i < far.size(); ++i) {
    const ForestTree& t = forest.trees[i];
    EXPECT_EQ(far[i].id, i);
    EXPECT_EQ(far[i].species, t.species);
    EXPECT_FALSE(far[i].farOnly);
    EXPECT_EQ(far[i].position, glm::vec3(t.base[3]));
    const float scale = glm::length(glm::vec3(t.base[0]));
    EXPECT_EQ(far[i].height, treeStats(forest.pieces, t.topology).height * scale);
    EXPECT_GT(far[i].height, 1.0f);
    // The yaw turns the impostor as the base frame turns the tree.
    const glm::vec3 x = glm::vec3(t.base[0]) / scale;
    EXPECT_LT(glm::length(yawRotate({1, 0, 0}, far[i].yaw) - x), 1e-5f);
  }
}

TEST(FarFieldTest, FarTreeFieldIsDeterministicAndFillsTheAnnulus) {
  FarTreeFieldSettings s;
  s.count = 100000;
  s.seed = 9;
  s.centre = {100.0f, -50.0f};
  s.innerRadius = 300.0f;
  s.outerRadius = 3000.0f;
  s.species = 3;
  s.firstId = 40;
  const std::vector<FarTree> a = farTreeField(s);
  const std::vector<FarTree> b = farTreeField(s);
  ASSERT_EQ(a.size(), 100000u);
  std::map<int, int> bySpecies;
  int inner = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].position, b[i].position);
    EXPECT_EQ(a[i].height, b[i].height);
    EXPECT_EQ(a[i].species, b[i].species);
    EXPECT_EQ(a[i].yaw, b[i].yaw);
    EXPECT_EQ(a[i].id, 40u + i);
    EXPECT_TRUE(a[i].farOnly);
    const float r = glm::length(glm::vec2(a[i].position.x, a[i].position.z) - s.centre);
    EXPECT_GE(r, s.innerRadius - 0.01f);
    EXPECT_LE(r, s.outerRadius + 0.01f);
    EXPECT_EQ(a[i].position.y, 0.0f);
    EXPECT_GE(a[i].height, s.minHeight);
    EXPECT_LE(a[i].height, s.maxHeight);
    bySpecies[a[i].species] += 1;
    inner += r < 0.5f * (s.innerRadius + s.outerRadius) ? 1 : 0;
  }
  EXPECT_EQ(bySpecies.size(), 3u);
  // Uniform by area: the inner half of the radii holds (1650² − 300²) / (3000² − 300²) = 29.6 % of the trees.
  EXPECT_NEAR(static_cast<double>(inner) / 100000.0, 0.296, 0.01);
  s.seed = 10;
  EXPECT_NE(farTreeField(s)[0].position, a[0].position);
  // On terrain: heights from the field, everything on the footprint.
  terrain::HeightField field(65, 65, 10.0f, 10.0f);
  for (int j = 0; j < 65; ++j) {
    for (int i = 0; i < 65; ++i) {
      field.at(i, j) = static_cast<float>(i) * 2.0f;
    }
  }
  FarTreeFieldSettings t;
  t.count = 1000;
  t.centre = {320.0f, 320.0f};
  t.outerRadius = 300.0f;
  t.verticalScale = 1.5f;
  for (const FarTree& f : farTreeField(t, &field)) {
    EXPECT_NEAR(f.position.y, f.position.x / 10.0f * 2.0f * 1.5f, 1e-3f);
  }
  t.innerRadius = 400.0f;
  t.outerRadius = 300.0f;
  EXPECT_THROW(farTreeField(t), Error);
}

// The impostor-only trees of --trees-far-count continue the forest: inside its height band, and without a top
// to the band no higher than the forest's highest tree (they once climbed the whole terrain onto the snow).
TEST(FarFieldTest, FarFieldTreesKeepToTheForestsHeightBand) {
  terrain::HeightField field(65, 65, 10.0f, 10.0f); // a ramp from 0 m (west) to 128 m (east)
  for (int j = 0; j < 65; ++j) {
    for (int i = 0; i < 65; ++i) {
      field.at(i, j) = static_cast<float>(i) * 2.0f;
    }
  }
  Forest forest = gridForest({"almond"}, 2, 5.0f, 3);
  for (ForestTree& t : forest.trees) {
    t.base[3] = glm::vec4(320.0f + t.base[3].x, 64.0f, 320.0f + t.base[3].z, 1.0f); // the highest tree: 64 m
  }
  ForestLook look;
  look.farCount = 4000;
  ForestSettings placement;
  placement.regionCentre = {320.0f, 320.0f};
  placement.regionRadius = 60.0f;
  const FarGround ground{&field, std::nullopt};
  const auto heights = [&] {
    float lo = 1e30f;
    float hi = -1e30f;
    const std::vector<FarTree> far = farFieldTrees(look, placement, forest, {}, ground);
    for (const FarTree& t : far) {
      lo = std::min(lo, t.position.y);
      hi = std::max(hi, t.position.y);
    }
    return std::tuple{far.size(), lo, hi};
  };
  const auto [count, lo, hi] = heights();
  EXPECT_GT(count, 1000u);
  EXPECT_LE(hi, 64.0f) << "above the forest's highest tree";
  EXPECT_LT(lo, 10.0f) << "the band has no floor: down to the low end of the ramp";
  placement.minHeight = 20.0f;
  placement.maxHeight = 100.0f;
  const auto [bandCount, bandLo, bandHi] = heights();
  EXPECT_GT(bandCount, 1000u);
  EXPECT_GE(bandLo, 20.0f);
  EXPECT_LE(bandHi, 100.0f);
  EXPECT_GT(bandHi, 90.0f) << "a given top replaces the forest's highest tree";
}

// Far trees sway (issue 30: impostors stood still while the pieces they replace bent): a species' lean per
// squared wind speed is calibrated on its joint springs in a steady wind, so a far tree leans about as much
// as its near twin bends; the lean grows as the square of the speed while the bends stay small, follows the
// wind's direction, is capped, and no two trees lean in unison in gusty wind.
TEST(FarFieldTest, FarTreesLeanAsMuchAsTheirNearTwinsBend) {
  for (const char* species : {"almond", "california-black-oak"}) {
    const Forest forest = gridForest({species}, 1, 5.0f, 3);
    const ImpostorSway gentle = calibrateImpostorSway(forest, 0, 3.0f);
    const ImpostorSway fresh = calibrateImpostorSway(forest, 0, 5.0f);
    const float lean3 = gentle.perSpeedSquared * 9.0f;
    const float lean5 = fresh.perSpeedSquared * 25.0f;
    std::printf("%s: lean %.4f at 3 m/s, %.4f at 5 m/s (k %.5f, %.5f per (m/s)^2)\n", species, lean3, lean5,
                gentle.perSpeedSquared, fresh.perSpeedSquared);
    // docs/trees.md: the springs bend a tree's top by a few tenths of a per cent (a 13 m oak) to about 2 % (a
    // 6 m almond) of its height at 3 m/s.
    EXPECT_GT(lean3, 0.002f) << species;
    EXPECT_LT(lean3, 0.08f) << species;
    // Small bends: the response is quadratic in the speed, k is nearly the same at both speeds.
    EXPECT_NEAR(fresh.perSpeedSquared / gentle.perSpeedSquared, 1.0f, 0.2f) << species;
    EXPECT_EQ(calibrateImpostorSway(forest, 0, 3.0f).perSpeedSquared, gentle.perSpeedSquared)
        << "deterministic";
  }
  EXPECT_THROW((void)calibrateImpostorSway(gridForest({"almond"}, 1, 5.0f, 3), 1), Error);

  ImpostorSway sway;
  sway.perSpeedSquared = 0.002f;
  FarTree tree;
  tree.position = glm::vec3(40.0f, 3.0f, -25.0f);
  tree.id = 17;
  wind::WindSettings steady;
  steady.direction = glm::vec2(0.0f, 1.0f);
  steady.speed = 5.0f;
  steady.gustStrength = 0.0f;
  steady.turbulence = 0.0f;
  const glm::vec2 lean = impostorLean(tree, sway, wind::toUniforms(steady, 2.0f));
  EXPECT_NEAR(lean.x, 0.0f, 1e-6f);
  EXPECT_NEAR(lean.y, 0.002f * 25.0f, 1e-5f) << "k |u| u downwind";
  steady.speed = 0.0f;
  EXPECT_EQ(impostorLean(tree, sway, wind::toUniforms(steady, 2.0f)), glm::vec2(0.0f)) << "still air";
  EXPECT_EQ(impostorLean(tree, ImpostorSway{}, wind::toUniforms(wind::WindSettings{}, 2.0f)),
            glm::vec2(0.0f));
  steady.speed = 40.0f;
  EXPECT_NEAR(glm::length(impostorLean(tree, sway, wind::toUniforms(steady, 2.0f))), sway.maxLean, 1e-5f)
      << "capped";

  // Gusty wind: trees side by side lean differently at one moment, and a tree's lean changes over time.
  wind::WindSettings gusty;
  gusty.speed = 6.0f;
  FarTree neighbour = tree;
  neighbour.id = 18;
  neighbour.position.x += 1.0f;
  const gpu::WindUniforms now = wind::toUniforms(gusty, 10.0f);
  EXPECT_GT(glm::length(impostorLean(tree, sway, now) - impostorLean(neighbour, sway, now)), 1e-3f);
  EXPECT_GT(
      glm::length(impostorLean(tree, sway, now) - impostorLean(tree, sway, wind::toUniforms(gusty, 11.5f))),
      1e-3f);
  EXPECT_NE(impostorWindOffset(17), impostorWindOffset(18));
  EXPECT_GE(impostorWindOffset(0xffffffffu), 0.0f);
  EXPECT_LT(impostorWindOffset(0xffffffffu), 600.0f);

  // The sheared sphere holds the sheared tree: a point on the unleaned sphere moved by the shear stays
  // inside.
  const glm::vec4 sphere(2.0f, 9.0f, -1.0f, 6.0f);
  const glm::vec2 l(0.2f, -0.1f);
  const glm::vec4 leaned = impostorLeanedSphere(sphere, 3.0f, l);
  for (int i = 0; i < 64; ++i) {
    const float a = static_cast<float>(i) * 0.7f;
    const float b = static_cast<float>(i) * 1.3f;
    const glm::vec3 p = glm::vec3(sphere) + sphere.w * glm::vec3(std::cos(a) * std::cos(b), std::sin(b),
                                                                 std::sin(a) * std::cos(b));
    const glm::vec3 q = p + glm::vec3(l.x, 0.0f, l.y) * (p.y - 3.0f);
    EXPECT_LE(glm::distance(q, glm::vec3(leaned)), leaned.w + 1e-4f);
  }
}

} // namespace
} // namespace sylva::trees
