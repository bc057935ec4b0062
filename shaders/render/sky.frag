#version 450 core
// Preetham sky and the sun's disc along each pixel's view ray, written as sRGB like the lit passes.
#include "../common/lighting.glsl"
#include "../common/sky.glsl"

in vec3 vRay;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 dir = normalize(vRay);
  vec3 sun = normalize(frame.sunDirection.xyz);
  vec3 radiance = skyHighlight(skyRadiance(dir, sun, frame.atmosphere.y, frame.atmosphere.z)) +
                  sunDisc(dir, sun, frame.sunDirection.w, frame.atmosphere.z);
  outColor = vec4(toSrgb(radiance), 1.0);
}
