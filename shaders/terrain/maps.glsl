// Bindings of the terrain map compute passes (normals.comp, splat.comp).
#pragma once
#include "../shared/Terrain.h"

layout(local_size_x = SYLVA_TERRAIN_GROUP_SIZE, local_size_y = SYLVA_TERRAIN_GROUP_SIZE) in;

layout(std140, binding = SYLVA_TERRAIN_BINDING) uniform MapsBlock {
  TerrainMapsUniforms maps;
};

layout(binding = 0) uniform sampler2D heightMap; // r32f metres (absent samples hold any finite value)
layout(binding = 1) uniform sampler2D validMask; // r8: 1 where the sample exists

bool sampleValid(ivec2 p) {
  return texelFetch(validMask, p, 0).r > 0.5;
}
