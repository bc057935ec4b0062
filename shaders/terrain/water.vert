#version 450 core
// Attribute-less water body over the terrain's footprint, 30 vertices of triangles: the surface at uWaterLevel
// (world metres, already multiplied by the vertical exaggeration), then four walls along the footprint's edges
// from uWaterBottom up to the surface, so that a cut-off sea shows its side instead of the bare sea floor.
#include "terrain.glsl"

uniform float uWaterLevel;
uniform float uWaterBottom;
out vec3 vWorldPos;
flat out int vWall;

void main() {
  const ivec2 kCorner[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(0, 1), ivec2(0, 1), ivec2(1, 0), ivec2(1, 1));
  int quad = gl_VertexID / 6;
  vec2 c = vec2(kCorner[gl_VertexID % 6]);
  vec2 e = terrain.extent.xy;
  if (quad == 0) {
    vWorldPos = vec3(c.x * e.x, uWaterLevel, c.y * e.y);
  } else {
    // Walls: c.x runs along the edge, c.y from bottom to surface. Edges: north (z = 0), south, west, east.
    float y = mix(uWaterBottom, uWaterLevel, c.y);
    if (quad == 1) {
      vWorldPos = vec3(c.x * e.x, y, 0.0);
    } else if (quad == 2) {
      vWorldPos = vec3(c.x * e.x, y, e.y);
    } else if (quad == 3) {
      vWorldPos = vec3(0.0, y, c.x * e.y);
    } else {
      vWorldPos = vec3(e.x, y, c.x * e.y);
    }
  }
  vWall = quad == 0 ? 0 : 1;
  gl_Position = frame.viewProj * vec4(vWorldPos, 1.0);
}
