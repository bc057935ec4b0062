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

std::vector<glm::uvec4> waterRects(const terrain::HeightField& field, const WaterGrid& grid,
                                   std::span<const std::uint32_t> cells, float level, float lift) {
  const std::size_t total = static_cast<std::size_t>(grid.cellsX) * static_cast<std::size_t>(grid.cellsZ);
  // 0: not drawn, 1: a wet cell drawn alone, 2: a wet cell whose surface is flat at the level.
  std::vector<std::uint8_t> kind(total, 0);
  const int w = field.width();
  const int h = field.height();
  const std::vector<float>& samples = field.samples();
  const auto flatCorner = [&](int gx, int gz) {
    // The water shader's vertex: sample min(g · stride, field − 1), surface max(level, height + lift).
    const int sx = std::min(gx * grid.stride, w - 1);
    const int sz = std::min(gz * grid.stride, h - 1);
    const float height = samples[static_cast<std::size_t>(sz) * static_cast<std::size_t>(w) + sx];
    return std::isfinite(height) && height + lift <= level;
  };
  for (std::uint32_t c : cells) {
    if (c >= total) {
      fail("shore: water cell {} outside the {}x{} grid", c, grid.cellsX, grid.cellsZ);
    }
    const int cx = static_cast<int>(c % static_cast<std::uint32_t>(grid.cellsX));
    const int cz = static_cast<int>(c / static_cast<std::uint32_t>(grid.cellsX));
    const bool flat =
        flatCorner(cx, cz) && flatCorner(cx + 1, cz) && flatCorner(cx, cz + 1) && flatCorner(cx + 1, cz + 1);
    kind[c] = flat ? 2 : 1;
  }
  const auto at = [&](int x, int z) -> std::uint8_t& {
    return kind[static_cast<std::size_t>(z) * static_cast<std::size_t>(grid.cellsX) +
                static_cast<std::size_t>(x)];
  };
  // Aligned square blocks of flat cells, largest first (a fan of a b × b block has 8b triangles against the
  // cells' 2b²: worth it from b = 8), then every cell left on its own.
  std::vector<glm::uvec4> rects;
  for (int b = 64; b >= 8; b /= 2) {
    for (int z = 0; z + b <= grid.cellsZ; z += b) {
      for (int x = 0; x + b <= grid.cellsX; x += b) {
        bool flat = true;
        for (int j = 0; j < b && flat; ++j) {
          for (int i = 0; i < b && flat; ++i) {
            flat = at(x + i, z + j) == 2;
          }
        }
        if (!flat) {
          continue;
        }
        for (int j = 0; j < b; ++j) {
          for (int i = 0; i < b; ++i) {
            at(x + i, z + j) = 0;
          }
        }
        rects.emplace_back(x, z, b, b);
      }
    }
  }
  for (int z = 0; z < grid.cellsZ; ++z) {
    for (int x = 0; x < grid.cellsX; ++x) {
      if (at(x, z) != 0) {
        rects.emplace_back(x, z, 1, 1);
      }
    }
  }
  return rects;
}

std::vector<glm::ivec2> waterTriangles(std::span<const glm::uvec4> rects) {
  std::vector<glm::ivec2> points;
  const auto cell = [&](int x, int z) {
    for (const glm::ivec2 c : {glm::ivec2(0, 0), glm::ivec2(0, 1), glm::ivec2(1, 0), glm::ivec2(1, 0),
                               glm::ivec2(0, 1), glm::ivec2(1, 1)}) {
      points.push_back(glm::ivec2(x, z) + c);
    }
  };
  // The cells' turn: (0,0) → (0,1) → (1,0) has cross((b − a), (c − a)) < 0 in (x, z).
  const auto triangle = [&](glm::ivec2 a, glm::ivec2 b, glm::ivec2 c) {
    const glm::ivec2 u = b - a;
    const glm::ivec2 v = c - a;
    if (u.x * v.y - u.y * v.x > 0) {
      std::swap(b, c);
    }
    points.push_back(a);
    points.push_back(b);
    points.push_back(c);
  };
  for (const glm::uvec4& r : rects) {
    const int x0 = static_cast<int>(r.x);
    const int z0 = static_cast<int>(r.y);
    const int w = static_cast<int>(r.z);
    const int h = static_cast<int>(r.w);
    if (w < 2 || h < 2) {
      for (int z = z0; z < z0 + h; ++z) {
        for (int x = x0; x < x0 + w; ++x) {
          cell(x, z);
        }
      }
      continue;
    }
    // The border, corner by corner, and a fan from an inner grid point.
    std::vector<glm::ivec2> border;
    for (int x = x0; x < x0 + w; ++x) {
      border.emplace_back(x, z0);
    }
    for (int z = z0; z < z0 + h; ++z) {
      border.emplace_back(x0 + w, z);
    }
    for (int x = x0 + w; x > x0; --x) {
      border.emplace_back(x, z0 + h);
    }
    for (int z = z0 + h; z > z0; --z) {
      border.emplace_back(x0, z);
    }
    const glm::ivec2 centre(x0 + w / 2, z0 + h / 2);
    for (std::size_t i = 0; i < border.size(); ++i) {
      triangle(centre, border[i], border[(i + 1) % border.size()]);
    }
  }
  return points;
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
