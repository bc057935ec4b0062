#version 450
// Grass culling, pass 1: one invocation per tile of the window within the draw distance. Tiles whose box
// (terrain height range plus the tallest blade) meets the frustum and the draw distance go on the visible
// list, whose length is the blade pass's dispatch size (cullField's tile loop in engine/grass/src/Cull.cpp).
// Nothing is stored per tile: the height range is read from the terrain here (tileHeightRange).
#include "grass.glsl"

layout(local_size_x = SYLVA_GRASS_TILE_GROUP, local_size_y = SYLVA_GRASS_TILE_GROUP) in;

layout(std430, binding = SYLVA_GRASS_VISIBLE_BINDING) writeonly buffer VisibleTiles {
  ivec2 visibleTiles[];
};
layout(std430, binding = SYLVA_GRASS_COMMAND_BINDING) buffer Commands {
  uint commands[SYLVA_GRASS_COMMAND_UINTS];
};

// tileHeightRange (Field.cpp).
vec2 tileRange(vec2 lo, vec2 hi) {
  ivec2 size = grass.grids.xy;
  int i0 = clamp(int(floor(lo.x / grass.spacing.x)), 0, size.x - 1);
  int i1 = clamp(int(ceil(hi.x / grass.spacing.x)), 0, size.x - 1);
  int j0 = clamp(int(floor(lo.y / grass.spacing.y)), 0, size.y - 1);
  int j1 = clamp(int(ceil(hi.y / grass.spacing.y)), 0, size.y - 1);
  if ((i1 - i0 + 1) * (j1 - j0 + 1) > SYLVA_GRASS_MAX_TILE_SAMPLES) {
    return grass.heights.xy;
  }
  vec2 range = vec2(1e30, -1e30);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      if (texelFetch(grassValid, ivec2(i, j), 0).r > 0.5) {
        float h = texelFetch(grassHeights, ivec2(i, j), 0).r;
        range = vec2(min(range.x, h), max(range.y, h));
      }
    }
  }
  return range;
}

void main() {
  if (gl_GlobalInvocationID.x >= uint(grass.window.z) || gl_GlobalInvocationID.y >= uint(grass.window.w)) {
    return;
  }
  ivec2 tile = grass.window.xy + ivec2(gl_GlobalInvocationID.xy);
  vec2 lo = grass.field.xy + vec2(tile) * grass.orient.w;
  vec2 hi = lo + vec2(grass.orient.w);
  vec2 range = tileRange(lo, hi);
  if (!(range.x <= range.y)) {
    return;
  }
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
