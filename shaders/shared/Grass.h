// GPU layouts of the grass field (docs/grass.md), shared by C++ and GLSL.
#ifndef SYLVA_SHARED_GRASS_H
#define SYLVA_SHARED_GRASS_H

#include "Prelude.h"

SYLVA_GPU_BEGIN

/** Knot counts of the three blade levels of detail. */
#define SYLVA_GRASS_LOD0_KNOTS 16
#define SYLVA_GRASS_LOD1_KNOTS 8
#define SYLVA_GRASS_LOD2_KNOTS 4

/** One blade of the patch: where it stands in its tile and what it is. */
struct GrassBlade {
  vec4 placement; // x, y: root in tile space (metres from the tile's corner, world x and z); z: rotation about
                  // the vertical, radians; w: scale (multiplies the blade type's length and width)
  uvec4 info;     // x: blade type index; y: per-blade colour/variation seed; z, w: unused
};
SYLVA_ASSERT_SIZE(GrassBlade, 32);

SYLVA_GPU_END

#endif
