#version 450 core
// Rule-based splat map; the CPU reference is sylva::terrain::splatMap (TerrainMaps.hpp). Each layer's raw weight
// is ramp(height) * ramp(slope); weights are normalised to sum 1, the first layer taking weight 1 where no rule
// applies, and written 4 layers per page of an rgba8 array (page k, channel c = layer 4k + c).
#include "maps.glsl"

layout(std140, binding = SYLVA_TERRAIN_LAYER_BINDING) uniform RulesBlock {
  SplatRuleGpu rules[SYLVA_TERRAIN_MAX_LAYERS];
};
layout(binding = 2) uniform sampler2D normalMap; // from normals.comp

vec3 normalAt(ivec2 p) {
  vec2 xz = texelFetch(normalMap, p, 0).xy; // rg16_snorm (x, z)
  return vec3(xz.x, sqrt(max(0.0, 1.0 - dot(xz, xz))), xz.y);
}
layout(rgba8, binding = 0) uniform writeonly image2DArray splatOut;

float ramp(float v, float lo, float hi, float blend) {
  if (blend > 0.0) {
    return clamp((v - lo) / blend + 0.5, 0.0, 1.0) * clamp((hi - v) / blend + 0.5, 0.0, 1.0);
  }
  return (lo <= v && v <= hi) ? 1.0 : 0.0;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, maps.field.xy))) {
    return;
  }
  int layers = maps.field.z;
  int pages = (layers + 3) / 4;
  if (!sampleValid(p)) {
    for (int page = 0; page < pages; ++page) {
      imageStore(splatOut, ivec3(p, page), vec4(0.0));
    }
    return;
  }
  float height = texelFetch(heightMap, p, 0).r;
  float ny = clamp(normalAt(p).y, -1.0, 1.0);
  float slope = degrees(acos(ny));
  float verticalScale = maps.spacing.w;
  if (verticalScale != 1.0) {
    // Exaggerated heights, rules in true metres and degrees (see splatMap).
    height = height / verticalScale;
    slope = degrees(atan(sqrt(max(0.0, 1.0 - ny * ny)) / (ny * verticalScale)));
  }
  float total = 0.0;
  for (int l = 0; l < layers; ++l) {
    total += ramp(height, rules[l].height.x, rules[l].height.y, rules[l].height.z) *
             ramp(slope, rules[l].slope.x, rules[l].slope.y, rules[l].slope.z);
  }
  for (int page = 0; page < pages; ++page) {
    vec4 w = vec4(0.0);
    for (int c = 0; c < 4; ++c) {
      int l = page * 4 + c;
      if (l >= layers) {
        break;
      }
      float raw = ramp(height, rules[l].height.x, rules[l].height.y, rules[l].height.z) *
                  ramp(slope, rules[l].slope.x, rules[l].slope.y, rules[l].slope.z);
      w[c] = total > 0.0 ? raw / total : (l == 0 ? 1.0 : 0.0);
    }
    imageStore(splatOut, ivec3(p, page), w);
  }
}
