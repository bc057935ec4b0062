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
