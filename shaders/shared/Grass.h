// GPU layouts of the grass field (docs/grass.md), shared by C++ and GLSL.
#ifndef SYLVA_SHARED_GRASS_H
#define SYLVA_SHARED_GRASS_H

#include "Prelude.h"
#include "Wind.h"

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

#define SYLVA_GRASS_BINDING 7          // uniform block GrassUniforms
#define SYLVA_GRASS_PATCH_BINDING 8    // storage: GrassBlade[] (the patch)
#define SYLVA_GRASS_TYPE_BINDING 9     // storage: GrassTypeGpu[]
#define SYLVA_GRASS_VISIBLE_BINDING 14 // storage: ivec2 visible tiles[]
#define SYLVA_GRASS_INSTANCE_BINDING 11 // storage: uvec4 instances[] (three lists of `capacity`)
#define SYLVA_GRASS_COMMAND_BINDING 12 // storage: uint[28]: the draw commands, the dispatch, the statistics
#define SYLVA_GRASS_DISPATCH_OFFSET 16 // uint index of the blade pass's dispatch (x = visible tiles, y, z = 1)
#define SYLVA_GRASS_STATS_OFFSET 20    // uint index of the statistics (see GrassCounters)
#define SYLVA_GRASS_COMMAND_UINTS 28
#define SYLVA_GRASS_SIMULATED 0xffffffffu // instance.x of a simulated blade (drawn from the pool's knots)
#define SYLVA_GRASS_TUFT_SIMULATED 0xfffffffeu // instance.x of a tuft blade following a simulated blade
#define SYLVA_GRASS_POOL_MASK 0xffffffu     // instance.y of a simulated instance: pool blade (bits 0..23)
#define SYLVA_GRASS_CAPTURE_BINDING 13 // storage: captured vertices (expansion parity tests)
#define SYLVA_GRASS_TILE_GROUP 8       // tile pass: 8 x 8 tiles per work group
#define SYLVA_GRASS_BLADE_GROUP 64     // blade pass: one work group per visible tile
#define SYLVA_GRASS_KNOT_SLOTS 28      // 16 + 8 + 4 knots per type
#define SYLVA_GRASS_MAX_TILE_SAMPLES 256 // kMaxTileRangeSamples

/** One blade type: colour, stiffness and its knot lines at the three levels (blade space, metres). */
struct GrassTypeGpu {
  vec4 colour;                         // rgb: linear base colour; w: stiffness
  vec4 size;                           // x: length of the finest knot line (m); y, z, w: unused
  vec4 knots[SYLVA_GRASS_KNOT_SLOTS];  // xyz: knot; w: width. Level 0 at 0..15, level 1 at 16..23, 2 at 24..27
};
SYLVA_ASSERT_SIZE(GrassTypeGpu, 480);

/**
 * One drawn instance: root (world metres, as float bits) and packed bits: patch index (bits 0..21), level
 * (22..23), fade kind (24..25: 0 full, 1 fade out, 2 fade in), fade amount × 63 (26..31). A simulated blade
 * is (SYLVA_GRASS_SIMULATED, pool blade, packed bits, release ramp as float bits); a tuft blade of a
 * simulated tile (SYLVA_GRASS_TUFT_SIMULATED, its field blade's pool blade | near layer << 24, packed bits of
 * its own patch blade, release ramp): drawn at its own root with its field blade's simulated bend.
 */
#define SYLVA_GRASS_INDEX_MASK 0x3fffffu

/**
 * The command buffer as C++ reads it back: four DrawArraysIndirectCommands (count, instanceCount, first,
 * baseInstance): levels 0, 1, 2 and the simulated blades (16 knots, from the pool), the blade pass's dispatch,
 * then statistics.
 */
struct GrassCounters {
  uvec4 draws[4];
  uvec4 dispatch;   // x: visible tiles; y, z: 1
  uvec4 blades;     // x: distinct blades drawn; y: culled by the frustum; z: by distance; w: by orientation
  uvec4 overflow;   // x: instances dropped because a list was full; y: visible tiles dropped (list full);
                    // z: tiles found visible (before clamping to the list); w: tuft blades drawn (near layers)
};
SYLVA_ASSERT_SIZE(GrassCounters, 112);

/** What the culling passes are told each frame (std140). */
struct GrassUniforms {
  vec4 planes[6];   // frustum planes (xyz normal, w offset; inside: dot(n, p) + w ≥ 0), world metres
  vec4 eye;         // xyz: camera position (m); w: draw distance (m)
  vec4 lod;         // x, y: LOD distances (m); z: LOD cross-fade width (m); w: far fade width (m)
  vec4 orient;      // x: orientation-culling distance (m); y: its |cos| threshold; z: tallest blade (m);
                    // w: tile size (m)
  vec4 field;       // x, y: world (x, z) of tile (0, 0)'s corner; z, w: terrain extent x, z (m)
  ivec4 tiles;      // x, y: tiles along x, z; z: blades per tile; w: blades in the patch
  ivec4 grids;      // x, y: terrain samples along x, z; z, w: density samples along x, z
  vec4 spacing;     // x, y: terrain spacing x, z (m); z, w: density spacing x, z (m)
  uvec4 lists;      // x, y, z: capacity of the instance list of level 0, 1, 2 (stored one after another);
                    // w: capacity of the visible tile list
  uvec4 options;    // x: simulation pool slots (0: no simulation); y: debug view; z: blade types;
                    // w: blades per pool slot
  vec4 ground;      // rgb: the field's average colour (linear) for the ground tint; w: unused
  ivec4 window;     // tiles the tile pass looks at: x0, z0, count along x, count along z (tileWindow)
  vec4 heights;     // x, y: the terrain's whole height range (tiles over too many samples use it); z, w: unused
  vec4 near;        // x: near layers' reach (m, nearReach); y: near layers (nearLayerCount, ≥ 1); z: tuft
                    // radius (m); w: unused
  uvec4 simulated;  // x: capacity of the simulated blades' list (pool blades and the tufts that follow them);
                    // y, z, w: unused
  WindUniforms wind;
};
SYLVA_ASSERT_SIZE(GrassUniforms, 384);

SYLVA_GPU_END

#endif
