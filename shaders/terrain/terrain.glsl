// Terrain bindings and the height function shared by every terrain stage. Heights must be evaluated exactly as
// the CPU query does (sylva::terrain::heightAt, bilinear): sample (i, j) sits at world (i·spacingX, j·spacingZ),
// i.e. texel centre (i + 0.5) / width, and interpolation is done here in full float precision from texelFetch,
// not by the texture unit (whose filtering weights have only 8 fractional bits).
#pragma once
#include "../shared/Terrain.h"
#include "../common/frame.glsl"

layout(std140, binding = SYLVA_TERRAIN_BINDING) uniform TerrainBlock {
  TerrainUniforms terrain;
};

layout(std430, binding = SYLVA_TERRAIN_NODE_BINDING) readonly buffer TerrainNodes {
  TerrainNode nodes[];
};

layout(binding = 0) uniform sampler2D heightMap;  // r32f metres, absent samples filled from valid neighbours
layout(binding = 1) uniform sampler2D validMask;  // r8: 1 where the source sample exists
layout(binding = 2) uniform sampler2D normalMap;  // rg16_snorm world normal (x, z); y = sqrt(1 - x² - z²)
layout(binding = 3) uniform sampler2DArray splatMap; // page k holds layers 4k..4k+3
layout(binding = 4) uniform sampler2DArray layerAlbedo; // one tileable albedo texture per splat layer

float heightSample(ivec2 p) {
  p = clamp(p, ivec2(0), terrain.field.xy - 1);
  return texelFetch(heightMap, p, 0).r;
}

// Bilinear height in metres at world xz (clamped to the field's edge samples).
float terrainHeight(vec2 xz) {
  vec2 g = clamp(xz / terrain.spacing.xy, vec2(0.0), vec2(terrain.field.xy - 1));
  ivec2 i0 = min(ivec2(floor(g)), terrain.field.xy - 2);
  vec2 f = g - vec2(i0);
  float h00 = heightSample(i0);
  float h10 = heightSample(i0 + ivec2(1, 0));
  float h01 = heightSample(i0 + ivec2(0, 1));
  float h11 = heightSample(i0 + ivec2(1, 1));
  return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

// Texture coordinate of world xz for the sampled maps (normals, splat): texel centres at sample positions.
vec2 terrainUv(vec2 xz) {
  return (xz / terrain.spacing.xy + 0.5) / vec2(terrain.field.xy);
}

// Geomorphing (TerrainDrawOptions::geomorph; CPU reference: sylva::terrain::morphedHeight, Geomorph.cpp).
// uMorphCamera: xyz = camera the selection was made for (world metres), w = 1 when on.
// uMorphLod: x = root size (m), y = max depth, z = base tessellation level T, w = LOD distance factor F.
uniform vec4 uMorphCamera;
uniform vec4 uMorphLod;

// The surface a depth-`depth` patch represents: bilinear over its vertex lattice, spacing root / (2^depth T).
float latticeHeight(vec2 xz, int depth) {
  if (depth >= int(uMorphLod.y)) {
    return terrainHeight(xz);
  }
  float step = uMorphLod.x / (exp2(float(depth)) * uMorphLod.z);
  vec2 q = xz / step;
  vec2 c = floor(q);
  vec2 f = q - c;
  vec2 p0 = c * step;
  vec2 p1 = (c + 1.0) * step;
  float h00 = terrainHeight(p0);
  float h10 = terrainHeight(vec2(p1.x, p0.y));
  float h01 = terrainHeight(vec2(p0.x, p1.y));
  float h11 = terrainHeight(p1);
  float a = h00 + (h10 - h00) * f.x;
  float b = h01 + (h11 - h01) * f.x;
  return a + (b - a) * f.y;
}

// Height drawn at world xz: a function of xz and the camera only, so both patches sharing a vertex agree.
// λ = log2(F·root / r) bounds the depth of any leaf at distance r from below; the height blends the surfaces of
// depths ⌈λ⌉ and ⌈λ⌉ − 1, both representable by such a leaf, continuously in r (docs/terrain-lod.md).
float terrainMorphedHeight(vec2 xz) {
  float h = terrainHeight(xz);
  if (uMorphCamera.w == 0.0) {
    return h;
  }
  float r = max(length(uMorphCamera.xyz - vec3(xz.x, h, xz.y)), 1e-3);
  float lambda = log2(uMorphLod.w * uMorphLod.x / r);
  int n = clamp(int(ceil(min(lambda, 64.0))), 0, int(uMorphLod.y));
  float t = n == 0 ? 0.0 : clamp(float(n) - lambda, 0.0, 1.0);
  float fine = latticeHeight(xz, n);
  if (t == 0.0) {
    return fine;
  }
  float coarse = latticeHeight(xz, n - 1);
  return fine + (coarse - fine) * t;
}
