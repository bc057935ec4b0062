#version 450 core
// Attribute-less water surface of the shore pass (docs/scenes.md "Water with a folding-textured shore"): the wet cells of a grid over the
// terrain's footprint as triangles of grid points (uPoints: scene::waterTriangles; flat rectangles as fans,
// shore cells as two triangles), each vertex on a height-field sample (every uStride-th). The surface
// lies at uLevel over water and is draped uLift above the ground on the wet strip (up to uWetTop), so the swash
// can run up the beach over the terrain that hides a flat plane; beyond the strip it stays at uWetTop, under the
// ground, where the terrain's depth hides it.
#include "../common/frame.glsl"

layout(binding = 0) uniform sampler2D uHeights; // R32F world heights, absent samples = 1e20 (always dry)
uniform ivec2 uField;   // samples
uniform vec2 uSpacing;  // metres per sample
uniform int uStride;    // samples per cell edge
uniform float uLevel;   // water surface, world metres
uniform float uLift;    // drape offset above the ground on the wet strip, world metres
uniform float uWetTop;  // world height where the wet strip ends (uLevel + wet · vertical scale)
layout(std430, binding = 0) readonly buffer WaterPoints {
  ivec2 uPoints[]; // grid points (cell corners), three per triangle (scene::waterTriangles)
};
out vec3 vWorldPos;

void main() {
  ivec2 g = uPoints[gl_VertexID];
  ivec2 s = min(g * uStride, uField - 1);
  float h = texelFetch(uHeights, s, 0).r;
  float y = min(max(uLevel, h + uLift), uWetTop + uLift);
  vWorldPos = vec3(vec2(s) * uSpacing, y).xzy;
  gl_Position = frame.viewProj * vec4(vWorldPos, 1.0);
}
