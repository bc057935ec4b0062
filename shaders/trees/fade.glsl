// The cross-fade between trees drawn as pieces and far-field impostors (docs/trees.md "Far field"): a screen-door
// dissolve with complementary masks, so in the fade band every pixel of a tree is drawn by exactly one of the two
// passes and nothing pops or doubles. CPU twins: farBlend and fadeThreshold in sylva/trees/FarField.hpp.
#pragma once
#include "../common/hash.glsl"

/** 0 nearer than range.x (pieces only), 1 beyond range.y (impostor only), linear between; range.y <= range.x:
 * no far field (always 0). */
float farBlend(float distance, vec2 range) {
  if (range.y <= range.x) {
    return 0.0;
  }
  return clamp((distance - range.x) / (range.y - range.x), 0.0, 1.0);
}

/** The dissolve threshold of a pixel for one tree, in (0, 1): a 4 x 4 Bayer matrix shifted per tree. */
float fadeThreshold(uvec2 pixel, uint tree) {
  const uint kBayer[16] = uint[16](0u, 8u, 2u, 10u, 12u, 4u, 14u, 6u, 3u, 11u, 1u, 9u, 15u, 7u, 13u, 5u);
  uint h = lowbias32(tree * 0x9e3779b9u + 0x632be5abu);
  uvec2 p = (pixel + uvec2(h & 3u, (h >> 2) & 3u)) & 3u;
  return (float(kBayer[p.y * 4u + p.x]) + 0.5) / 16.0;
}

/** Whether the pieces of a tree cover this pixel at blend `blend` (exactly one of this and the next holds). */
bool piecesKeep(float blend, uvec2 pixel, uint tree) { return blend < fadeThreshold(pixel, tree); }
/** Whether the impostor of a tree covers this pixel at blend `blend`. */
bool impostorKeeps(float blend, uvec2 pixel, uint tree) { return blend >= fadeThreshold(pixel, tree); }
