#version 450 core
// Attribute-less water surface of the shore pass (docs/scenes.md "Water with a folding-textured shore"): the wet cells (uCellList) of a uCells.x × uCells.y grid over the
// terrain's footprint, 6 vertices per cell, each vertex on a height-field sample (every uStride-th). The surface
// lies at uLevel over water and is draped uLift above the ground on the wet strip (up to uWetTop), so the swash
// can run up the beach over the terrain that hides a flat plane; beyond the strip it stays at uWetTop, under the
// ground, where the terrain's depth hides it.
#include "../common/frame.glsl"

layout(binding = 0) uniform sampler2D uHeights; // R32F world heights, absent samples = 1e20 (always dry)
uniform ivec2 uField;   // samples
uniform vec2 uSpacing;  // metres per sample
uniform ivec2 uCells;   // grid cells of the mesh
uniform int uStride;    // samples per cell edge
uniform float uLevel;   // water surface, world metres
uniform float uLift;    // drape offset above the ground on the wet strip, world metres
uniform float uWetTop;  // world height where the wet strip ends (uLevel + wet · vertical scale)
layout(std430, binding = 0) readonly buffer WaterCells {
  uint uCellList[]; // the cells that can show water (scene::wetCells), x + z · uCells.x
};
out vec3 vWorldPos;

void main() {
  const ivec2 kCorner[6] = ivec2[6](ivec2(0, 0), ivec2(0, 1), ivec2(1, 0), ivec2(1, 0), ivec2(0, 1), ivec2(1, 1));
  int cell = int(uCellList[gl_VertexID / 6]);
  ivec2 g = ivec2(cell % uCells.x, cell / uCells.x) + kCorner[gl_VertexID % 6];
  ivec2 s = min(g * uStride, uField - 1);
  float h = texelFetch(uHeights, s, 0).r;
  float y = min(max(uLevel, h + uLift), uWetTop + uLift);
  vWorldPos = vec3(vec2(s) * uSpacing, y).xzy;
  gl_Position = frame.viewProj * vec4(vWorldPos, 1.0);
}
