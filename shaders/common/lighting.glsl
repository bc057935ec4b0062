// Simple outdoor lighting: Lambert sun (shadowed, shadows.glsl) + hemispheric ambient + distance haze (atmosphere.glsl). All inputs linear.
#pragma once
#include "atmosphere.glsl"
#include "frame.glsl"
#include "shadows.glsl"

vec3 shadeOutdoor(vec3 albedo, vec3 normal, vec3 worldPos) {
  vec3 sun = normalize(frame.sunDirection.xyz);
  float diffuse = max(dot(normal, sun), 0.0) * frame.sunDirection.w * sunVisibility(worldPos, normal);
  float sky = 0.5 + 0.5 * normal.y;
  vec3 lit = albedo * (diffuse * vec3(1.0, 0.96, 0.88) + mix(vec3(0.18, 0.16, 0.14), vec3(0.32, 0.38, 0.48), sky));
  return applyAtmosphere(lit, worldPos);
}

// Linear → sRGB for 8-bit output without an sRGB framebuffer.
vec3 toSrgb(vec3 linear) {
  return mix(12.92 * linear, 1.055 * pow(linear, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, linear));
}
