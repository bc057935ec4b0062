// Shared declarations of the foliage passes (docs/trees.md "Foliage"; sylva/trees/Foliage.hpp holds the CPU
// twins of the depth code and the fragment rule).
#pragma once
#include "../shared/Trees.h"

layout(std140, binding = SYLVA_TREE_FOLIAGE_UNIFORM_BINDING) uniform FoliageBlock {
  FoliageUniforms foliage;
};

/** The alpha of a covered texel at depth t across the sphere (encodeFoliageDepth): (1 + ⌊254 t + ½⌋) / 255
 * (floor, not round(): GLSL leaves the direction of round(x.5) to the implementation). */
float encodeFoliageDepth(float t) {
  return (1.0 + floor(254.0 * clamp(t, 0.0, 1.0) + 0.5)) / 255.0;
}

/** sRGB → linear for colours the bake stored sRGB-encoded. */
vec3 fromSrgb(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c));
}
