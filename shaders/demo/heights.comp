#version 450 core
// Writes the demo height field (metres) into an r32f image: rolling hills plus a ripple around a point.
#include "demo.glsl"

layout(local_size_x = SYLVA_DEMO_GROUP_SIZE, local_size_y = SYLVA_DEMO_GROUP_SIZE) in;
layout(r32f, binding = 0) uniform writeonly image2D heights;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(texel, demo.field.xy))) {
    return;
  }
  vec2 uv = (vec2(texel) + 0.5) / vec2(demo.field.xy);
  vec2 xz = (uv - 0.5) * demo.grid.y;
  float hills = 0.55 * sin(xz.x * 0.045) * cos(xz.y * 0.035) + 0.25 * sin(xz.x * 0.11 + xz.y * 0.07) +
                0.12 * cos(length(xz) * 0.09);
  float r = length(xz - demo.wave.zw);
  float ripple = 0.18 * sin(r * demo.wave.y - demo.wave.x * 2.0) * exp(-r * 0.02);
  imageStore(heights, texel, vec4((hills + ripple) * demo.grid.z));
}
