#version 450
// Grass culling, pass 1: one invocation per tile. Tiles whose box (terrain height range plus the tallest
// blade) meets the frustum and the draw distance go on the visible list, whose length is the blade pass's
// dispatch size (cullField's tile loop in engine/grass/src/Cull.cpp).
#include "grass.glsl"

layout(local_size_x = SYLVA_GRASS_TILE_GROUP, local_size_y = SYLVA_GRASS_TILE_GROUP) in;

layout(std430, binding = SYLVA_GRASS_TILE_BINDING) readonly buffer TileRanges {
  vec2 tileRanges[];
};
layout(std430, binding = SYLVA_GRASS_VISIBLE_BINDING) writeonly buffer VisibleTiles {
  ivec2 visibleTiles[];
};
layout(std430, binding = SYLVA_GRASS_COMMAND_BINDING) buffer Commands {
  uint commands[24];
};

void main() {
  ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
  if (tile.x >= grass.tiles.x || tile.y >= grass.tiles.y) {
    return;
  }
  vec2 range = tileRanges[tile.y * grass.tiles.x + tile.x];
  if (!(range.x <= range.y)) {
    return;
  }
  vec2 lo = grass.field.xy + vec2(tile) * grass.orient.w;
  vec2 hi = lo + vec2(grass.orient.w);
  vec3 bmin = vec3(lo.x, range.x, lo.y);
  vec3 bmax = vec3(hi.x, range.y + grass.orient.z, hi.y);
  // Frustum::test: outside when the box lies wholly behind one plane.
  vec3 c = (bmin + bmax) * 0.5;
  vec3 e = (bmax - bmin) * 0.5;
  for (int i = 0; i < 6; ++i) {
    vec4 p = grass.planes[i];
    if (dot(p.xyz, c) + p.w < -dot(abs(p.xyz), e)) {
      return;
    }
  }
  vec3 nearest = clamp(grass.eye.xyz, bmin, bmax);
  if (length(nearest - grass.eye.xyz) > grass.eye.w) {
    return;
  }
  uint slot = atomicAdd(commands[SYLVA_GRASS_STATS_OFFSET + 6], 1u);
  if (slot < grass.lists.w) {
    visibleTiles[slot] = tile;
  }
}
