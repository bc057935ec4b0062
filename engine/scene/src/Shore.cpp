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

WaterGrid waterGrid(int fieldWidth, int fieldHeight, int maxCells) {
  if (fieldWidth < 2 || fieldHeight < 2 || maxCells < 1) {
    fail("shore: a water grid needs at least 2x2 samples and 1 cell (got {}x{}, {})", fieldWidth, fieldHeight,
         maxCells);
  }
  WaterGrid g;
  const int longest = std::max(fieldWidth, fieldHeight) - 1;
  g.stride = (longest + maxCells - 1) / maxCells;
  g.cellsX = (fieldWidth - 1 + g.stride - 1) / g.stride;
  g.cellsZ = (fieldHeight - 1 + g.stride - 1) / g.stride;
  return g;
}

std::vector<std::uint32_t> wetCells(const terrain::HeightField& field, const WaterGrid& grid, float wetTop,
                                    float tolerance) {
  const int w = field.width();
  const int h = field.height();
  const float dryFrom = wetTop + std::max(tolerance, 0.0f);
  // Rows of the sample grid: whether a sample is wet, then per cell its samples plus a one-sample ring.
  std::vector<std::uint8_t> wet(static_cast<std::size_t>(w) * h);
  const std::vector<float>& samples = field.samples();
  for (std::size_t i = 0; i < wet.size(); ++i) {
    wet[i] = samples[i] < dryFrom ? 1 : 0; // NaN compares false: dry
  }
  std::vector<std::uint32_t> cells;
  for (int cz = 0; cz < grid.cellsZ; ++cz) {
    const int z0 = std::max(cz * grid.stride - 1, 0);
    const int z1 = std::min((cz + 1) * grid.stride + 1, h - 1);
    for (int cx = 0; cx < grid.cellsX; ++cx) {
      const int x0 = std::max(cx * grid.stride - 1, 0);
      const int x1 = std::min((cx + 1) * grid.stride + 1, w - 1);
      bool any = false;
      for (int z = z0; z <= z1 && !any; ++z) {
        const std::uint8_t* row = &wet[static_cast<std::size_t>(z) * w];
        for (int x = x0; x <= x1 && !any; ++x) {
          any = row[x] != 0;
        }
      }
      if (any) {
        cells.push_back(static_cast<std::uint32_t>(cx + cz * grid.cellsX));
      }
    }
  }
  return cells;
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
