#version 450 core
// Per-edge tessellation from the distance of each edge's midpoint to the camera: computed from the edge alone,
// so neighbouring patches agree on shared edges and no cracks appear.
#include "demo.glsl"
#include "../common/frame.glsl"

layout(vertices = 4) out;
in vec2 vWorldXz[];
out vec2 tcWorldXz[];

float edgeLevel(vec2 a, vec2 b) {
  vec2 mid = 0.5 * (a + b);
  float distance = length(vec3(mid.x, 0.0, mid.y) - frame.cameraPos.xyz);
  float level = demo.grid.w * clamp(120.0 / max(distance, 1.0), 0.125, 1.0);
  return clamp(level, 1.0, 64.0);
}

void main() {
  tcWorldXz[gl_InvocationID] = vWorldXz[gl_InvocationID];
  if (gl_InvocationID == 0) {
    // Quad edge order: [0] u=0, [1] v=0, [2] u=1, [3] v=1; corners 0..3 are (0,0), (1,0), (1,1), (0,1) in (u,v).
    gl_TessLevelOuter[0] = edgeLevel(vWorldXz[0], vWorldXz[3]);
    gl_TessLevelOuter[1] = edgeLevel(vWorldXz[0], vWorldXz[1]);
    gl_TessLevelOuter[2] = edgeLevel(vWorldXz[1], vWorldXz[2]);
    gl_TessLevelOuter[3] = edgeLevel(vWorldXz[3], vWorldXz[2]);
    gl_TessLevelInner[0] = max(gl_TessLevelOuter[1], gl_TessLevelOuter[3]);
    gl_TessLevelInner[1] = max(gl_TessLevelOuter[0], gl_TessLevelOuter[2]);
  }
}
