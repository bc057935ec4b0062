// Terrain GPU layouts, shared by C++ (sylva::terrain::TerrainRenderer) and shaders/terrain/*.
#ifndef SYLVA_SHARED_TERRAIN_H
#define SYLVA_SHARED_TERRAIN_H

#include "Prelude.h"

SYLVA_GPU_BEGIN

#define SYLVA_TERRAIN_BINDING 3      // uniform block TerrainUniforms
#define SYLVA_TERRAIN_NODE_BINDING 4 // shader storage block of TerrainNode
#define SYLVA_TERRAIN_LAYER_BINDING 5 // uniform block of SplatLayerGpu rules
#define SYLVA_TERRAIN_GROUP_SIZE 16
#define SYLVA_TERRAIN_MAX_LAYERS 64

// One patch to draw. Surface patches have grid.w = -1; skirt patches (coverage pass only) hang below edge grid.w.
struct TerrainNode {
  vec4 rect;      // x, z: min corner (world metres); y: edge length S (metres); w: minY (metres)
  vec4 tessOuter; // gl_TessLevelOuter[0..3]: u=0 (west, x-min), v=0 (north, z-min), u=1 (east), v=1 (south)
  vec4 tessInner; // x: inner level (both directions); y: maxY (metres); z: edge flags (bit e: edge e doubled); w: 0
  ivec4 grid;     // x, z: node index in its depth's grid; y: depth; w: -1 surface, 0..3 skirt under that edge
};
SYLVA_ASSERT_SIZE(TerrainNode, 64);

struct TerrainUniforms {
  ivec4 field;   // x, y: samples along x and z; z: splat pages; w: layer count
  vec4 spacing;  // x, z spacing (metres per sample); z: texture tiling (metres per repeat); w: skirt depth (m)
  vec4 extent;   // x, z extent (metres); z: debug view (0 shaded, 1 LOD colours, 2 normals, 3 splat); w: unused
  vec4 heightRange; // x: min height, y: max height (metres, valid samples); z, w: unused
};
SYLVA_ASSERT_SIZE(TerrainUniforms, 64);

// One splat rule (sylva::terrain::SplatLayer) in the rules block.
struct SplatRuleGpu {
  vec4 height; // minHeight, maxHeight, heightBlend (metres), unused
  vec4 slope;  // minSlope, maxSlope, slopeBlend (degrees), unused
};
SYLVA_ASSERT_SIZE(SplatRuleGpu, 32);

// Parameters of the map compute passes (uniform block at SYLVA_TERRAIN_BINDING while they run).
struct TerrainMapsUniforms {
  ivec4 field;   // x, y: samples; z: layer count; w: border mode (0 clamp, 1 constant)
  vec4 spacing;  // x, z spacing (metres per sample); z: constant border height (metres); w: unused
};
SYLVA_ASSERT_SIZE(TerrainMapsUniforms, 32);

SYLVA_GPU_END

#endif
