// Grass field bindings and the functions the culling passes and the blade shaders share (docs/grass.md).
// Every function here has a C++ twin in engine/grass (named in its comment) computing the same operations in
// the same order, so the CPU reference and the GPU keep the same blades.
#pragma once
#include "../shared/Grass.h"
#include "../common/hash.glsl"

layout(std140, binding = SYLVA_GRASS_BINDING) uniform GrassBlock {
  GrassUniforms grass;
};

layout(std430, binding = SYLVA_GRASS_PATCH_BINDING) readonly buffer GrassPatch {
  GrassBlade patchBlades[];
};

layout(std430, binding = SYLVA_GRASS_TYPE_BINDING) readonly buffer GrassTypes {
  GrassTypeGpu bladeTypes[];
};

layout(binding = 0) uniform sampler2D grassHeights; // r32f terrain heights (metres), absent samples filled
layout(binding = 1) uniform sampler2D grassValid;   // r8: > 0.5 where the terrain sample exists
layout(binding = 2) uniform sampler2D grassDensityMap; // r32f baked density [0, 1]

// First patch blade of tile (tx, tz) (tileStart).
uint grassTileStart(ivec2 tile, uint patchSize) {
  uint key = uint(tile.x) * 0x9e3779b1u ^ lowbias32(uint(tile.y) ^ 0x85ebca6bu);
  return lowbias32(key) % patchSize;
}

// Terrain height at world xz as the terrain's tessellation shader samples it, NaN-free: `ok` is false when
// one of the four samples is absent (rootHeight).
float grassTerrainHeight(vec2 xz, out bool ok) {
  ivec2 size = grass.grids.xy;
  float gx = clamp(xz.x / grass.spacing.x, 0.0, float(size.x - 1));
  float gz = clamp(xz.y / grass.spacing.y, 0.0, float(size.y - 1));
  ivec2 i0 = min(ivec2(floor(vec2(gx, gz))), size - 2);
  ok = texelFetch(grassValid, i0, 0).r > 0.5 && texelFetch(grassValid, i0 + ivec2(1, 0), 0).r > 0.5 &&
       texelFetch(grassValid, i0 + ivec2(0, 1), 0).r > 0.5 && texelFetch(grassValid, i0 + ivec2(1, 1), 0).r > 0.5;
  float fx = gx - float(i0.x);
  float fz = gz - float(i0.y);
  float top = texelFetch(grassHeights, i0, 0).r * (1.0 - fx) + texelFetch(grassHeights, i0 + ivec2(1, 0), 0).r * fx;
  float bottom =
      texelFetch(grassHeights, i0 + ivec2(0, 1), 0).r * (1.0 - fx) + texelFetch(grassHeights, i0 + ivec2(1, 1), 0).r * fx;
  return top * (1.0 - fz) + bottom * fz;
}

// Baked density at world xz (DensityGrid::at).
float grassDensity(vec2 xz) {
  ivec2 size = grass.grids.zw;
  float gx = clamp(xz.x / grass.spacing.z, 0.0, float(size.x - 1));
  float gz = clamp(xz.y / grass.spacing.w, 0.0, float(size.y - 1));
  ivec2 i0 = min(ivec2(floor(vec2(gx, gz))), size - 2);
  float fx = gx - float(i0.x);
  float fz = gz - float(i0.y);
  float top = texelFetch(grassDensityMap, i0, 0).r * (1.0 - fx) + texelFetch(grassDensityMap, i0 + ivec2(1, 0), 0).r * fx;
  float bottom = texelFetch(grassDensityMap, i0 + ivec2(0, 1), 0).r * (1.0 - fx) +
                 texelFetch(grassDensityMap, i0 + ivec2(1, 1), 0).r * fx;
  return top * (1.0 - fz) + bottom * fz;
}

int grassLodKnots(int lod) { return lod == 0 ? SYLVA_GRASS_LOD0_KNOTS : lod == 1 ? SYLVA_GRASS_LOD1_KNOTS : SYLVA_GRASS_LOD2_KNOTS; }
int grassLodFirst(int lod) { return lod == 0 ? 0 : lod == 1 ? SYLVA_GRASS_LOD0_KNOTS : SYLVA_GRASS_LOD0_KNOTS + SYLVA_GRASS_LOD1_KNOTS; }

uint grassPackInfo(uint patchIndex, int lod, int fade, float amount) {
  uint q = uint(clamp(amount, 0.0, 1.0) * 63.0 + 0.5);
  return (patchIndex & SYLVA_GRASS_INDEX_MASK) | (uint(lod) << 22) | (uint(fade) << 24) | (q << 26);
}

// Rotates v about the unit axis by angle (Rodrigues; rotate in Expand.cpp).
vec3 grassRotate(vec3 v, vec3 axis, float angle) {
  float c = cos(angle);
  float s = sin(angle);
  return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1.0 - c));
}

// The blade's finest knot line, bent downwind: bladeCentreLine (Expand.cpp) at level 0, the rest pose of a
// simulated blade.
void grassCentreLine(uint type, GrassBlade b, vec3 root, vec2 wind, out vec3 centre[SYLVA_GRASS_LOD0_KNOTS]) {
  float scale = b.placement.w;
  float cy = cos(b.placement.z);
  float sy = sin(b.placement.z);
  float speed = length(wind);
  float theta = min(1.3, 0.12 * abs(speed) / max(bladeTypes[type].colour.w, 0.05));
  vec3 downwind = speed > 1e-6 ? vec3(wind.x, 0.0, wind.y) / speed : vec3(0.0);
  vec3 axis = speed > 1e-6 ? normalize(cross(vec3(0.0, 1.0, 0.0), downwind)) : vec3(1.0, 0.0, 0.0);
  float total = 0.0;
  for (int m = 1; m < SYLVA_GRASS_LOD0_KNOTS; ++m) {
    total += length(bladeTypes[type].knots[m].xyz - bladeTypes[type].knots[m - 1].xyz);
  }
  total = max(total, 1e-9);
  centre[0] = root;
  float along = 0.0;
  for (int m = 1; m < SYLVA_GRASS_LOD0_KNOTS; ++m) {
    vec3 d = bladeTypes[type].knots[m].xyz - bladeTypes[type].knots[m - 1].xyz;
    vec3 segment = vec3(cy * d.x + sy * d.z, d.y, -sy * d.x + cy * d.z) * scale;
    along += length(d);
    float u = along / total;
    centre[m] = centre[m - 1] + grassRotate(segment, axis, theta * u * u);
  }
}
