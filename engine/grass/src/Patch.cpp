#include <sylva/grass/Patch.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace sylva::grass {

std::vector<gpu::GrassBlade> makePatch(const PatchSettings& s, int types) {
  if (s.blades < 1 || s.blades > (1 << 22)) {
    fail("patch: {} blades outside 1..{}", s.blades, 1 << 22);
  }
  if (!(s.tileSize > 0.0f) || !std::isfinite(s.tileSize)) {
    fail("patch: tile size {} m must be a finite number > 0", s.tileSize);
  }
  if (!(s.minScale > 0.0f) || !(s.maxScale >= s.minScale) || !std::isfinite(s.maxScale)) {
    fail("patch: scale range [{}, {}] must satisfy 0 < min ≤ max", s.minScale, s.maxScale);
  }
  if (types < 1) {
    fail("patch: no blade types");
  }
  std::vector<float> weights = s.typeWeights;
  if (weights.empty()) {
    weights.assign(static_cast<std::size_t>(types), 1.0f);
  }
  if (weights.size() != static_cast<std::size_t>(types)) {
    fail("patch: {} type weights for {} blade types", weights.size(), types);
  }
  float total = 0.0f;
  for (float w : weights) {
    if (!(w >= 0.0f) || !std::isfinite(w)) {
      fail("patch: type weights must be finite and ≥ 0");
    }
    total += w;
  }
  if (total <= 0.0f) {
    fail("patch: type weights sum to zero");
  }
  Rng rng(hash64(s.seed), 0x5eedu);
  // Jittered grid: one root per cell of a side × side grid over the tile (the last row partly filled).
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(s.blades))));
  const float cell = s.tileSize / static_cast<float>(side);
  std::vector<gpu::GrassBlade> patch(static_cast<std::size_t>(s.blades));
  for (int i = 0; i < s.blades; ++i) {
    const int cx = i % side;
    const int cz = i / side;
    gpu::GrassBlade& b = patch[static_cast<std::size_t>(i)];
    const float x = (static_cast<float>(cx) + rng.uniform()) * cell;
    const float z = (static_cast<float>(cz) + rng.uniform()) * cell;
    const float rotation = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
    const float scale = rng.uniform(s.minScale, s.maxScale);
    float pick = rng.uniform(0.0f, total);
    std::uint32_t type = 0;
    while (type + 1 < weights.size() && pick >= weights[type]) {
      pick -= weights[type];
      ++type;
    }
    b.placement = {std::min(x, std::nextafter(s.tileSize, 0.0f)),
                   std::min(z, std::nextafter(s.tileSize, 0.0f)), rotation, scale};
    b.info = {type, rng.nextU32(), 0u, 0u};
  }
  // Shuffle (Fisher–Yates, seeded) so every contiguous range is an unbiased sample of the tile.
  for (std::size_t i = patch.size(); i > 1; --i) {
    std::swap(patch[i - 1], patch[rng.below(static_cast<std::uint32_t>(i))]);
  }
  return patch;
}

std::size_t patchBytes(std::size_t blades, std::size_t types) {
  // Blades, plus per type and level the knots (vec4) and widths (float).
  std::size_t knots = 0;
  for (int k : {16, 8, 4}) {
    knots += static_cast<std::size_t>(k);
  }
  return blades * sizeof(gpu::GrassBlade) + types * knots * (sizeof(float) * 4 + sizeof(float));
}

std::size_t perBladeFieldBytes(std::size_t fieldBlades) {
  // Every blade with its own 16 knots: position vec4 + previous position vec4 (what a solver keeps) + width.
  return fieldBlades * 16 * (sizeof(float) * 4 * 2 + sizeof(float));
}

} // namespace sylva::grass
