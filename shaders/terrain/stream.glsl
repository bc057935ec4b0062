// Streamed terrain tiles (sylva::terrain::StreamedTerrain, docs/terrain-data.md "Streaming"): bindings shared by
// the stream.* stages. Tiles are layers of one r32f texture array of (T + 1)² samples; every vertex sits exactly
// on a sample, so heights are texel fetches (no interpolation) and positions are integer sample indices
// relative to the render origin times the spacing: neighbours compute the same floats, and worlds of any size
// keep float precision near the camera.
#pragma once
#include "../shared/Terrain.h"
#include "../common/frame.glsl"

layout(std140, binding = SYLVA_STREAM_BINDING) uniform StreamBlock {
  StreamUniforms stream;
};

layout(std430, binding = SYLVA_STREAM_TILE_BINDING) readonly buffer StreamTiles {
  StreamTileGpu tiles[];
};

layout(binding = 0) uniform sampler2DArray tileHeights; // r32f metres, NaN absent

float tileHeight(int layer, ivec2 s) {
  int t = stream.shape.x;
  return texelFetch(tileHeights, ivec3(clamp(s, ivec2(0), ivec2(t)), layer), 0).r;
}

// Sample s of drawn tile `tile`, or of its same-level neighbour when s lies one step beyond its border (the
// tiles share their border samples, so -1 is the west tile's T - 1); NaN when that neighbour is not on the GPU.
float tileHeightAcross(int tile, ivec2 s) {
  int t = stream.shape.x;
  ivec4 flags = tiles[tile].flags;
  int layer = tiles[tile].key.w + 1;
  if (s.x < 0) {
    layer = flags.y & 0xFFFF;
    s.x += t;
  } else if (s.x > t) {
    layer = flags.y >> 16;
    s.x -= t;
  } else if (s.y < 0) {
    layer = flags.z & 0xFFFF;
    s.y += t;
  } else if (s.y > t) {
    layer = flags.z >> 16;
    s.y -= t;
  }
  return layer == 0 ? uintBitsToFloat(0x7FC00000u) : tileHeight(layer - 1, s);
}
