// The CPU sky (Preetham 1999), its aerial perspective and the lens-flare geometry: known properties of the
// model and values computed by hand from the paper's formulas.
#include <sylva/render/Sky.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

constexpr float kPi = 3.14159265358979f;

glm::vec3 elevated(float elevationDegrees, float azimuthDegrees) {
  const float e = glm::radians(elevationDegrees);
  const float a = glm::radians(azimuthDegrees);
  return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

float luminance(const glm::vec3& c) {
  return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

const glm::vec3 kSkySun = elevated(40.0f, 0.0f);

TEST(Sky, ZenithValuesMatchHandComputation) {
  // T = 3, θs = 50°: χ = (4/9 − 3/120)(π − 2·0.872665) = 0.585655, tan χ = 0.662070,
  // Yz = (4.0453·3 − 4.9710)·0.662070 − 0.2155·3 + 2.4192 = 6.52504 kcd/m².
  const glm::vec3 z = zenithLuminanceChromaticity(3.0f, glm::radians(50.0f));
  EXPECT_NEAR(z.x, 6.52504f, 1e-3f);
  EXPECT_NEAR(z.y, 0.244412f, 1e-4f);
  EXPECT_NEAR(z.z, 0.250521f, 1e-4f);
  // T = 2, θs = 30°.
  const glm::vec3 z2 = zenithLuminanceChromaticity(2.0f, glm::radians(30.0f));
  EXPECT_NEAR(z2.x, 5.88674f, 1e-3f);
  EXPECT_NEAR(z2.y, 0.251421f, 1e-4f);
  EXPECT_NEAR(z2.z, 0.255924f, 1e-4f);
}

TEST(Sky, PerezAndColourSpaceValues) {
  // F(0, γ) for Y at T = 3: (1 + A e^B)(1 + C e^{Dγ} + E cos²γ) with A = −0.9269, B = −0.6387,
  // C = 5.2570, D = −2.2153, E = 0.1693 at γ = 0.5: (1 − 0.48938)(1 + 1.73657 + 0.13039) = 1.46392.
  const PerezCoefficients c = perezCoefficients(3.0f);
  EXPECT_NEAR(c.Y[0], -0.9269f, 1e-5f);
  EXPECT_NEAR(perezDistribution(c.Y, 1.0f, 0.5f, std::cos(0.5f)), 1.46392f, 2e-4f);
  // D65 white (x, y) = (0.3127, 0.3290) at Y = 1 maps to sRGB (1, 1, 1).
  const glm::vec3 white = xyYToLinearSrgb(0.3127f, 0.3290f, 1.0f);
  EXPECT_NEAR(white.r, 1.0f, 2e-3f);
  EXPECT_NEAR(white.g, 1.0f, 2e-3f);
  EXPECT_NEAR(white.b, 1.0f, 2e-3f);
}

TEST(Sky, RadianceValuesMatchHandComputation) {
  // Zenith: Y = Yz, (x, y) = zenith chromaticity, so sRGB · calibration is (0.22736, 0.51364, 1.10829).
  const glm::vec3 zenith = skyRadiance({0.0f, 1.0f, 0.0f}, kSkySun, {});
  EXPECT_NEAR(zenith.r, 0.22736f, 2e-3f);
  EXPECT_NEAR(zenith.g, 0.51364f, 2e-3f);
  EXPECT_NEAR(zenith.b, 1.10829f, 4e-3f);
  // Horizon opposite the sun: Y = 7.83718, (x, y) = (0.311967, 0.317443) → (0.46990, 0.59130, 0.72876).
  const glm::vec3 away = skyRadiance({-1.0f, 0.0f, 0.0f}, kSkySun, {});
  EXPECT_NEAR(away.r, 0.46990f, 2e-3f);
  EXPECT_NEAR(away.g, 0.59130f, 2e-3f);
  EXPECT_NEAR(away.b, 0.72876f, 2e-3f);
}

TEST(Sky, HorizonAveragesToTheOldFogColour) {
  glm::vec3 sum(0.0f);
  const int n = 180;
  for (int i = 0; i < n; ++i) {
    sum += skyRadiance(elevated(0.0f, 360.0f * static_cast<float>(i) / n), kSkySun, {});
  }
  const glm::vec3 mean = sum / static_cast<float>(n);
  EXPECT_NEAR(mean.r, 0.62f, 0.01f);
  EXPECT_NEAR(mean.g, 0.72f, 0.01f);
  EXPECT_NEAR(mean.b, 0.85f, 0.01f);
}

TEST(Sky, ZenithIsDarkerAndBluerThanTheHorizonWhenClear) {
  for (float turbidity : {2.0f, 2.5f, 3.0f}) { // clear; by T = 4 Preetham's zenith outshines the side horizon
    SkyParams p;
    p.turbidity = turbidity;
    const glm::vec3 zenith = skyRadiance({0.0f, 1.0f, 0.0f}, kSkySun, p);
    const glm::vec3 horizon = skyRadiance(elevated(0.0f, 90.0f), kSkySun, p);
    // Photometric luminance: Preetham's Y, i.e. before the per-channel calibration.
    EXPECT_LT(luminance(zenith / kSkyCalibration), luminance(horizon / kSkyCalibration)) << turbidity;
    EXPECT_GT(zenith.b / zenith.r, horizon.b / horizon.r) << turbidity;
  }
}

TEST(Sky, SymmetricAboutTheSunsVerticalPlane) {
  // The sun is in the xy plane: mirroring z must not change anything.
  for (float elevation : {0.0f, 10.0f, 35.0f, 70.0f}) {
    for (float azimuth : {15.0f, 60.0f, 120.0f, 170.0f}) {
      const glm::vec3 a = skyRadiance(elevated(elevation, azimuth), kSkySun, {});
      const glm::vec3 b = skyRadiance(elevated(elevation, -azimuth), kSkySun, {});
      EXPECT_NEAR(a.r, b.r, 1e-5f);
      EXPECT_NEAR(a.g, b.g, 1e-5f);
      EXPECT_NEAR(a.b, b.b, 1e-5f);
    }
  }
}

TEST(Sky, BrighterTowardsTheSun) {
  // Along the sun's elevation circle, luminance falls as the azimuth leaves the sun.
  float previous = 1e9f;
  for (float azimuth = 5.0f; azimuth <= 90.0f; azimuth += 5.0f) {
    const float l = luminance(skyRadiance(elevated(40.0f, azimuth), kSkySun, {}));
    EXPECT_LT(l, previous) << azimuth;
    previous = l;
  }
  // The haze's Mie glow is strongest towards the sun.
  const glm::vec3 towards = skyInscatter(elevated(0.0f, 0.0f), kSkySun, {});
  const glm::vec3 away = skyInscatter(elevated(0.0f, 180.0f), kSkySun, {});
  EXPECT_GT(luminance(towards), luminance(away));
}

TEST(Sky, ContinuousEverywhereIncludingTheHorizon) {
  // Small steps in direction give small changes: no jump at the horizon (below it the horizon is seen), at
  // the zenith or around the sun.
  SkyParams p;
  for (float azimuth = 0.0f; azimuth < 360.0f; azimuth += 7.5f) {
    glm::vec3 previous = skyRadiance(elevated(-5.0f, azimuth), kSkySun, p);
    for (float e = -4.9f; e <= 90.0f; e += 0.1f) {
      const glm::vec3 c = skyRadiance(elevated(e, azimuth), kSkySun, p);
      EXPECT_LT(glm::length(c - previous), 0.03f) << azimuth << " " << e;
      previous = c;
    }
  }
  // Below the horizon: exactly the horizon of that azimuth.
  const glm::vec3 below = skyRadiance(elevated(-30.0f, 45.0f), kSkySun, p);
  const glm::vec3 horizon = skyRadiance(elevated(0.0f, 45.0f), kSkySun, p);
  EXPECT_NEAR(glm::length(below - horizon), 0.0f, 1e-5f);
}

TEST(Sky, ExposureScalesAndTurbidityHazes) {
  SkyParams p;
  p.exposure = 0.5f;
  const glm::vec3 a = skyRadiance(elevated(20.0f, 100.0f), kSkySun, {});
  const glm::vec3 b = skyRadiance(elevated(20.0f, 100.0f), kSkySun, p);
  EXPECT_NEAR(b.g, 0.5f * a.g, 1e-5f);
  // Above 1 the roll-off keeps the hue and whitens: continuous at 1, never above 1, monotone.
  EXPECT_EQ(skyHighlight(glm::vec3(0.2f, 0.5f, 1.0f)), glm::vec3(0.2f, 0.5f, 1.0f));
  const glm::vec3 h = skyHighlight(glm::vec3(0.4f, 1.0f, 2.0f)); // hue (0.2, 0.5, 1), whiten by 1/2
  EXPECT_NEAR(h.r, 0.6f, 1e-6f);
  EXPECT_NEAR(h.g, 0.75f, 1e-6f);
  EXPECT_NEAR(h.b, 1.0f, 1e-6f);
  EXPECT_LT(glm::length(skyHighlight(glm::vec3(0.2f, 0.5f, 1.0001f)) - glm::vec3(0.2f, 0.5f, 1.0f)), 1e-3f);
  // Hazier skies are whiter at the zenith (less blue over red).
  SkyParams hazy;
  hazy.turbidity = 8.0f;
  const glm::vec3 clear = skyRadiance({0.0f, 1.0f, 0.0f}, kSkySun, {});
  const glm::vec3 milky = skyRadiance({0.0f, 1.0f, 0.0f}, kSkySun, hazy);
  EXPECT_LT(milky.b / milky.r, clear.b / clear.r);
}

TEST(Sky, AutoExposureKeepsTheHorizonSteady) {
  EXPECT_NEAR(skyAutoExposure(kSkySun, 3.0f), 1.0f, 1e-6f);
  // Hazier skies are brighter in Preetham's model: the auto exposure darkens them, and the horizon's mean
  // photometric luminance after it stays the calibration point's.
  auto meanY = [](const glm::vec3& sun, float turbidity, float exposure) {
    SkyParams p;
    p.turbidity = turbidity;
    p.exposure = exposure;
    float sum = 0.0f;
    for (int i = 0; i < 64; ++i) {
      const float a = 360.0f * (static_cast<float>(i) + 0.5f) / 64.0f;
      // Linear sRGB luminance weights give back Y (before the per-channel calibration).
      sum += luminance(skyRadiance(elevated(0.0f, a), sun, p) / kSkyCalibration);
    }
    return sum / 64.0f;
  };
  const float reference = meanY(kSkySun, 3.0f, 1.0f);
  for (float turbidity : {2.0f, 6.0f, 10.0f}) {
    for (float elevation : {5.0f, 20.0f, 60.0f}) {
      const glm::vec3 sun = elevated(elevation, 30.0f);
      const float exposure = skyAutoExposure(sun, turbidity);
      EXPECT_GT(exposure, 0.0f);
      EXPECT_NEAR(meanY(sun, turbidity, exposure) / reference, 1.0f, 0.02f) << turbidity << " " << elevation;
    }
  }
  EXPECT_LT(skyAutoExposure(kSkySun, 10.0f), skyAutoExposure(kSkySun, 3.0f));
}

TEST(Sky, SunDiscIsBrightInsideAndZeroOutside) {
  SkyParams p;
  EXPECT_GT(luminance(sunDisc(kSkySun, kSkySun, p)), 10.0f);
  const glm::vec3 edge = glm::normalize(kSkySun + glm::vec3(0.0f, 0.0f, 2.0f * kSunAngularRadius));
  EXPECT_EQ(sunDisc(edge, kSkySun, p), glm::vec3(0.0f));
  EXPECT_EQ(sunDisc(-kSkySun, kSkySun, p), glm::vec3(0.0f));
  EXPECT_EQ(skyWithSun(edge, kSkySun, p), skyHighlight(skyRadiance(edge, kSkySun, p)));
}

TEST(Sky, HenyeyGreensteinIsNormalised) {
  // ∫ p dω = 2π ∫ p(cos θ) d cos θ = 1.
  double sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const float mu = -1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / n;
    sum += henyeyGreenstein(mu, kSkyMieG) * 2.0 / n;
  }
  EXPECT_NEAR(2.0 * kPi * sum, 1.0, 1e-3);
  EXPECT_NEAR(henyeyGreenstein(0.3f, 0.0f), 1.0f / (4.0f * kPi), 1e-6f);
}

TEST(Aerial, HazeGrowsMonotonicallyWithDistance) {
  const glm::vec3 lit(0.1f, 0.3f, 0.05f);
  const glm::vec3 view = glm::normalize(glm::vec3(0.3f, -0.1f, 1.0f));
  SkyParams p;
  const glm::vec3 inscatter = skyInscatter(view, kSkySun, p);
  EXPECT_EQ(aerial(lit, view, 0.0f, kSkySun, p), lit);
  float previous = 1e9f;
  for (float d = 50.0f; d <= 20000.0f; d *= 1.5f) {
    const float gap = glm::length(aerial(lit, view, d, kSkySun, p) - inscatter);
    EXPECT_LT(gap, previous) << d;
    previous = gap;
  }
  EXPECT_LT(previous, 1e-3f);
  // Hand value: d = 500 m, density 0.0012: T = e^{−0.6} = 0.548812.
  const float t = std::exp(-0.6f);
  const glm::vec3 expected = lit * t + inscatter * (1.0f - t);
  const glm::vec3 got = aerial(lit, view, 500.0f, kSkySun, p);
  EXPECT_NEAR(got.g, expected.g, 1e-6f);
  EXPECT_NEAR(t, 0.548812f, 1e-6f);
}

TEST(Aerial, InscatterBelowTheHorizonIsTheHorizonSkyPlusGlow) {
  SkyParams p;
  const glm::vec3 down = elevated(-20.0f, 130.0f);
  const glm::vec3 glow = kSunColour * (kSkyMieStrength * p.sunIntensity * p.exposure *
                                       henyeyGreenstein(glm::dot(down, kSkySun), kSkyMieG));
  const glm::vec3 expected = skyHighlight(skyRadiance(elevated(0.0f, 130.0f), kSkySun, p) + glow);
  EXPECT_NEAR(glm::length(skyInscatter(down, kSkySun, p) - expected), 0.0f, 1e-5f);
}

TEST(Flare, GhostsLieOnTheLineThroughTheCentre) {
  const glm::vec2 sun(0.6f, 0.3f);
  const std::vector<FlareGhost> ghosts = flareGhosts(sun);
  ASSERT_EQ(ghosts.size(), static_cast<std::size_t>(kFlareGhostCount));
  EXPECT_EQ(ghosts.front().centre, sun);                             // the halo sits on the sun
  EXPECT_NEAR(glm::length(ghosts.back().centre + sun), 0.0f, 1e-6f); // t = 2: mirrored through the centre
  for (const FlareGhost& g : ghosts) {
    // Collinear with the sun and the centre: cross product zero.
    EXPECT_NEAR(g.centre.x * sun.y - g.centre.y * sun.x, 0.0f, 1e-6f);
    EXPECT_GT(g.radius, 0.0f);
  }
  EXPECT_EQ(flareSpriteProfile(1.0f, 0), 0.0f);
  EXPECT_EQ(flareSpriteProfile(0.0f, 1), 1.0f);
  EXPECT_NEAR(flareSpriteProfile(0.5f, 0), 0.55f, 1e-6f);
}

TEST(Flare, SamplesCoverTheDiscEvenly) {
  int inner = 0;
  for (int i = 0; i < kFlareSamples; ++i) {
    const float r = glm::length(flareSampleOffset(i));
    EXPECT_LE(r, 1.0f);
    inner += r < std::sqrt(0.5f) ? 1 : 0;
  }
  EXPECT_EQ(inner, kFlareSamples / 2); // equal area inside and outside r = 1/√2
}

TEST(Flare, VisibilityCountsTheDepthAtTheSun) {
  const int w = 64;
  const int h = 48;
  const glm::vec4 sun(32.0f, 24.0f, 1.0f, 6.0f);
  auto clear = [](int, int) { return 1.0f; };
  auto covered = [](int, int) { return 0.5f; };
  auto halfCovered = [](int x, int) { return x < 32 ? 0.5f : 1.0f; };
  EXPECT_EQ(flareVisibility(sun, w, h, clear), 1.0f);
  EXPECT_EQ(flareVisibility(sun, w, h, covered), 0.0f);
  const float half = flareVisibility(sun, w, h, halfCovered);
  EXPECT_GT(half, 0.35f);
  EXPECT_LT(half, 0.65f);
  EXPECT_EQ(flareVisibility(glm::vec4(32.0f, 24.0f, 0.0f, 6.0f), w, h, clear), 0.0f);  // behind the camera
  EXPECT_LT(flareVisibility(glm::vec4(64.0f, 24.0f, 1.0f, 6.0f), w, h, clear), 0.65f); // half off the target
}

TEST(Flare, SunProjectsWhereTheCameraLooks) {
  // Looking straight at the sun puts it at the target's centre; looking away puts it behind.
  const glm::vec3 sun = kSkySun;
  const glm::mat4 view = glm::lookAt(glm::vec3(5.0f, 2.0f, -3.0f), glm::vec3(5.0f, 2.0f, -3.0f) + sun,
                                     glm::vec3(0.0f, 1.0f, 0.0f));
  const float f = 1.0f / std::tan(glm::radians(30.0f));
  const glm::mat4 p = glm::perspective(glm::radians(60.0f), 1.5f, 0.1f, 1000.0f);
  const glm::vec4 s = sunScreenPosition(p * view, sun, 96, 64, 2.0f);
  EXPECT_EQ(s.z, 1.0f);
  EXPECT_NEAR(s.x, 48.0f, 1e-3f);
  EXPECT_NEAR(s.y, 32.0f, 1e-3f);
  EXPECT_NEAR(s.w, std::max(f * kSunAngularRadius * 32.0f, 2.0f), 1e-5f);
  EXPECT_EQ(sunScreenPosition(p * view, -sun, 96, 64, 2.0f).z, 0.0f);
  // The sky's ray through the centre is the camera's forward axis, towards the sun.
  const glm::vec3 ray = skyViewDirection(p * view, view, glm::vec2(0.0f));
  EXPECT_NEAR(glm::dot(ray, sun), 1.0f, 1e-5f);
}

} // namespace
} // namespace sylva::render
