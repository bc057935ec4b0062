// The shore rule: depth from the height field and level, the band weight's shape, the slope, the swash
// texture coordinates (rows along depth contours, advance up the slope, tiling in metres) and the swash
// clock.
#include <sylva/core/Error.hpp>
#include <sylva/scene/Shore.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <limits>
#include <numbers>

namespace sylva::scene {
namespace {

/** A plane h = a·x + b·z + c on a w×h grid of `spacing` metres, times `scale`. */
terrain::HeightField plane(float a, float b, float c, int w = 33, int h = 33, float spacing = 2.0f,
                           float scale = 1.0f) {
  terrain::HeightField field(w, h, spacing, spacing);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      field.at(i, j) =
          scale * (a * static_cast<float>(i) * spacing + b * static_cast<float>(j) * spacing + c);
    }
  }
  return field;
}

TEST(Shore, DepthIsLevelMinusHeightInTrueMetres) {
  const terrain::HeightField field = plane(0.1f, 0.0f, -2.0f, 33, 33, 2.0f, 3.0f); // exaggerated 3×
  // h(true) = 0.1·x − 2; level 0 → depth 2 − 0.1·x; the shoreline at x = 20.
  EXPECT_NEAR(waterDepth(field, 3.0f, 0.0f, 0.0f, 10.0f), 2.0f, 1e-5f);
  EXPECT_NEAR(waterDepth(field, 3.0f, 0.0f, 20.0f, 10.0f), 0.0f, 1e-5f);
  EXPECT_NEAR(waterDepth(field, 3.0f, 0.0f, 31.0f, 7.5f), -1.1f, 1e-5f);
  // A level in world (exaggerated) metres: 3 m world = 1 m true.
  EXPECT_NEAR(waterDepth(field, 3.0f, 3.0f, 20.0f, 10.0f), 1.0f, 1e-5f);
  terrain::HeightField holes = field;
  holes.at(5, 5) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(waterDepth(holes, 3.0f, 0.0f, 10.0f, 10.0f)));
}

TEST(Shore, BandIsOneAtTheWaterlineAndFadesBothWays) {
  ShoreSettings s;
  s.band = 6.0f;
  s.wet = 0.5f;
  EXPECT_FLOAT_EQ(shoreBand(0.0f, s), 1.0f);
  EXPECT_FLOAT_EQ(shoreBand(3.0f, s), 0.5f);
  EXPECT_FLOAT_EQ(shoreBand(6.0f, s), 0.0f);
  EXPECT_FLOAT_EQ(shoreBand(60.0f, s), 0.0f);
  EXPECT_FLOAT_EQ(shoreBand(-0.25f, s), 0.5f);
  EXPECT_FLOAT_EQ(shoreBand(-0.5f, s), 0.0f);
  EXPECT_FLOAT_EQ(shoreBand(-5.0f, s), 0.0f);
  EXPECT_FLOAT_EQ(shoreBand(std::numeric_limits<float>::quiet_NaN(), s), 0.0f);
  // Monotonic away from the waterline on both sides.
  float previous = 1.0f;
  for (float d = 0.1f; d <= 7.0f; d += 0.1f) {
    EXPECT_LE(shoreBand(d, s), previous);
    previous = shoreBand(d, s);
  }
  previous = 1.0f;
  for (float d = 0.01f; d <= 0.6f; d += 0.01f) {
    EXPECT_LE(shoreBand(-d, s), previous);
    previous = shoreBand(-d, s);
  }
}

TEST(Shore, GradientOfAPlaneIsItsTrueSlope) {
  const terrain::HeightField field = plane(0.08f, -0.03f, 1.0f, 17, 17, 2.0f, 2.0f);
  for (const glm::vec2 p : {glm::vec2(5.3f, 7.1f), glm::vec2(0.0f, 0.0f), glm::vec2(32.0f, 32.0f)}) {
    const glm::vec2 g = shoreGradient(field, 2.0f, p.x, p.y);
    EXPECT_NEAR(g.x, 0.08f, 1e-5f);
    EXPECT_NEAR(g.y, -0.03f, 1e-5f);
  }
  // A bump: the gradient points towards the top from every side.
  terrain::HeightField bump(17, 17, 1.0f, 1.0f, 0.0f);
  for (int j = 0; j < 17; ++j) {
    for (int i = 0; i < 17; ++i) {
      bump.at(i, j) = -0.05f * static_cast<float>((i - 8) * (i - 8) + (j - 8) * (j - 8));
    }
  }
  EXPECT_GT(shoreGradient(bump, 1.0f, 4.0f, 8.0f).x, 0.0f);
  EXPECT_LT(shoreGradient(bump, 1.0f, 12.0f, 8.0f).x, 0.0f);
  EXPECT_GT(shoreGradient(bump, 1.0f, 8.0f, 3.0f).y, 0.0f);
  EXPECT_NEAR(shoreGradient(bump, 1.0f, 8.0f, 3.0f).x, 0.0f, 1e-6f);
}

TEST(Shore, SwashRowsFollowDepthAndAdvanceUphill) {
  ShoreSettings s;
  s.tile = 10.0f;
  s.waterline = 0.4f;
  const float aspect = 0.5f;     // the frame is twice as wide as high: v spans 5 m
  const glm::vec2 g(0.1f, 0.0f); // uphill towards +x (east)
  // On the waterline: v is the image's resting water edge.
  SwashCoords c = swashCoords({3.0f, 4.0f}, 0.0f, g, s, aspect);
  EXPECT_NEAR(c.uv[0].y, 0.4f, 1e-6f);
  EXPECT_NEAR(c.uv[1].y, 0.4f, 1e-6f);
  EXPECT_FLOAT_EQ(c.mix, 0.0f); // exactly along direction 0: one sample
  // 0.1 m above the water at slope 0.1 is 1 m uphill: v grows by 1 / 5 (down the image, where the water
  // runs).
  c = swashCoords({13.0f, 4.0f}, -0.1f, g, s, aspect);
  EXPECT_NEAR(c.uv[0].y, 0.6f, 1e-6f);
  // 0.25 m deep is 2.5 m towards the water: v shrinks.
  c = swashCoords({0.0f, 4.0f}, 0.25f, g, s, aspect);
  EXPECT_NEAR(c.uv[0].y, 0.4f - 0.5f, 1e-6f);
  // u runs along the shore, the image's right to the right of a viewer looking down with uphill at the
  // image's bottom: for a beach rising to the east that is north (−z). It tiles every 10 m.
  const SwashCoords a = swashCoords({3.0f, 4.0f}, 0.0f, g, s, aspect);
  const SwashCoords b = swashCoords({3.0f, 14.0f}, 0.0f, g, s, aspect);
  EXPECT_NEAR(b.uv[0].x - a.uv[0].x, -1.0f, 1e-5f);
  const SwashCoords moved = swashCoords({8.0f, 4.0f}, 0.0f, g, s, aspect);
  EXPECT_NEAR(moved.uv[0].x, a.uv[0].x, 1e-6f); // moving uphill does not change u
}

TEST(Shore, SwashAdvanceTurnsWithTheSlope) {
  ShoreSettings s;
  s.tile = 12.0f;
  // For each of the 8 axis directions, u is constant uphill and changes by 1 per tile across it.
  for (int k = 0; k < kSwashDirections; ++k) {
    const float a = static_cast<float>(k) * 2.0f * std::numbers::pi_v<float> / kSwashDirections;
    const glm::vec2 up(std::cos(a), std::sin(a));
    const glm::vec2 across(std::sin(a), -std::cos(a));
    const glm::vec2 p(5.0f, -3.0f);
    const SwashCoords c0 = swashCoords(p, 0.0f, 0.2f * up, s, 1.0f);
    const SwashCoords c1 = swashCoords(p + 7.0f * up, 0.0f, 0.2f * up, s, 1.0f);
    const SwashCoords c2 = swashCoords(p + 12.0f * across, 0.0f, 0.2f * up, s, 1.0f);
    const int i = c0.mix < 0.5f ? 0 : 1;
    EXPECT_TRUE(c0.mix < 1e-4f || c0.mix > 1.0f - 1e-4f) << k;
    EXPECT_NEAR(c1.uv[i].x, c0.uv[i].x, 1e-4f) << k;
    EXPECT_NEAR(c2.uv[i].x - c0.uv[i].x, 1.0f, 1e-4f) << k;
  }
  // Between two directions both are read; the blend is continuous across sector ends.
  const auto at = [&](float angle) {
    const glm::vec2 g = 0.1f * glm::vec2(std::cos(angle), std::sin(angle));
    const SwashCoords c = swashCoords({40.0f, 25.0f}, 0.0f, g, s, 1.0f);
    return (1.0f - c.mix) * c.uv[0].x + c.mix * c.uv[1].x;
  };
  const float step = 2.0f * std::numbers::pi_v<float> / kSwashDirections;
  for (int k = -3; k < 4; ++k) {
    const float edge = static_cast<float>(k) * step;
    EXPECT_NEAR(at(edge - 1e-4f), at(edge + 1e-4f), 2e-3f) << k;
  }
  const glm::vec2 half = 0.1f * glm::vec2(std::cos(0.5f * step), std::sin(0.5f * step));
  EXPECT_FLOAT_EQ(swashCoords({1.0f, 2.0f}, 0.0f, half, s, 1.0f).mix, 0.5f);
}

TEST(Shore, FlatGroundUsesTheMinimumSlope) {
  ShoreSettings s;
  s.tile = 10.0f;
  s.waterline = 0.5f;
  const SwashCoords c = swashCoords({0.0f, 0.0f}, -0.02f, {0.0f, 0.0f}, s, 1.0f);
  EXPECT_NEAR(c.uv[0].y, 0.5f + (0.02f / kMinShoreSlope) / 10.0f, 1e-6f);
  EXPECT_TRUE(std::isfinite(c.uv[0].x));
}

TEST(Shore, SwashTimeLoopsOneProjectCyclePerPeriod) {
  EXPECT_DOUBLE_EQ(swashTime(0.0, 8.0, 4.0), 0.0);
  EXPECT_DOUBLE_EQ(swashTime(2.0, 8.0, 4.0), 1.0);
  EXPECT_DOUBLE_EQ(swashTime(10.0, 8.0, 4.0), 1.0);
  EXPECT_DOUBLE_EQ(swashTime(5.0, 0.0, 4.0), 1.0); // 0 = the project's own period
  EXPECT_NEAR(swashTime(1e6 + 1.0, 4.0, 4.0), 1.0, 1e-6);
  EXPECT_THROW(swashTime(1.0, -1.0, 4.0), Error);
  EXPECT_THROW(swashTime(1.0, 2.0, 0.0), Error);
}

TEST(Shore, ValidateNamesTheField) {
  ShoreSettings s;
  EXPECT_NO_THROW(validate(s));
  s.band = 0.0f;
  try {
    validate(s);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("band"), std::string::npos);
  }
  s = {};
  s.tile = std::numeric_limits<float>::infinity();
  EXPECT_THROW(validate(s), Error);
  s = {};
  s.waterline = 1.5f;
  EXPECT_THROW(validate(s), Error);
  s = {};
  s.folding.clear();
  EXPECT_THROW(validate(s), Error);
}

TEST(Shore, WetCellsHoldEveryFragmentTheWaterShaderKeeps) {
  // A bowl: a lake in the middle of a 200×150 field (stride 2 with at most 100 cells per axis), dry hills
  // around it, and absent samples in one corner.
  const int w = 200;
  const int h = 150;
  const float spacing = 1.5f;
  const float scale = 2.0f; // vertical exaggeration
  terrain::HeightField field(w, h, spacing, spacing);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const float dx = static_cast<float>(i - 90) * spacing;
      const float dz = static_cast<float>(j - 70) * spacing;
      field.at(i, j) = scale * (0.01f * (dx * dx + dz * dz) - 20.0f + std::sin(0.3f * dx) * 0.5f);
    }
  }
  for (int j = 0; j < 10; ++j) {
    for (int i = 0; i < 10; ++i) {
      field.at(i, j) = std::numeric_limits<float>::quiet_NaN();
    }
  }
  const WaterGrid grid = waterGrid(w, h, 100);
  EXPECT_EQ(grid.stride, 2);
  EXPECT_EQ(grid.cellsX, 100);
  EXPECT_EQ(grid.cellsZ, 75);
  const float level = 0.0f;
  const float wet = 0.5f; // true metres above the water
  const float wetTop = level + wet * scale;
  const std::vector<std::uint32_t> cells = wetCells(field, grid, wetTop, 1e-3f);
  ASSERT_FALSE(cells.empty());
  EXPECT_TRUE(std::is_sorted(cells.begin(), cells.end()));
  // The lake is a small part of the footprint: most cells are left out.
  EXPECT_LT(cells.size(), static_cast<std::size_t>(grid.cellsX * grid.cellsZ) / 2);
  std::vector<bool> isWet(static_cast<std::size_t>(grid.cellsX * grid.cellsZ), false);
  for (std::uint32_t c : cells) {
    isWet[c] = true;
  }
  // Every point the shader keeps (depth > −wet, the water.frag test) lies in a listed cell.
  int kept = 0;
  for (int j = 0; j <= 4 * (h - 1); ++j) {
    for (int i = 0; i <= 4 * (w - 1); ++i) {
      const float x = static_cast<float>(i) * spacing / 4.0f;
      const float z = static_cast<float>(j) * spacing / 4.0f;
      if (!(waterDepth(field, scale, level, x, z) > -wet)) {
        continue;
      }
      ++kept;
      const int cx = std::min(static_cast<int>(x / spacing) / grid.stride, grid.cellsX - 1);
      const int cz = std::min(static_cast<int>(z / spacing) / grid.stride, grid.cellsZ - 1);
      ASSERT_TRUE(isWet[static_cast<std::size_t>(cx + cz * grid.cellsX)])
          << "kept water at " << x << ", " << z;
    }
  }
  EXPECT_GT(kept, 1000);
  // Absent samples are dry; a field entirely under water keeps every cell.
  EXPECT_FALSE(isWet[0]);
  const terrain::HeightField sea = plane(0.0f, 0.0f, -5.0f, 33, 33);
  EXPECT_EQ(wetCells(sea, waterGrid(33, 33, 512), 0.0f, 0.0f).size(), 32u * 32u);
  EXPECT_THROW(waterGrid(1, 5, 10), Error);
}

TEST(Shore, FlatWaterMergesIntoFansWithoutTJunctions) {
  // A bowl lake (stride 1), absent samples in one corner: the wet cells as rectangles, then triangles.
  const int w = 200;
  const int h = 160;
  terrain::HeightField field(w, h, 2.0f, 2.0f);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const float dx = static_cast<float>(i - 100);
      const float dz = static_cast<float>(j - 80);
      field.at(i, j) = 0.005f * (dx * dx + dz * dz) - 20.0f + std::sin(0.7f * dx) * 0.3f;
    }
  }
  for (int j = 40; j < 50; ++j) {
    for (int i = 55; i < 65; ++i) {
      field.at(i, j) = std::numeric_limits<float>::quiet_NaN(); // a hole in the lake bed
    }
  }
  const WaterGrid grid = waterGrid(w, h, 512);
  ASSERT_EQ(grid.stride, 1);
  const float level = 0.0f;
  const float lift = 0.03f;
  const std::vector<std::uint32_t> cells = wetCells(field, grid, 0.5f, 1e-3f);
  const std::vector<glm::uvec4> rects = waterRects(field, grid, cells, level, lift);
  ASSERT_FALSE(rects.empty());
  const auto corner = [&](int gx, int gz) { return field.at(std::min(gx, w - 1), std::min(gz, h - 1)); };
  // Every wet cell exactly once; merged rectangles only over cells flat at the level.
  std::vector<int> covered(static_cast<std::size_t>(grid.cellsX * grid.cellsZ), 0);
  std::size_t merged = 0;
  for (const glm::uvec4& r : rects) {
    ASSERT_GE(r.z, 1u);
    ASSERT_GE(r.w, 1u);
    merged += r.z * r.w > 1 ? 1 : 0;
    for (unsigned z = r.y; z < r.y + r.w; ++z) {
      for (unsigned x = r.x; x < r.x + r.z; ++x) {
        ++covered[x + z * static_cast<unsigned>(grid.cellsX)];
        if (r.z * r.w > 1) {
          for (const glm::ivec2 c :
               {glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(0, 1), glm::ivec2(1, 1)}) {
            const float height = corner(static_cast<int>(x) + c.x, static_cast<int>(z) + c.y);
            ASSERT_TRUE(std::isfinite(height) && height + lift <= level) << x << ", " << z;
          }
        }
      }
    }
  }
  std::vector<int> expected(covered.size(), 0);
  for (std::uint32_t c : cells) {
    expected[c] = 1;
  }
  EXPECT_EQ(covered, expected);
  EXPECT_GT(merged, 0u);
  EXPECT_LT(rects.size(), cells.size() / 3) << "the flat lake merges";
  // The triangles: all turning like the cells', areas adding up to the cells (no gap, no overlap inside a
  // rectangle), far fewer vertices; a fan holds every grid point of its border (no T-junction).
  const std::vector<glm::ivec2> points = waterTriangles(rects);
  ASSERT_EQ(points.size() % 3, 0u);
  long long doubleArea = 0;
  for (std::size_t t = 0; t < points.size(); t += 3) {
    const glm::ivec2 u = points[t + 1] - points[t];
    const glm::ivec2 v = points[t + 2] - points[t];
    const int cross = u.x * v.y - u.y * v.x;
    ASSERT_LT(cross, 0) << "triangle " << t / 3;
    doubleArea -= cross;
  }
  EXPECT_EQ(doubleArea, 2 * static_cast<long long>(cells.size()));
  EXPECT_LT(points.size(), 6 * cells.size() / 3) << "a third of the cells' vertices";
  for (const glm::uvec4& r : rects) {
    if (r.z < 2 || r.w < 2) {
      continue;
    }
    const std::vector<glm::ivec2> fan = waterTriangles(std::span<const glm::uvec4>(&r, 1));
    EXPECT_EQ(fan.size(), 3 * 2 * static_cast<std::size_t>(r.z + r.w));
    const glm::ivec2 lo(r.x, r.y);
    const glm::ivec2 hi = lo + glm::ivec2(r.z, r.w);
    for (int z = lo.y; z <= hi.y; ++z) {
      for (int x = lo.x; x <= hi.x; ++x) {
        if (x != lo.x && x != hi.x && z != lo.y && z != hi.y) {
          continue;
        }
        EXPECT_NE(std::find(fan.begin(), fan.end(), glm::ivec2(x, z)), fan.end())
            << "border point " << x << ", " << z << " of the rectangle at " << lo.x << ", " << lo.y;
      }
    }
  }
  EXPECT_THROW(waterRects(field, grid, std::vector<std::uint32_t>{1u << 30}, level, lift), Error);
}

} // namespace
} // namespace sylva::scene
