#version 450
// Evaluates the wind at a list of points: the GPU side of the CPU/GPU parity test (tests/gl/wind).
#include "../common/wind.glsl"

layout(local_size_x = 64) in;

layout(std140, binding = SYLVA_WIND_BINDING) uniform WindBlock {
  WindUniforms wind;
};
layout(std430, binding = 0) readonly buffer Points {
  vec2 points[];
};
layout(std430, binding = 1) writeonly buffer Velocities {
  vec2 velocities[];
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < uint(points.length())) {
    velocities[i] = windVelocity(wind, points[i]);
  }
}
