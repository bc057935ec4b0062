// The shore rule (docs/scenes.md "Water with a folding-textured shore"): water depth, band weight, slope and
// swash texture coordinates. The water shader (shaders/scene/water.frag) evaluates the same expressions in
// float.
#include <sylva/scene/Shore.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::scene {
namespace {

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

void requirePositive(float value, const char* field) {
  if (!std::isfinite(value) || value <= 0.0f) {
    fail("shore: {} = {} must be finite and > 0", field, value);
  }
}

} // namespace

void validate(const ShoreSettings& s) {
  if (!std::isfinite(s.level)) {
    fail("shore: level = {} must be finite", s.level);
  }
  requirePositive(s.band, "band");
  requirePositive(s.wet, "wet");
  requirePositive(s.tile, "tile");
  if (!std::isfinite(s.period) || s.period < 0.0f) {
    fail("shore: period = {} must be finite and >= 0 (0: the project's)", s.period);
  }
  if (!std::isfinite(s.waterline) || s.waterline < 0.0f || s.waterline > 1.0f) {
    fail("shore: waterline = {} must be in [0, 1]", s.waterline);
  }
  if (s.folding.empty()) {
    fail("shore: folding (the project file) is empty");
  }
}

float waterDepth(const terrain::HeightField& field, float verticalScale, float level, float x, float z) {
  return (level - terrain::heightAt(field, x, z)) / verticalScale;
}

glm::vec2 shoreGradient(const terrain::HeightField& field, float verticalScale, float x, float z) {
  const auto slope = [&](float a0, float a1, bool alongX) {
    if (a1 <= a0) {
      return 0.0f;
    }
    const float h0 = alongX ? terrain::heightAt(field, a0, z) : terrain::heightAt(field, x, a0);
    const float h1 = alongX ? terrain::heightAt(field, a1, z) : terrain::heightAt(field, x, a1);
    const float d = (h1 - h0) / (a1 - a0);
    return std::isfinite(d) ? d / verticalScale : 0.0f;
  };
  const float hx = 0.5f * field.spacingX();
  const float hz = 0.5f * field.spacingZ();
  const float x0 = std::clamp(x - hx, 0.0f, field.extentX());
  const float x1 = std::clamp(x + hx, 0.0f, field.extentX());
  const float z0 = std::clamp(z - hz, 0.0f, field.extentZ());
  const float z1 = std::clamp(z + hz, 0.0f, field.extentZ());
  return {slope(x0, x1, true), slope(z0, z1, false)};
}

float shoreBand(float depth, const ShoreSettings& s) {
  if (std::isnan(depth)) {
    return 0.0f;
  }
  return depth >= 0.0f ? 1.0f - smoothstep(0.0f, s.band, depth) : 1.0f - smoothstep(0.0f, s.wet, -depth);
}

SwashCoords swashCoords(glm::vec2 xz, float depth, glm::vec2 gradient, const ShoreSettings& s, float aspect) {
  constexpr float kStep = 2.0f * std::numbers::pi_v<float> / static_cast<float>(kSwashDirections);
  const float slope = std::max(std::sqrt(gradient.x * gradient.x + gradient.y * gradient.y), kMinShoreSlope);
  const float v = s.waterline + (-depth / slope) / (s.tile * aspect);
  const float angle = std::atan2(gradient.y, gradient.x); // (−π, π]; atan2(0, 0) = 0
  const float sector = angle / kStep;
  const float k0 = std::floor(sector);
  const float f = sector - k0;
  SwashCoords out;
  for (int i = 0; i < 2; ++i) {
    const float a = (k0 + static_cast<float>(i)) * kStep;
    const glm::vec2 t(std::sin(a), -std::cos(a));
    out.uv[i] = glm::vec2((xz.x * t.x + xz.y * t.y) / s.tile, v);
  }
  out.mix = smoothstep(0.3f, 0.7f, f);
  return out;
}

double swashTime(double time, double period, double projectPeriod) {
  if (!(projectPeriod > 0.0) || !std::isfinite(projectPeriod)) {
    fail("shore: the folding project's period {} s must be > 0", projectPeriod);
  }
  const double p = period == 0.0 ? projectPeriod : period;
  if (!(p > 0.0) || !std::isfinite(p)) {
    fail("shore: period = {} s must be > 0", period);
  }
  const double cycles = time / p;
  return (cycles - std::floor(cycles)) * projectPeriod;
}

} // namespace sylva::scene
