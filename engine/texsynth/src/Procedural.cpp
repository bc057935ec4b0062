#include <sylva/texsynth/Procedural.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sylva::texsynth {

namespace {

/** Hash of an integer lattice point to [0, 1). */
float lattice(std::uint64_t seed, int x, int y) {
  const std::uint64_t h =
      hash64(seed ^ hash64((static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
                           static_cast<std::uint32_t>(y)));
  return static_cast<float>(h >> 40) / static_cast<float>(1 << 24);
}

/** Smooth value noise in [0, 1) at (x, y) in lattice units. */
float valueNoise(std::uint64_t seed, float x, float y) {
  const float fx = std::floor(x);
  const float fy = std::floor(y);
  const int ix = static_cast<int>(fx);
  const int iy = static_cast<int>(fy);
  const float tx = x - fx;
  const float ty = y - fy;
  const float sx = tx * tx * (3.0f - 2.0f * tx);
  const float sy = ty * ty * (3.0f - 2.0f * ty);
  const float a = lattice(seed, ix, iy);
  const float b = lattice(seed, ix + 1, iy);
  const float c = lattice(seed, ix, iy + 1);
  const float d = lattice(seed, ix + 1, iy + 1);
  return (a + (b - a) * sx) + ((c + (d - c) * sx) - (a + (b - a) * sx)) * sy;
}

} // namespace

Texture proceduralBark(int size, std::uint64_t seed) {
  if (size < 16 || size > 4096) {
    fail("size: {} is out of range [16, 4096]", size);
  }
  Texture texture = Texture::blank(size, size, 6, "procedural bark");
  // Heights: grooves run along the rows (vertical in the picture), about 12 per 256 texels; their columns
  // waver with low-frequency noise and their depth varies along the groove.
  std::vector<float> height(static_cast<std::size_t>(size) * size);
  const float period = 22.0f;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float waver = 6.0f * (valueNoise(seed ^ 1u, x / 64.0f, y / 48.0f) - 0.5f);
      const float phase = (static_cast<float>(x) + waver) / period;
      const float ridge = std::pow(std::abs(std::sin(3.14159265f * phase)), 0.6f);
      const float depth = 0.5f + 0.5f * valueNoise(seed ^ 2u, phase, y / 40.0f);
      const float fine = valueNoise(seed ^ 3u, x / 3.0f, y / 5.0f);
      height[static_cast<std::size_t>(y) * size + x] = ridge * depth + 0.15f * fine;
    }
  }
  const auto h = [&](int x, int y) {
    x = std::min(std::max(x, 0), size - 1);
    y = std::min(std::max(y, 0), size - 1);
    return height[static_cast<std::size_t>(y) * size + x];
  };
  const float strength = 2.5f;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float v = h(x, y);
      const float tint = valueNoise(seed ^ 4u, x / 90.0f, y / 90.0f);
      float* texel = texture.at(x, y);
      // Dark brown in the grooves, lighter grey-brown on the ridges.
      texel[0] = std::clamp(0.16f + 0.34f * v + 0.06f * tint, 0.0f, 1.0f);
      texel[1] = std::clamp(0.11f + 0.26f * v + 0.04f * tint, 0.0f, 1.0f);
      texel[2] = std::clamp(0.07f + 0.18f * v + 0.03f * tint, 0.0f, 1.0f);
      const float dx = strength * 0.5f * (h(x + 1, y) - h(x - 1, y));
      const float dy = strength * 0.5f * (h(x, y + 1) - h(x, y - 1));
      const float length = std::sqrt(dx * dx + dy * dy + 1.0f);
      texel[3] = -dx / length;
      texel[4] = -dy / length;
      texel[5] = 1.0f / length;
    }
  }
  return texture;
}

Texture loadSourceTexture(const std::string& colourPath, const std::string& normalPath) {
  if (colourPath == "procedural") {
    if (!normalPath.empty()) {
      fail("--normal: the procedural bark has its own normals; give --normal only with a photo");
    }
    return proceduralBark(1024, 1);
  }
  return loadPhotoTexture(colourPath, normalPath);
}

} // namespace sylva::texsynth
