#include <sylva/grass/Field.hpp>

#include <sylva/core/Error.hpp>
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
  const std::pair<float, const char*> finite[] = {
      {s.base, "base"},          {s.noiseFrequency, "noiseFrequency"}, {s.coverage, "coverage"},
      {s.contrast, "contrast"},  {s.heightFade, "heightFade"},         {s.maxSlopeDegrees, "maxSlopeDegrees"},
      {s.slopeFade, "slopeFade"}};
  for (const auto& [v, name] : finite) {
    if (!std::isfinite(v) || v < 0.0f) {
      fail("grass density: {} must be a finite number ≥ 0, got {}", name, v);
    }
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
  return std::clamp(d, 0.0f, 1.0f);
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
  if (tx * tz > static_cast<double>(1 << 26)) {
    fail("grass: {:.0f} x {:.0f} tiles of {} m is more than 2^26 tiles", tx, tz, tileSize);
  }
  layout.tilesX = std::max(1, static_cast<int>(tx));
  layout.tilesZ = std::max(1, static_cast<int>(tz));
  return layout;
}

std::uint32_t tileStart(int tx, int tz, std::uint32_t patchBlades) {
  const std::uint64_t key =
      (static_cast<std::uint64_t>(static_cast<std::uint32_t>(tx)) << 32) | static_cast<std::uint32_t>(tz);
  return static_cast<std::uint32_t>(hash64(key) % patchBlades);
}

void forEachTileBlade(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                      const terrain::HeightField& terrain, const DensityMap& density, int tx, int tz,
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
    const float height = terrain::heightAt(terrain, xz.x, xz.y);
    if (std::isnan(height)) {
      continue;
    }
    const glm::vec3 normal = terrain::normalAt(terrain, xz.x, xz.y);
    const float slope = std::acos(std::clamp(normal.y, -1.0f, 1.0f)) * 57.29578f;
    if ((static_cast<float>(j) + 0.5f) / static_cast<float>(layout.bladesPerTile) >=
        density.at(xz.x, xz.y, height, slope)) {
      continue;
    }
    visit({glm::vec3(xz.x, height, xz.y), index, j, tx, tz});
  }
}

std::size_t countFieldBlades(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                             const terrain::HeightField& terrain, const DensityMap& density) {
  std::size_t count = 0;
  for (int tz = 0; tz < layout.tilesZ; ++tz) {
    for (int tx = 0; tx < layout.tilesX; ++tx) {
      forEachTileBlade(layout, patch, terrain, density, tx, tz, [&](const FieldBlade&) { ++count; });
    }
  }
  return count;
}

} // namespace sylva::grass
