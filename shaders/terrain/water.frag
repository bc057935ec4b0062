#version 450 core
// Still water at sea level: colour and opacity from the true water depth under each fragment (terrain heights
// divided by the vertical exaggeration), Schlick Fresnel towards the sky colour (the analytic sky in mode 1),
// a sun glint, and the same distance haze as the terrain. Drawn after the terrain with alpha blending and no
// depth writes; fragments over absent samples (nodata) or dry ground are discarded.
#include "terrain.glsl"
#include "../common/lighting.glsl"

uniform float uWaterLevel;     // world metres (exaggerated)
uniform float uVerticalScale;  // vertical exaggeration of the drawn terrain
in vec3 vWorldPos;
flat in int vWall;
layout(location = 0) out vec4 outColor;

const float kDepthScale = 12.0; // true metres over which shallow water turns deep

void main() {
  vec2 xz = vWorldPos.xz;
  ivec2 nearest = clamp(ivec2(floor(xz / terrain.spacing.xy + 0.5)), ivec2(0), terrain.field.xy - 1);
  if (texelFetch(validMask, nearest, 0).r < 0.5) {
    discard;
  }
  float ground = terrainHeight(xz);
  float depth = (uWaterLevel - ground) / uVerticalScale;
  if (depth <= 0.0 || (vWall != 0 && vWorldPos.y < ground)) {
    discard; // dry ground, or a wall fragment inside the ground
  }
  float deep = 1.0 - exp(-depth / kDepthScale);
  vec3 water = mix(vec3(0.05, 0.30, 0.36), vec3(0.005, 0.04, 0.12), deep);
  vec3 toEye = normalize(frame.cameraPos.xyz - vWorldPos);
  float cosView = clamp(toEye.y, 0.0, 1.0);
  float fresnel = 0.02 + 0.6 * pow(1.0 - cosView, 5.0);
  // Mode 1 (scenes): the analytic sky in the mirror direction (common/sky.glsl); mode 0: the old tint.
  vec3 sky = frame.atmosphere.x > 0.5 ? frameSkyRadiance(reflect(-toEye, vec3(0.0, 1.0, 0.0)))
                                      : mix(frame.fogColor.rgb, vec3(0.25, 0.42, 0.72), 0.5);
  vec3 sun = normalize(frame.sunDirection.xyz);
  float glint = pow(max(dot(reflect(-toEye, vec3(0.0, 1.0, 0.0)), sun), 0.0), 400.0) * frame.sunDirection.w;
  vec3 lit = mix(water * (0.35 + 0.65 * max(sun.y, 0.0)), sky, fresnel) + vec3(glint);
  if (vWall != 0) {
    lit = water * 0.6; // the side of the water body: no sky reflection
    fresnel = 0.0;
  }
  float alpha = clamp(mix(0.55, 0.97, deep) + fresnel, 0.0, 1.0);
  outColor = vec4(toSrgb(applyAtmosphere(lit, vWorldPos)), alpha);
}
