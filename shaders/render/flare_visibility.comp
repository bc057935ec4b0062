#version 450 core
// The sun's visibility for the lens flare: 64 depth texels on a golden-angle disc around the sun's projected
// pixel (render::flareSampleOffset, render::sunScreenPosition); a texel with window depth ≥ 1 (nothing drawn)
// sees the sky. Off-target samples and a sun behind the camera count as hidden. One work group; writes the
// fraction and the sun's NDC position for flare.vert (no CPU readback).
#include "../common/sky.glsl"

layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D sceneDepth;
layout(std430, binding = 0) buffer FlareState {
  vec4 sunPixel;  // xy: window pixel, z: 1 in front of the camera, w: sample radius in pixels
  vec4 result;    // x: visibility 0..1, yz: sun NDC, w: unused
} state;
uniform float uMinRadiusPixels;

shared uint visibleSamples;

void main() {
  uint index = gl_LocalInvocationIndex;
  if (index == 0u) {
    visibleSamples = 0u;
  }
  barrier();
  vec3 sun = normalize(frame.sunDirection.xyz);
  vec4 clip = frame.viewProj * vec4(sun, 0.0);
  mat4 vp = frame.viewProj;
  float p11 = length(vec3(vp[0][1], vp[1][1], vp[2][1]));
  float radius = max(p11 * kSunAngularRadius * 0.5 * frame.viewport.y, uMinRadiusPixels);
  bool front = clip.w > 0.0;
  vec2 ndc = front ? clip.xy / clip.w : vec2(0.0);
  vec2 pixel = (ndc * 0.5 + 0.5) * frame.viewport.xy;

  float r = sqrt((float(index) + 0.5) / 64.0);
  float angle = float(index) * 2.39996323;
  ivec2 texel = ivec2(floor(pixel + vec2(r * cos(angle), r * sin(angle)) * radius));
  ivec2 size = textureSize(sceneDepth, 0);
  if (front && all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, size)) &&
      texelFetch(sceneDepth, texel, 0).r >= 1.0) {
    atomicAdd(visibleSamples, 1u);
  }
  barrier();
  if (index == 0u) {
    state.sunPixel = vec4(pixel, front ? 1.0 : 0.0, radius);
    state.result = vec4(float(visibleSamples) / 64.0, ndc, 0.0);
  }
}
