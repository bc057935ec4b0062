#include <sylva/terrain/HeightQuery.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>

#include "TestUtil.hpp"

namespace sylva::terrain {
namespace {

using test::kNaN;
using Surface = std::function<double(double, double)>;

HeightField sampled(const Surface& f, int w, int h, float sx, float sz) {
  HeightField field(w, h, sx, sz);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      field.at(i, j) = static_cast<float>(f(i * static_cast<double>(sx), j * static_cast<double>(sz)));
    }
  }
  return field;
}

// h = 3 + 0.5·x − 0.25·z: dyadic coefficients, so samples and interpolants are exact in binary.
double plane(double x, double z) {
  return 3.0 + 0.5 * x - 0.25 * z;
}
double paraboloid(double x, double z) {
  return 0.02 * x * x + 0.01 * z * z - 0.005 * x * z;
}
double wave(double x, double z) {
  return 10.0 * std::sin(0.1 * x) * std::cos(0.07 * z);
}

std::string name(Interpolation interpolation) {
  return interpolation == Interpolation::Bilinear ? "bilinear" : "bicubic";
}

TEST(HeightQuery, BilinearReproducesPlanesExactly) {
  const HeightField field = sampled(plane, 9, 7, 2.0f, 0.5f);
  // Dyadic query points: every step of the interpolation is exact, so equality is exact.
  for (float x = 0.0f; x <= field.extentX(); x += 0.375f) {
    for (float z = 0.0f; z <= field.extentZ(); z += 0.125f) {
      ASSERT_EQ(heightAt(field, x, z), static_cast<float>(plane(x, z))) << x << "," << z;
    }
  }
  Rng rng(7);
  for (int k = 0; k < 1000; ++k) {
    const float x = rng.uniform(0.0f, field.extentX());
    const float z = rng.uniform(0.0f, field.extentZ());
    ASSERT_NEAR(heightAt(field, x, z), plane(x, z), 1e-5) << x << "," << z;
  }
}

TEST(HeightQuery, BicubicReproducesPlanesAndQuadraticsInsideButNotAtTheClampedEdge) {
  const HeightField planeField = sampled(plane, 9, 7, 2.0f, 0.5f);
  const HeightField quadField = sampled(paraboloid, 12, 10, 1.5f, 2.0f);
  Rng rng(11);
  for (int k = 0; k < 1000; ++k) {
    // Interior cells: the 4×4 support lies inside the grid.
    float x = rng.uniform(1.0f, 7.0f) * 2.0f;
    float z = rng.uniform(1.0f, 5.0f) * 0.5f;
    ASSERT_NEAR(heightAt(planeField, x, z, Interpolation::Bicubic), plane(x, z), 1e-5);
    x = rng.uniform(1.0f, 10.0f) * 1.5f;
    z = rng.uniform(1.0f, 8.0f) * 2.0f;
    ASSERT_NEAR(heightAt(quadField, x, z, Interpolation::Bicubic), paraboloid(x, z), 2e-5) << x << "," << z;
  }
  // Outermost cell: the clamped sample h(−1) = h(0) bends the plane. For h = x at gx = 0.5 the Catmull-Rom
  // weights (−1/16, 9/16, 9/16, −1/16) on (0, 0, 1, 2) give 7/16, not 1/2.
  const HeightField line = sampled([](double x, double) { return x; }, 6, 3, 1.0f, 1.0f);
  EXPECT_FLOAT_EQ(heightAt(line, 0.5f, 1.0f, Interpolation::Bicubic), 7.0f / 16.0f);
  EXPECT_FLOAT_EQ(heightAt(line, 0.5f, 1.0f, Interpolation::Bilinear), 0.5f);
}

TEST(HeightQuery, InterpolationErrorBoundsOnSmoothSurfaces) {
  const float s = 1.0f;
  const HeightField field = sampled(wave, 80, 90, s, s);
  double bilinearMax = 0.0;
  double bicubicMax = 0.0;
  Rng rng(3);
  for (int k = 0; k < 4000; ++k) {
    const float x = rng.uniform(2.0f, 77.0f);
    const float z = rng.uniform(2.0f, 87.0f);
    bilinearMax = std::max(bilinearMax, std::abs(heightAt(field, x, z) - wave(x, z)));
    bicubicMax = std::max(bicubicMax, std::abs(heightAt(field, x, z, Interpolation::Bicubic) - wave(x, z)));
  }
  // Bilinear: |error| ≤ s²/8 · (max|h_xx| + max|h_zz|) = (0.1 + 0.049) / 8.
  EXPECT_LE(bilinearMax, (10.0 * 0.01 + 10.0 * 0.0049) / 8.0 + 1e-5);
  // Catmull-Rom is third order: far below bilinear on this smooth surface.
  EXPECT_LT(bicubicMax, bilinearMax / 5.0);
  EXPECT_GT(bilinearMax, 0.0);
}

TEST(HeightQuery, SamplePositionsReturnSamplesAndOutsideClampsToEdge) {
  const HeightField field = sampled(wave, 10, 8, 3.0f, 2.0f);
  for (const Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Bicubic}) {
    for (int j = 0; j < 8; ++j) {
      for (int i = 0; i < 10; ++i) {
        ASSERT_EQ(heightAt(field, i * 3.0f, j * 2.0f, interpolation), field.at(i, j)) << name(interpolation);
      }
    }
    EXPECT_EQ(heightAt(field, -50.0f, 4.0f, interpolation), field.at(0, 2));
    EXPECT_EQ(heightAt(field, 500.0f, 500.0f, interpolation), field.at(9, 7));
  }
}

TEST(HeightQuery, TextureCentreMappingMatchesBilinear) {
  // Emulates GL_LINEAR + CLAMP_TO_EDGE at u = (x/spacingX + 0.5)/W, v = (z/spacingZ + 0.5)/H: texel space
  // p = u·W − 0.5, then lerp between texels floor(p) and floor(p) + 1, clamped.
  const HeightField field = sampled(wave, 13, 11, 1.25f, 0.75f);
  const auto texture = [&](float x, float z) {
    const double u = (x / field.spacingX() + 0.5) / field.width();
    const double v = (z / field.spacingZ() + 0.5) / field.height();
    const double px = u * field.width() - 0.5;
    const double pz = v * field.height() - 0.5;
    const auto texel = [&](int i, int j) {
      return static_cast<double>(
          field.at(std::clamp(i, 0, field.width() - 1), std::clamp(j, 0, field.height() - 1)));
    };
    const int i = static_cast<int>(std::floor(px));
    const int j = static_cast<int>(std::floor(pz));
    const double tx = px - i;
    const double tz = pz - j;
    return (1 - tz) * ((1 - tx) * texel(i, j) + tx * texel(i + 1, j)) +
           tz * ((1 - tx) * texel(i, j + 1) + tx * texel(i + 1, j + 1));
  };
  Rng rng(5);
  for (int k = 0; k < 500; ++k) {
    const float x = rng.uniform(-2.0f, field.extentX() + 2.0f);
    const float z = rng.uniform(-2.0f, field.extentZ() + 2.0f);
    ASSERT_NEAR(heightAt(field, x, z), texture(x, z), 1e-4) << x << "," << z;
  }
}

TEST(HeightQuery, AbsentSamplesOnlyAffectTheirCells) {
  HeightField field = sampled(plane, 6, 6, 1.0f, 1.0f);
  field.at(2, 2) = kNaN;
  EXPECT_TRUE(std::isnan(heightAt(field, 2.5f, 2.5f)));
  EXPECT_TRUE(std::isnan(heightAt(field, 1.5f, 1.5f)));
  EXPECT_TRUE(std::isnan(heightAt(field, 2.0f, 2.0f)));
  EXPECT_EQ(heightAt(field, 3.0f, 2.0f), plane(3, 2)) << "zero-weight neighbours do not contribute";
  EXPECT_EQ(heightAt(field, 2.0f, 3.0f), plane(2, 3));
  EXPECT_EQ(heightAt(field, 3.5f, 3.5f), plane(3.5, 3.5));
  EXPECT_TRUE(std::isnan(heightAt(field, 3.5f, 3.5f, Interpolation::Bicubic))) << "inside the 4×4 support";
  EXPECT_FALSE(std::isnan(heightAt(field, 4.5f, 4.5f, Interpolation::Bicubic)));
}

TEST(HeightQuery, NormalsOfPlanesAndWaves) {
  const HeightField field = sampled(plane, 9, 7, 2.0f, 0.5f);
  const glm::vec3 expected = glm::normalize(glm::vec3(-0.5f, 1.0f, 0.25f));
  for (const Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Bicubic}) {
    const glm::vec3 n = normalAt(field, 7.3f, 1.1f, interpolation);
    EXPECT_NEAR(glm::length(n - expected), 0.0f, 1e-5f) << name(interpolation);
  }
  // At the border the difference is one-sided but still exact for bilinear.
  EXPECT_NEAR(glm::length(normalAt(field, 0.0f, 0.0f) - expected), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::length(normalAt(field, field.extentX(), field.extentZ()) - expected), 0.0f, 1e-5f);

  const HeightField waves = sampled(wave, 100, 100, 0.5f, 0.5f);
  Rng rng(9);
  for (int k = 0; k < 300; ++k) {
    const double x = rng.uniform(2.0f, 47.0f);
    const double z = rng.uniform(2.0f, 47.0f);
    const glm::dvec3 analytic = glm::normalize(glm::dvec3(-std::cos(0.1 * x) * std::cos(0.07 * z), 1.0,
                                                          0.7 * std::sin(0.1 * x) * std::sin(0.07 * z)));
    for (const Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Bicubic}) {
      const glm::vec3 n = normalAt(waves, static_cast<float>(x), static_cast<float>(z), interpolation);
      ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
      ASSERT_GT(glm::dot(glm::dvec3(n), analytic), 0.999) << name(interpolation) << " at " << x << "," << z;
    }
  }
}

TEST(HeightQuery, NormalNextToAHoleFallsBackToOneSidedDifferences) {
  HeightField field = sampled(plane, 6, 6, 1.0f, 1.0f);
  field.at(4, 2) = kNaN;
  field.at(4, 3) = kNaN;
  const glm::vec3 expected = glm::normalize(glm::vec3(-0.5f, 1.0f, 0.25f));
  // At x = 3, z = 2.5: the +x side (3.5) lies in the hole cell; the −x side and the centre are valid.
  EXPECT_NEAR(glm::length(normalAt(field, 3.0f, 2.5f) - expected), 0.0f, 1e-5f);
  EXPECT_TRUE(std::isnan(normalAt(field, 4.0f, 2.5f).x));
}

// ---- ray casts ----

double planeHitDistance(const glm::dvec3& o, const glm::dvec3& d) {
  return (3.0 + 0.5 * o.x - 0.25 * o.z - o.y) / (d.y - 0.5 * d.x + 0.25 * d.z);
}

TEST(HeightQuery, RaysHitAPlaneWhereTheAlgebraSays) {
  const HeightField field = sampled(plane, 33, 17, 1.5f, 2.5f);
  Rng rng(21);
  int hits = 0;
  for (const Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Bicubic}) {
    for (int k = 0; k < 400; ++k) {
      const glm::dvec3 o(rng.uniform(0.0f, 48.0f), rng.uniform(30.0f, 60.0f), rng.uniform(0.0f, 40.0f));
      const glm::dvec3 target(rng.uniform(4.0f, 44.0f), 0.0, rng.uniform(6.0f, 34.0f));
      glm::dvec3 d = glm::normalize(glm::dvec3(target.x, plane(target.x, target.z), target.z) - o);
      const double t = planeHitDistance(o, d);
      const auto hit = raycast(field, glm::vec3(o), glm::vec3(d), 500.0f, interpolation);
      ASSERT_TRUE(hit.has_value()) << name(interpolation) << " ray " << k;
      const double tolerance = interpolation == Interpolation::Bilinear ? 2e-4 : 2e-3;
      ASSERT_NEAR(hit->distance, t, tolerance) << name(interpolation) << " ray " << k;
      ASSERT_NEAR(hit->position.y, heightAt(field, hit->position.x, hit->position.z, interpolation),
                  tolerance);
      ASSERT_NEAR(glm::length(hit->normal - glm::normalize(glm::vec3(-0.5f, 1.0f, 0.25f))), 0.0f, 1e-4f);
      ++hits;
    }
  }
  EXPECT_EQ(hits, 800);
}

TEST(HeightQuery, FirstHitOnAWavySurfaceHasNoEarlierCrossing) {
  const HeightField field = sampled(wave, 120, 120, 1.0f, 1.0f);
  for (const Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Bicubic}) {
    Rng rng(33); // the same 200 rays for both interpolations
    int hits = 0;
    for (int k = 0; k < 200; ++k) {
      const glm::vec3 o(rng.uniform(0.0f, 119.0f), rng.uniform(12.0f, 30.0f), rng.uniform(0.0f, 119.0f));
      const glm::vec3 d = glm::normalize(
          glm::vec3(rng.uniform(-1.0f, 1.0f), rng.uniform(-0.6f, -0.05f), rng.uniform(-1.0f, 1.0f)));
      const auto hit = raycast(field, o, d, 400.0f, interpolation);
      if (!hit) {
        continue;
      }
      ++hits;
      ASSERT_NEAR(hit->position.y, heightAt(field, hit->position.x, hit->position.z, interpolation), 1e-3)
          << name(interpolation);
      for (float t = 0.0f; t < hit->distance - 0.01f; t += 0.05f) {
        const glm::vec3 p = o + d * t;
        ASSERT_GT(p.y, heightAt(field, p.x, p.z, interpolation) - 1e-4f) << "crossed earlier at t = " << t;
      }
    }
    EXPECT_GT(hits, 80) << name(interpolation);
  }
}

TEST(HeightQuery, VerticalRaysLandOnTheInterpolatedHeight) {
  const HeightField field = sampled(paraboloid, 40, 30, 0.5f, 0.5f);
  for (const Interpolation interpolation : {Interpolation::Bilinear, Interpolation::Bicubic}) {
    for (float x = 0.25f; x < 19.5f; x += 1.3f) {
      const float z = 0.37f * x + 1.0f;
      const auto hit =
          raycast(field, glm::vec3(x, 100.0f, z), glm::vec3(0.0f, -1.0f, 0.0f), 1000.0f, interpolation);
      ASSERT_TRUE(hit.has_value());
      EXPECT_NEAR(hit->position.y, heightAt(field, x, z, interpolation), 1e-5);
      EXPECT_NEAR(hit->distance, 100.0f - hit->position.y, 1e-5);
    }
    // No distance limit: the vertical ray is not cut by the footprint box.
    const auto far = raycast(field, glm::vec3(7.1f, 1.0e6f, 3.3f), glm::vec3(0.0f, -2.0f, 0.0f),
                             std::numeric_limits<float>::infinity(), interpolation);
    ASSERT_TRUE(far.has_value()) << name(interpolation);
    EXPECT_NEAR(far->position.y, heightAt(field, 7.1f, 3.3f, interpolation), 0.07f) << "float ulp at 1e6 m";
    EXPECT_FALSE(raycast(field, glm::vec3(7.1f, 10.0f, 3.3f), glm::vec3(0.0f, 1.0f, 0.0f),
                         std::numeric_limits<float>::infinity(), interpolation));
  }
}

TEST(HeightQuery, MissesBelowStartsAndGrazingRays) {
  HeightField flat(10, 10, 1.0f, 1.0f, 5.0f);
  const glm::vec3 down(0.0f, -1.0f, 0.0f);
  // Up, outside the footprint, too short.
  EXPECT_FALSE(raycast(flat, {4, 10, 4}, {0, 1, 0}, 100.0f));
  EXPECT_FALSE(raycast(flat, {20, 10, 4}, down, 100.0f));
  EXPECT_FALSE(raycast(flat, {4, 10, 4}, down, 4.9f));
  ASSERT_TRUE(raycast(flat, {4, 10, 4}, down, 5.0f));
  // Starting below the surface: the ray is already in the ground.
  const auto below = raycast(flat, {4, 2, 4}, {1, 0, 0}, 100.0f);
  ASSERT_TRUE(below.has_value());
  EXPECT_EQ(below->distance, 0.0f);
  const auto belowUp = raycast(flat, {4, 2, 4}, {0, 1, 0}, 100.0f, Interpolation::Bicubic);
  ASSERT_TRUE(belowUp.has_value());
  EXPECT_EQ(belowUp->distance, 0.0f);
  // Entering the footprint from the side below the edge height hits at the entry.
  const auto side = raycast(flat, {-3, 2, 4}, {1, 0, 0}, 100.0f);
  ASSERT_TRUE(side.has_value());
  EXPECT_NEAR(side->distance, 3.0f, 1e-6f);
  // Grazing: horizontal rays just above a flat surface miss, on it they touch.
  EXPECT_FALSE(raycast(flat, {0.5f, 5.001f, 0.5f}, {1, 0, 1}, 100.0f));
  EXPECT_FALSE(raycast(flat, {0.5f, 5.001f, 0.5f}, {1, 0, 1}, 100.0f, Interpolation::Bicubic));
  EXPECT_TRUE(raycast(flat, {0.5f, 5.0f, 0.5f}, {1, 0, 0.3f}, 100.0f));

  // A single peak: a horizontal ray through it just below the top hits near it, just above misses.
  HeightField peak(11, 11, 1.0f, 1.0f, 0.0f);
  peak.at(5, 5) = 10.0f;
  const auto under = raycast(peak, {5.0f, 9.99f, -1.0f}, {0, 0, 1}, 100.0f);
  ASSERT_TRUE(under.has_value());
  EXPECT_NEAR(under->position.z, 5.0f, 0.01f);
  EXPECT_FALSE(raycast(peak, {5.0f, 10.01f, -1.0f}, {0, 0, 1}, 100.0f));
  // Rays parallel to an axis at a cell boundary and along a diagonal through lattice corners.
  const auto diagonal = raycast(peak, {0.0f, 9.0f, 0.0f}, {1, 0, 1}, 100.0f);
  ASSERT_TRUE(diagonal.has_value());
  // In cell (4, 4) the bilinear patch is 10·u·v; along u = v it reaches 9 at u = √0.9.
  EXPECT_NEAR(diagonal->position.x, 4.0f + std::sqrt(0.9f), 1e-4f);
  EXPECT_NEAR(diagonal->position.z, diagonal->position.x, 1e-5f);
}

TEST(HeightQuery, RaysFallThroughHoles) {
  HeightField field(6, 6, 1.0f, 1.0f, 1.0f);
  field.at(2, 2) = kNaN;
  // The four cells around (2, 2) are holes; the vertical ray there passes through.
  EXPECT_FALSE(raycast(field, {2.2f, 5.0f, 2.3f}, {0, -1, 0}, 100.0f));
  EXPECT_FALSE(raycast(field, {2.2f, 5.0f, 2.3f}, {0, -1, 0}, 100.0f, Interpolation::Bicubic));
  ASSERT_TRUE(raycast(field, {4.5f, 5.0f, 4.5f}, {0, -1, 0}, 100.0f));
  // A slanted ray over the hole (cells x ∈ [1, 3]) is not stopped there and lands at y = 1 further on:
  // y = 1.5 − 0.2·(x − 1.5) = 1 at x = 4.
  const auto hit = raycast(field, {1.5f, 1.5f, 2.5f}, glm::normalize(glm::vec3(1.0f, -0.2f, 0.0f)), 100.0f);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->position.x, 4.0f, 1e-5f);
  // Starting inside the hole below the ground level, the ray hits the side of the first valid cell.
  const auto wall = raycast(field, {1.5f, 0.5f, 2.5f}, {1, 0, 0}, 100.0f);
  ASSERT_TRUE(wall.has_value());
  EXPECT_NEAR(wall->position.x, 3.0f, 1e-5f);
}

TEST(HeightQuery, ZeroDirectionIsAnError) {
  const HeightField field(4, 4);
  EXPECT_THROW(raycast(field, {1, 1, 1}, {0, 0, 0}, 10.0f), Error);
  EXPECT_THROW(raycast(field, {1, 1, 1}, {kNaN, 0, 0}, 10.0f), Error);
}

} // namespace
} // namespace sylva::terrain
