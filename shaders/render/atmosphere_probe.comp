#version 450 core
// Probe of the shared haze (tests and tools): applyAtmosphere(lit, worldPos) for a list of points, under the
// bound frame uniforms, exactly as every lit pass calls it. Input vec4 pairs (lit.rgb, _), (worldPos.xyz, _);
// output vec4 (colour, 0) per point.
#include "../common/atmosphere.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points {
  vec4 points[];
};
layout(std430, binding = 1) writeonly buffer Colours {
  vec4 colours[];
};
uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) {
    return;
  }
  colours[i] = vec4(applyAtmosphere(points[2u * i].rgb, points[2u * i + 1u].xyz), 0.0);
}
