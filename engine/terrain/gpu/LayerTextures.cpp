// Procedural, tileable albedo textures for splat layers: the seed paper's multi-texturing needs one texture
// per layer, and Sylva ships no third-party textures. Colours are chosen by keywords in the layer's name.
#include <sylva/terrain/gpu/TerrainRenderer.hpp>

#include <sylva/core/Random.hpp>

#include <array>
#include <cmath>
#include <string>

namespace sylva::terrain {

namespace {

struct Look {
  glm::vec3 base;   // sRGB
  glm::vec3 accent; // sRGB, mixed in by noise
  float contrast;
};

Look lookFor(const std::string& name, int index) {
  auto has = [&](const char* word) { return name.find(word) != std::string::npos; };
  if (has("sand") || has("beach")) {
    return {{0.78f, 0.70f, 0.50f}, {0.66f, 0.58f, 0.40f}, 0.5f};
  }
  if (has("grass") || has("meadow")) {
    return {{0.30f, 0.45f, 0.16f}, {0.45f, 0.52f, 0.20f}, 0.8f};
  }
  if (has("rock") || has("cliff") || has("stone")) {
    return {{0.45f, 0.43f, 0.41f}, {0.30f, 0.29f, 0.28f}, 1.0f};
  }
  if (has("snow") || has("ice")) {
    return {{0.93f, 0.95f, 0.98f}, {0.80f, 0.85f, 0.93f}, 0.4f};
  }
  if (has("dirt") || has("soil") || has("mud")) {
    return {{0.40f, 0.30f, 0.20f}, {0.30f, 0.22f, 0.15f}, 0.7f};
  }
  if (has("forest")) {
    return {{0.16f, 0.28f, 0.12f}, {0.22f, 0.33f, 0.14f}, 0.8f};
  }
  // Unknown names get a distinct muted colour per index.
  const float hue = static_cast<float>(index) * 0.618034f;
  const glm::vec3 c = 0.45f + 0.2f * glm::cos(6.2831853f * (hue + glm::vec3(0.0f, 0.33f, 0.67f)));
  return {c, c * 0.8f, 0.7f};
}

/** Periodic value noise with period `cells` over [0, 1)² (tileable by construction). */
float periodicNoise(float u, float v, int cells, std::uint64_t seed) {
  const float x = u * static_cast<float>(cells);
  const float y = v * static_cast<float>(cells);
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const float fx = x - static_cast<float>(x0);
  const float fy = y - static_cast<float>(y0);
  auto lattice = [&](int i, int j) {
    const auto wi = static_cast<std::uint64_t>(((i % cells) + cells) % cells);
    const auto wj = static_cast<std::uint64_t>(((j % cells) + cells) % cells);
    return static_cast<float>(hash64(seed ^ (wi * 0x9E3779B97F4A7C15ULL) ^ (wj << 32)) >> 40) / 16777216.0f;
  };
  const float sx = fx * fx * (3.0f - 2.0f * fx);
  const float sy = fy * fy * (3.0f - 2.0f * fy);
  const float a = lattice(x0, y0) + (lattice(x0 + 1, y0) - lattice(x0, y0)) * sx;
  const float b = lattice(x0, y0 + 1) + (lattice(x0 + 1, y0 + 1) - lattice(x0, y0 + 1)) * sx;
  return a + (b - a) * sy;
}

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

} // namespace

Image proceduralLayerTexture(const SplatLayer& layer, int index, int size) {
  const Look look = lookFor(layer.name, index);
  const std::uint64_t seed = hash64(static_cast<std::uint64_t>(index) + 1000);
  Image image(size, size, 4, PixelType::U8);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(size);
      const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(size);
      float n = 0.0f;
      float amplitude = 0.5f;
      for (int octave = 0; octave < 5; ++octave) {
        n += amplitude * periodicNoise(u, v, 4 << octave, seed + static_cast<std::uint64_t>(octave));
        amplitude *= 0.5f;
      }
      const float t = std::clamp(0.5f + (n - 0.5f) * 2.0f * look.contrast, 0.0f, 1.0f);
      const glm::vec3 srgb = glm::mix(look.base, look.accent, t);
      // Stored linear: the shader lights in linear space and encodes sRGB at the end.
      image.set(x, y, 0, srgbToLinear(srgb.r));
      image.set(x, y, 1, srgbToLinear(srgb.g));
      image.set(x, y, 2, srgbToLinear(srgb.b));
      image.set(x, y, 3, 1.0f);
    }
  }
  return image;
}

} // namespace sylva::terrain
