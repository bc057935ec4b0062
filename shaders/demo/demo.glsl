// Demo scene bindings shared by its stages.
#pragma once
#include "../shared/Demo.h"

layout(std140, binding = SYLVA_DEMO_BINDING) uniform DemoBlock {
  DemoUniforms demo;
};

// World xz (metres) of patch corner `corner` (0..3, counter-clockwise from the min corner) of instance `id`.
vec2 demoPatchCorner(int id, int corner) {
  int n = int(demo.grid.x);
  float size = demo.grid.y / float(n);
  vec2 origin = vec2(float(id % n), float(id / n)) * size;
  vec2 offsets[4] = vec2[4](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(1.0, 1.0), vec2(0.0, 1.0));
  return origin + offsets[corner] * size - vec2(0.5 * demo.grid.y);
}

// Texture coordinate of world xz, texel centres at (i + 0.5) / size.
vec2 demoUv(vec2 xz) {
  return xz / demo.grid.y + 0.5;
}
