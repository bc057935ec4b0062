// Terrain GPU layouts, shared by C++ (sylva::terrain::TerrainRenderer) and shaders/terrain/*.
#ifndef SYLVA_SHARED_TERRAIN_H
#define SYLVA_SHARED_TERRAIN_H

#include "Prelude.h"

SYLVA_GPU_BEGIN

#define SYLVA_TERRAIN_BINDING 3       // uniform block TerrainUniforms
#define SYLVA_TERRAIN_NODE_BINDING 4  // shader storage block of TerrainNode
#define SYLVA_TERRAIN_LAYER_BINDING 5 // uniform block of SplatLayerGpu rules
#define SYLVA_TERRAIN_GROUP_SIZE 16
#define SYLVA_TERRAIN_MAX_LAYERS 64

// One patch to draw. Surface patches have grid.w = -1; skirt patches (coverage pass only) hang below edge
// grid.w.
struct TerrainNode {
  vec4 rect;      // x, z: min corner (world metres); y: edge length S (metres); w: minY (metres)
  vec4 tessOuter; // gl_TessLevelOuter[0..3]: u=0 (west, x-min), v=0 (north, z-min), u=1 (east), v=1 (south)
  vec4 tessInner; // x: inner level (both directions); y: maxY (metres); z: edge flags (bit e: edge e
                  // doubled); w: 0
  ivec4 grid;     // x, z: node index in its depth's grid; y: depth; w: -1 surface, 0..3 skirt under that edge
};
SYLVA_ASSERT_SIZE(TerrainNode, 64);

struct TerrainUniforms {
  ivec4 field;  // x, y: samples along x and z; z: splat pages; w: layer count
  vec4 spacing; // x, z spacing (metres per sample); z: texture tiling (metres per repeat); w: skirt depth (m)
  vec4 extent; // x, z extent (metres); z: debug view (0 shaded, 1 LOD colours, 2 normals, 3 splat); w: unused
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
  ivec4 field;  // x, y: samples; z: layer count; w: border mode (0 clamp, 1 constant)
  vec4 spacing; // x, z spacing (metres per sample); z: constant border height (metres); w: unused
};
SYLVA_ASSERT_SIZE(TerrainMapsUniforms, 32);

// GPU quadtree selection (sylva::terrain::GpuQuadtreeSelection, shaders/terrain/select.comp).
#define SYLVA_TERRAIN_SELECT_NODE_BINDING 6     // std430: TerrainSelectNode per node, every depth
#define SYLVA_TERRAIN_SELECT_PARAMS_BINDING 7   // std430: TerrainSelectParams
#define SYLVA_TERRAIN_SELECT_LIST_BINDING 8     // std430: two candidate lists (uvec2 grid x, z), ping-pong
#define SYLVA_TERRAIN_SELECT_SPLIT_BINDING 9    // std430: split bits, every depth
#define SYLVA_TERRAIN_SELECT_COUNTER_BINDING 10 // std430: TerrainSelectCounters (the indirect draw first)
#define SYLVA_TERRAIN_SELECT_GROUP_SIZE 256
#define SYLVA_TERRAIN_SELECT_MAX_DEPTH 27 // depths 0..27 fit the offset tables (7 uvec4)

// One quadtree node's data: own height range, the LOD box's (3x3-dilated) range, the LOD error (metres).
struct TerrainSelectNode {
  vec4 range; // x, y: min, max height (metres; min > max: absent); z, w: LOD box min, max
  vec4 error; // x: LOD error (saturated, dilated when the selection is restricted), metres; y, z, w: unused
};
SYLVA_ASSERT_SIZE(TerrainSelectNode, 32);

// The view and the policy of one selection (the CPU Quadtree's config and select() arguments).
struct TerrainSelectParams {
  vec4 camera;    // xyz: camera (world metres); w: root size (metres)
  vec4 lod;       // x: distance factor; y: error scale K/tau (0: distance LOD); z: distance floor; w: tess T
  ivec4 grid;     // x, y: roots along x, z; z: max depth; w: deepest depth that may split (max depth or 0)
  ivec4 flags;    // x: frustum culling; y: stitch edges (crack method != none); z: list capacity; w: unused
  vec4 planes[6]; // frustum planes (n.xyz, d), inward, normalised (sylva::Frustum)
  uvec4 offsets[7];    // first node of depth d: offsets[d / 4][d % 4]
  uvec4 bitOffsets[7]; // first split bit of depth d
};
SYLVA_ASSERT_SIZE(TerrainSelectParams, 384);

// Counters: the DrawArraysIndirect command of the selected patches first (count 4, one instance per leaf).
struct TerrainSelectCounters {
  uvec4 draw;  // x: 4 control points; y: leaves (instances); z: first; w: base instance
  uvec4 lists; // x, y: candidates in list 0 and 1; z: overflow (candidates dropped, list full); w: unused
};
SYLVA_ASSERT_SIZE(TerrainSelectCounters, 32);

// Streamed terrain tiles (sylva::terrain::StreamedTerrain, shaders/terrain/stream.*).
#define SYLVA_STREAM_TILE_BINDING 11 // std430: StreamTileGpu per drawn tile
#define SYLVA_STREAM_BINDING 12      // uniform block StreamUniforms

// One drawn tile: which samples it holds and where its texture-array layer is.
struct StreamTileGpu {
  ivec4 key; // x: tile column, y: tile row, z: level, w: texture-array layer
  // x: coarser edges (bit e: PatchEdge e keeps every second vertex); y: layer + 1 of the same-level tile to
  // the west (bits 0-15) and east (16-31), 0 when it is not on the GPU; z: the same for north (−y) and south
  // (+y), so normals at the tile's border take central differences across it; w: unused
  ivec4 flags;
};
SYLVA_ASSERT_SIZE(StreamTileGpu, 32);

struct StreamUniforms {
  ivec4 shape; // x: tile size T, y: patch level P (T / P patches per tile edge), z: patches per tile edge, w:
               // view
  ivec4 origin; // x, y: level-0 sample index of the render origin (x, z); z, w: unused
  vec4 spacing; // x, z spacing (metres per level-0 sample); z, w: unused
};
SYLVA_ASSERT_SIZE(StreamUniforms, 48);

SYLVA_GPU_END

#endif
