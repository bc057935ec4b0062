#version 450 core
// Sobel normal map; the CPU reference is sylva::terrain::sobelNormalMap (same formula, same border and absent-
// sample rules; see TerrainMaps.hpp):
//   gx = [h(1,-1) + 2h(1,0) + h(1,1) - h(-1,-1) - 2h(-1,0) - h(-1,1)] / (8 spacingX), gz likewise along z,
//   n = normalize(-gx, 1, -gz).
#include "maps.glsl"

// Stored as (x, z) in rg16_snorm: y = sqrt(1 - x² - z²) is positive for every height-field normal.
layout(rg16_snorm, binding = 0) uniform writeonly image2D normalsOut;

float neighbour(ivec2 centre, ivec2 offset, float centreHeight) {
  ivec2 p = centre + offset;
  if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, maps.field.xy))) {
    if (maps.field.w == 1) {
      return maps.spacing.z;
    }
    p = clamp(p, ivec2(0), maps.field.xy - 1);
  }
  return sampleValid(p) ? texelFetch(heightMap, p, 0).r : centreHeight;
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, maps.field.xy))) {
    return;
  }
  if (!sampleValid(p)) {
    imageStore(normalsOut, p, vec4(0.0));
    return;
  }
  float c = texelFetch(heightMap, p, 0).r;
  float hmm = neighbour(p, ivec2(-1, -1), c);
  float hm0 = neighbour(p, ivec2(-1, 0), c);
  float hmp = neighbour(p, ivec2(-1, 1), c);
  float h0m = neighbour(p, ivec2(0, -1), c);
  float h0p = neighbour(p, ivec2(0, 1), c);
  float hpm = neighbour(p, ivec2(1, -1), c);
  float hp0 = neighbour(p, ivec2(1, 0), c);
  float hpp = neighbour(p, ivec2(1, 1), c);
  float gx = (hpm + 2.0 * hp0 + hpp - hmm - 2.0 * hm0 - hmp) / (8.0 * maps.spacing.x);
  float gz = (hmp + 2.0 * h0p + hpp - hmm - 2.0 * h0m - hpm) / (8.0 * maps.spacing.y);
  vec3 n = normalize(vec3(-gx, 1.0, -gz));
  imageStore(normalsOut, p, vec4(n.x, n.z, 0.0, 0.0));
}
