#version 450 core
// Displaces the tessellated patch by the height texture written by heights.comp.
#include "demo.glsl"
#include "../common/frame.glsl"

layout(quads, fractional_odd_spacing, ccw) in;
in vec2 tcWorldXz[];
out vec3 teWorldPos;

layout(binding = 0) uniform sampler2D heights;

void main() {
  vec2 u = gl_TessCoord.xy;
  vec2 xz = mix(mix(tcWorldXz[0], tcWorldXz[1], u.x), mix(tcWorldXz[3], tcWorldXz[2], u.x), u.y);
  float h = textureLod(heights, demoUv(xz), 0.0).r;
  teWorldPos = vec3(xz.x, h, xz.y);
  gl_Position = frame.viewProj * vec4(teWorldPos, 1.0);
}
