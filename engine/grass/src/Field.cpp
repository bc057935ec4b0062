#include <sylva/grass/Field.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::grass {
namespace {

terrain::ProceduralSpec noiseSpec(const DensitySettings& s) {
  terrain::ProceduralSpec spec;
  spec.seed = s.seed;
  return spec;
}

/** 0 below a, 1 above b, smooth between (a ≤ b; a == b is a step). */
float ramp(float a, float b, float x) {
  if (b <= a) {
    return x >= a ? 1.0f : 0.0f;
  }
  const float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

float paintAt(const DensitySettings& s, float x, float z) {
  if (!s.paint || x < s.paintMin.x || z < s.paintMin.y || x > s.paintMax.x || z > s.paintMax.y) {
    return 1.0f;
  }
  const Image& img = *s.paint;
  const float u = (x - s.paintMin.x) / (s.paintMax.x - s.paintMin.x) * static_cast<float>(img.width()) - 0.5f;
  const float v =
      (z - s.paintMin.y) / (s.paintMax.y - s.paintMin.y) * static_cast<float>(img.height()) - 0.5f;
  const int x0 = std::clamp(static_cast<int>(std::floor(u)), 0, img.width() - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(v)), 0, img.height() - 1);
  const int x1 = std::min(x0 + 1, img.width() - 1);
  const int y1 = std::min(y0 + 1, img.height() - 1);
  const float fu = std::clamp(u - std::floor(u), 0.0f, 1.0f);
  const float fv = std::clamp(v - std::floor(v), 0.0f, 1.0f);
  const float top = img.get(x0, y0, 0) * (1.0f - fu) + img.get(x1, y0, 0) * fu;
  const float bottom = img.get(x0, y1, 0) * (1.0f - fu) + img.get(x1, y1, 0) * fu;
  return top * (1.0f - fv) + bottom * fv;
}

} // namespace

DensityMap::DensityMap(DensitySettings settings)
    : mSettings(std::move(settings)), mNoise(noiseSpec(mSettings)) {
  const DensitySettings& s = mSettings;
  const std::pair<float, const char*> finite[] = {{s.base, "base"},
                                                  {s.noiseFrequency, "noiseFrequency"},
                                                  {s.coverage, "coverage"},
                                                  {s.contrast, "contrast"},
                                                  {s.heightFade, "heightFade"},
                                                  {s.maxSlopeDegrees, "maxSlopeDegrees"},
                                                  {s.slopeFade, "slopeFade"},
                                                  {s.verticalScale, "verticalScale"}};
  for (const auto& [v, name] : finite) {
    if (!std::isfinite(v) || v < 0.0f) {
      fail("grass density: {} must be a finite number ≥ 0, got {}", name, v);
    }
  }
  if (!(s.verticalScale > 0.0f)) {
    fail("grass density: verticalScale must be > 0, got {}", s.verticalScale);
  }
  if (std::isnan(s.minHeight) || std::isnan(s.maxHeight) || s.minHeight > s.maxHeight) {
    fail("grass density: height range [{}, {}] is empty", s.minHeight, s.maxHeight);
  }
  if (s.paint && (s.paint->empty() || !(s.paintMax.x > s.paintMin.x) || !(s.paintMax.y > s.paintMin.y))) {
    fail("grass density: the paint mask needs an image and a rectangle with area");
  }
}

float DensityMap::noise(float x, float z) const {
  const DensitySettings& s = mSettings;
  // Two octaves of gradient noise (about [-1, 1]) → [0, 1], then a contrast curve centred where `coverage` of
  // the ground stays covered.
  const double f = s.noiseFrequency;
  const double n = 0.7 * mNoise.perlin(0, x * f, z * f) + 0.3 * mNoise.perlin(1, x * f * 2.7, z * f * 2.7);
  const float v = static_cast<float>(0.5 + 0.5 * n);
  // v is about normal around 0.5 with σ ≈ 0.11; centring the ramp at 0.5 + 0.25·(0.5 − coverage) leaves about
  // `coverage` of the ground with density above one half.
  const float centre = 0.5f + 0.25f * (0.5f - s.coverage);
  return std::clamp((v - centre) * s.contrast + 0.5f, 0.0f, 1.0f);
}

float DensityMap::at(float x, float z, float height, float slopeDegrees) const {
  const DensitySettings& s = mSettings;
  if (std::isnan(height)) {
    return 0.0f;
  }
  float d = s.base * noise(x, z);
  if (std::isfinite(s.minHeight)) {
    d *= ramp(s.minHeight, s.minHeight + s.heightFade, height);
  }
  if (std::isfinite(s.maxHeight)) {
    d *= 1.0f - ramp(s.maxHeight - s.heightFade, s.maxHeight, height);
  }
  d *= 1.0f - ramp(s.maxSlopeDegrees - s.slopeFade, s.maxSlopeDegrees, slopeDegrees);
  d *= paintAt(s, x, z);
  if (s.layer) {
    const float trueSlope =
        std::atan(std::tan(std::clamp(slopeDegrees, 0.0f, 89.9f) * 0.01745329f) / s.verticalScale) *
        57.29578f;
    d *= std::clamp(terrain::splatWeight(*s.layer, height / s.verticalScale, trueSlope), 0.0f, 1.0f);
  }
  return std::clamp(d, 0.0f, 1.0f);
}

DensityGrid::DensityGrid(const DensityMap& map, const terrain::HeightField& terrain, float maxSpacing) {
  if (!(maxSpacing > 0.0f) || !std::isfinite(maxSpacing)) {
    fail("grass density: grid spacing {} m must be a finite number > 0", maxSpacing);
  }
  const double ex = std::max(terrain.extentX(), 1e-3f);
  const double ez = std::max(terrain.extentZ(), 1e-3f);
  double cellsX = std::ceil(ex / maxSpacing);
  double cellsZ = std::ceil(ez / maxSpacing);
  constexpr double kMaxSamples = 16777216.0;
  if ((cellsX + 1.0) * (cellsZ + 1.0) > kMaxSamples) {
    const double f = std::sqrt((cellsX + 1.0) * (cellsZ + 1.0) / kMaxSamples);
    cellsX = std::floor(cellsX / f) - 1.0;
    cellsZ = std::floor(cellsZ / f) - 1.0;
  }
  mWidth = static_cast<int>(std::max(cellsX, 1.0)) + 1;
  mHeight = static_cast<int>(std::max(cellsZ, 1.0)) + 1;
  mSpacing = glm::vec2(static_cast<float>(ex / (mWidth - 1)), static_cast<float>(ez / (mHeight - 1)));
  mValues.assign(static_cast<std::size_t>(mWidth) * static_cast<std::size_t>(mHeight), 0.0f);
  parallelFor(
      static_cast<std::size_t>(mHeight),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
          for (int i = 0; i < mWidth; ++i) {
            const float x = std::min(static_cast<float>(i) * mSpacing.x, terrain.extentX());
            const float z = std::min(static_cast<float>(j) * mSpacing.y, terrain.extentZ());
            const float h = terrain::heightAt(terrain, x, z);
            float d = 0.0f;
            if (!std::isnan(h)) {
              const glm::vec3 n = terrain::normalAt(terrain, x, z);
              const float slope = std::acos(std::clamp(n.y, -1.0f, 1.0f)) * 57.29578f;
              d = map.at(x, z, h, std::isnan(slope) ? 90.0f : slope);
            }
            mValues[j * static_cast<std::size_t>(mWidth) + static_cast<std::size_t>(i)] = d;
          }
        }
      },
      4);
}

float DensityGrid::at(float x, float z) const {
  if (mValues.empty()) {
    return 0.0f;
  }
  // The same arithmetic as grassDensity() in shaders/grass/grass.glsl.
  const float gx = std::clamp(x / mSpacing.x, 0.0f, static_cast<float>(mWidth - 1));
  const float gz = std::clamp(z / mSpacing.y, 0.0f, static_cast<float>(mHeight - 1));
  const int i0 = std::min(static_cast<int>(std::floor(gx)), mWidth - 2);
  const int j0 = std::min(static_cast<int>(std::floor(gz)), mHeight - 2);
  const float fx = gx - static_cast<float>(i0);
  const float fz = gz - static_cast<float>(j0);
  const auto v = [&](int i, int j) {
    return mValues[static_cast<std::size_t>(j) * static_cast<std::size_t>(mWidth) +
                   static_cast<std::size_t>(i)];
  };
  const float top = v(i0, j0) * (1.0f - fx) + v(i0 + 1, j0) * fx;
  const float bottom = v(i0, j0 + 1) * (1.0f - fx) + v(i0 + 1, j0 + 1) * fx;
  return top * (1.0f - fz) + bottom * fz;
}

float rootHeight(const terrain::HeightField& terrain, float x, float z) {
  const int w = terrain.width();
  const int h = terrain.height();
  if (w < 2 || h < 2) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  // terrainHeight() of shaders/terrain/terrain.glsl (and grassTerrainHeight()), in the same order.
  const float gx = std::clamp(x / terrain.spacingX(), 0.0f, static_cast<float>(w - 1));
  const float gz = std::clamp(z / terrain.spacingZ(), 0.0f, static_cast<float>(h - 1));
  const int i0 = std::min(static_cast<int>(std::floor(gx)), w - 2);
  const int j0 = std::min(static_cast<int>(std::floor(gz)), h - 2);
  if (!terrain.valid(i0, j0) || !terrain.valid(i0 + 1, j0) || !terrain.valid(i0, j0 + 1) ||
      !terrain.valid(i0 + 1, j0 + 1)) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  const float fx = gx - static_cast<float>(i0);
  const float fz = gz - static_cast<float>(j0);
  const float top = terrain.at(i0, j0) * (1.0f - fx) + terrain.at(i0 + 1, j0) * fx;
  const float bottom = terrain.at(i0, j0 + 1) * (1.0f - fx) + terrain.at(i0 + 1, j0 + 1) * fx;
  return top * (1.0f - fz) + bottom * fz;
}

glm::vec2 tileHeightRange(const FieldLayout& layout, const terrain::HeightField& terrain, int tx, int tz,
                          glm::vec2 whole) {
  const glm::vec2 lo =
      layout.origin + glm::vec2(static_cast<float>(tx), static_cast<float>(tz)) * layout.tileSize;
  const glm::vec2 hi = lo + glm::vec2(layout.tileSize);
  const int i0 = std::clamp(static_cast<int>(std::floor(lo.x / terrain.spacingX())), 0, terrain.width() - 1);
  const int i1 = std::clamp(static_cast<int>(std::ceil(hi.x / terrain.spacingX())), 0, terrain.width() - 1);
  const int j0 = std::clamp(static_cast<int>(std::floor(lo.y / terrain.spacingZ())), 0, terrain.height() - 1);
  const int j1 = std::clamp(static_cast<int>(std::ceil(hi.y / terrain.spacingZ())), 0, terrain.height() - 1);
  if ((i1 - i0 + 1) * (j1 - j0 + 1) > kMaxTileRangeSamples) {
    return whole;
  }
  glm::vec2 range(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity());
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      if (terrain.valid(i, j)) {
        range.x = std::min(range.x, terrain.at(i, j));
        range.y = std::max(range.y, terrain.at(i, j));
      }
    }
  }
  return range;
}

glm::ivec4 tileWindow(const FieldLayout& layout, glm::vec2 eye, float distance) {
  // The same arithmetic as GrassRenderer::cull's dispatch window.
  const glm::vec2 lo = (eye - glm::vec2(distance) - layout.origin) / layout.tileSize;
  const glm::vec2 hi = (eye + glm::vec2(distance) - layout.origin) / layout.tileSize;
  const auto clampTo = [](float v, int n) {
    return static_cast<int>(std::clamp(std::floor(v), 0.0f, static_cast<float>(n)));
  };
  const int x0 = clampTo(lo.x, layout.tilesX);
  const int z0 = clampTo(lo.y, layout.tilesZ);
  const int x1 = clampTo(hi.x + 1.0f, layout.tilesX);
  const int z1 = clampTo(hi.y + 1.0f, layout.tilesZ);
  return {x0, z0, x1 - x0, z1 - z0};
}

FieldLayout layoutOver(const terrain::HeightField& terrain, float tileSize, int bladesPerTile) {
  if (!(tileSize > 0.0f) || !std::isfinite(tileSize)) {
    fail("grass: tile size {} m must be a finite number > 0", tileSize);
  }
  if (bladesPerTile < 1) {
    fail("grass: blades per tile must be ≥ 1, got {}", bladesPerTile);
  }
  FieldLayout layout;
  layout.tileSize = tileSize;
  layout.bladesPerTile = bladesPerTile;
  const double tx = std::ceil(static_cast<double>(terrain.extentX()) / tileSize);
  const double tz = std::ceil(static_cast<double>(terrain.extentZ()) / tileSize);
  if (tx > static_cast<double>(1 << 20) || tz > static_cast<double>(1 << 20)) {
    fail("grass: {:.0f} x {:.0f} tiles of {} m is more than 2^20 tiles along a side", tx, tz, tileSize);
  }
  layout.tilesX = std::max(1, static_cast<int>(tx));
  layout.tilesZ = std::max(1, static_cast<int>(tz));
  return layout;
}

std::uint32_t tileStart(int tx, int tz, std::uint32_t patchBlades) {
  // grassTileStart() in shaders/grass/grass.glsl: 32-bit arithmetic wraps the same in C++ and GLSL.
  const std::uint32_t key =
      static_cast<std::uint32_t>(tx) * 0x9e3779b1u ^ lowbias32(static_cast<std::uint32_t>(tz) ^ 0x85ebca6bu);
  return lowbias32(key) % patchBlades;
}

void forEachTileBlade(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                      const terrain::HeightField& terrain, const DensityGrid& density, int tx, int tz,
                      const std::function<void(const FieldBlade&)>& visit) {
  if (patch.empty()) {
    return;
  }
  const auto n = static_cast<std::uint32_t>(patch.size());
  const std::uint32_t start = tileStart(tx, tz, n);
  const glm::vec2 corner =
      layout.origin + glm::vec2(static_cast<float>(tx), static_cast<float>(tz)) * layout.tileSize;
  const int count = std::min<int>(layout.bladesPerTile, static_cast<int>(n));
  for (int j = 0; j < count; ++j) {
    const std::uint32_t index = (start + static_cast<std::uint32_t>(j)) % n;
    const gpu::GrassBlade& b = patch[index];
    const glm::vec2 xz = corner + glm::vec2(b.placement.x, b.placement.y);
    if (xz.x < 0.0f || xz.y < 0.0f || xz.x > terrain.extentX() || xz.y > terrain.extentZ()) {
      continue;
    }
    const float height = rootHeight(terrain, xz.x, xz.y);
    if (std::isnan(height)) {
      continue;
    }
    if ((static_cast<float>(j) + 0.5f) / static_cast<float>(layout.bladesPerTile) >= density.at(xz.x, xz.y)) {
      continue;
    }
    visit({glm::vec3(xz.x, height, xz.y), index, j, tx, tz});
  }
}

std::size_t countFieldBlades(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                             const terrain::HeightField& terrain, const DensityGrid& density) {
  std::size_t count = 0;
  for (int tz = 0; tz < layout.tilesZ; ++tz) {
    for (int tx = 0; tx < layout.tilesX; ++tx) {
      forEachTileBlade(layout, patch, terrain, density, tx, tz, [&](const FieldBlade&) { ++count; });
    }
  }
  return count;
}

} // namespace sylva::grass
