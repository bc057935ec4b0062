#pragma once
// Far-field trees (docs/trees.md "Far field"): beyond a distance trees become impostors; in a band they
// cross-fade by a screen-door dissolve with complementary masks. These are the CPU twins of
// shaders/trees/fade.glsl.

#include <sylva/core/Random.hpp>

#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cstdint>

namespace sylva::trees {

/** 0 nearer than range.x (pieces only), 1 beyond range.y (impostor only), linear between, metres; range.y <=
 * range.x: no far field (always 0). */
inline float farBlend(float distance, glm::vec2 range) {
  if (range.y <= range.x) {
    return 0.0f;
  }
  return std::clamp((distance - range.x) / (range.y - range.x), 0.0f, 1.0f);
}

/** The dissolve threshold of pixel (x, y) for tree `tree`, in (0, 1): a 4 × 4 Bayer matrix shifted per tree.
 */
inline float fadeThreshold(glm::uvec2 pixel, std::uint32_t tree) {
  constexpr std::array<std::uint32_t, 16> kBayer{0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
  const std::uint32_t h = lowbias32(tree * 0x9e3779b9u + 0x632be5abu);
  const glm::uvec2 p = (pixel + glm::uvec2(h & 3u, (h >> 2) & 3u)) & 3u;
  return (static_cast<float>(kBayer[p.y * 4u + p.x]) + 0.5f) / 16.0f;
}

/** Whether a tree's pieces cover the pixel at `blend`; impostorKeeps() is its complement. */
inline bool piecesKeep(float blend, glm::uvec2 pixel, std::uint32_t tree) {
  return blend < fadeThreshold(pixel, tree);
}
inline bool impostorKeeps(float blend, glm::uvec2 pixel, std::uint32_t tree) {
  return blend >= fadeThreshold(pixel, tree);
}

} // namespace sylva::trees
