// The wind field: gusts travel downwind, places across the wind sway independently (no field waving in
// unison), statistics match the settings, validation names the field.
#include <sylva/core/Error.hpp>
#include <sylva/wind/Wind.hpp>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace sylva::wind {
namespace {

std::vector<float> gustSeries(const WindSettings& s, glm::vec2 at, int samples, float dt) {
  std::vector<float> out;
  for (int i = 0; i < samples; ++i) {
    out.push_back(gustSpeed(toUniforms(s, static_cast<float>(i) * dt), at));
  }
  return out;
}

double correlation(const std::vector<float>& a, const std::vector<float>& b, int lag) {
  double ma = 0.0;
  double mb = 0.0;
  int n = 0;
  for (std::size_t i = 0; i + lag < a.size(); ++i) {
    ma += a[i];
    mb += b[i + lag];
    ++n;
  }
  ma /= n;
  mb /= n;
  double sab = 0.0;
  double saa = 0.0;
  double sbb = 0.0;
  for (std::size_t i = 0; i + lag < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i + lag] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i + lag] - mb) * (b[i + lag] - mb);
  }
  return sab / std::sqrt(saa * sbb + 1e-30);
}

TEST(Wind, ValueNoiseIsBoundedContinuousAndSeeded) {
  float lo = 1.0f;
  float hi = -1.0f;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 p(i * 0.173f - 50.0f, i * 0.071f, i * 0.029f - 7.0f);
    const float v = valueNoise(p, 5);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    EXPECT_NEAR(valueNoise(p + glm::vec3(1e-4f), 5), v, 1e-2f);
  }
  EXPECT_GE(lo, -1.0f);
  EXPECT_LE(hi, 1.0f);
  EXPECT_LT(lo, -0.5f);
  EXPECT_GT(hi, 0.5f);
  EXPECT_NE(valueNoise({0.5f, 0.5f, 0.5f}, 1), valueNoise({0.5f, 0.5f, 0.5f}, 2));
}

TEST(Wind, GustsTravelDownwindAtTheirSpeed) {
  WindSettings s;
  s.direction = {1.0f, 0.0f};
  s.speed = 5.0f;
  s.gustTravel = 1.0f;
  const float dt = 0.25f;
  const float distance = 20.0f; // 4 s downwind at 5 m/s: a lag of 16 samples
  const std::vector<float> upwind = gustSeries(s, {0.0f, 3.0f}, 800, dt);
  const std::vector<float> downwind = gustSeries(s, {distance, 3.0f}, 800, dt);
  int bestLag = 0;
  double best = -2.0;
  for (int lag = 0; lag < 40; ++lag) {
    const double c = correlation(upwind, downwind, lag);
    if (c > best) {
      best = c;
      bestLag = lag;
    }
  }
  EXPECT_NEAR(bestLag, 16, 1);
  // Gusts also change shape as they travel (0.82 over these 4 s), so the lagged match is strong, not perfect.
  EXPECT_GT(best, 0.75);
  EXPECT_GT(best, correlation(upwind, downwind, 0) + 0.3);
}

TEST(Wind, PlacesAcrossTheWindDoNotMoveInUnison) {
  WindSettings s;
  const std::vector<float> a = gustSeries(s, {0.0f, 0.0f}, 800, 0.25f);
  const std::vector<float> b = gustSeries(s, {0.0f, 60.0f}, 800, 0.25f);
  EXPECT_LT(std::abs(correlation(a, b, 0)), 0.5);
  // Yet neighbours a metre apart move together (coherent gusts, not per-blade noise).
  const std::vector<float> c = gustSeries(s, {0.0f, 1.0f}, 800, 0.25f);
  EXPECT_GT(correlation(a, c, 0), 0.9);
}

TEST(Wind, MeanAndGustStrengthFollowTheSettings) {
  WindSettings s;
  s.speed = 4.0f;
  s.gustStrength = 0.5f;
  s.turbulence = 0.0f;
  double sum = 0.0;
  float peak = 0.0f;
  int n = 0;
  for (int i = 0; i < 4000; ++i) {
    const glm::vec2 at(static_cast<float>(i % 64) * 7.3f, static_cast<float>(i / 64) * 5.1f);
    const gpu::WindUniforms u = toUniforms(s, static_cast<float>(i) * 0.37f);
    const glm::vec2 v = windVelocity(u, at);
    // Without turbulence the wind blows along the mean direction, never slower than the mean speed.
    EXPECT_NEAR(v.y, 0.0f, 1e-6f);
    EXPECT_GE(v.x, 4.0f - 1e-5f);
    EXPECT_LE(v.x, 4.0f * 1.5f + 1e-4f);
    sum += v.x;
    peak = std::max(peak, v.x);
    ++n;
  }
  EXPECT_GT(peak, 4.0f * 1.35f);
  EXPECT_GT(sum / n, 4.05);
  EXPECT_LT(sum / n, 4.0 * 1.3);
}

TEST(Wind, BatchedVelocitiesEqualTheScalarOnesBitForBit) {
  // windVelocities (eight lanes, AVX2 where there is one) against windVelocity: every point, several times,
  // positions far from the origin and negative (floor by truncation), time offsets per point.
  WindSettings settings;
  settings.direction = {-0.6f, 0.8f};
  settings.speed = 9.0f;
  settings.gustStrength = 1.5f;
  settings.seed = 77;
  std::vector<glm::vec2> positions;
  std::vector<float> offsets;
  for (int i = 0; i < 1003; ++i) {
    const float a = static_cast<float>(i);
    positions.emplace_back(std::sin(a * 1.7f) * (a * 3.1f - 900.0f), std::cos(a * 0.37f) * a * 1.3f);
    offsets.push_back(i % 5 == 0 ? 0.0f : std::fmod(a * 13.7f, 600.0f));
  }
  positions[3] = {-1.0f, -2.0f}; // integer lattice points, negative
  positions[4] = {0.0f, -0.0f};
  std::vector<glm::vec2> out(positions.size());
  for (const float time : {0.0f, 3.25f, 1234.5f}) {
    const gpu::WindUniforms u = toUniforms(settings, time);
    windVelocities(u, positions, offsets, out);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      gpu::WindUniforms shifted = u;
      shifted.flow.w = shifted.flow.w + offsets[i];
      const glm::vec2 expected = windVelocity(shifted, positions[i]);
      ASSERT_EQ(expected.x, out[i].x) << "point " << i << " at t = " << time;
      ASSERT_EQ(expected.y, out[i].y) << "point " << i << " at t = " << time;
    }
    windVelocities(u, positions, {}, out);
    for (std::size_t i = 0; i < positions.size(); ++i) {
      ASSERT_EQ(windVelocity(u, positions[i]), out[i]) << "point " << i << " without offsets";
    }
  }
  std::vector<glm::vec2> tooFew(3);
  EXPECT_THROW(windVelocities(toUniforms(settings, 0.0f), positions, offsets, tooFew), Error);
}

TEST(Wind, JsonRoundTripAndValidation) {
  WindSettings s;
  s.direction = {0.0f, 2.0f};
  s.speed = 7.5f;
  s.seed = 42;
  const WindSettings back = windSettingsFromJson(toJson(s), "scene.json: wind");
  EXPECT_EQ(back.direction, s.direction);
  EXPECT_EQ(back.speed, 7.5f);
  EXPECT_EQ(back.seed, 42u);
  auto message = [](const nlohmann::json& j) {
    try {
      windSettingsFromJson(j, "w");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(message({{"speed", -1.0}}).find("speed"), std::string::npos);
  EXPECT_NE(message({{"direction", {0.0, 0.0}}}).find("direction"), std::string::npos);
  EXPECT_NE(message({{"gustLength", 0.0}}).find("gustLength"), std::string::npos);
  EXPECT_NE(message({{"gale", 1.0}}).find("/gale: unknown field"), std::string::npos);
  WindSettings nan;
  nan.turbulence = std::nanf("");
  EXPECT_THROW(toUniforms(nan, 0.0f), Error);
}

} // namespace
} // namespace sylva::wind
