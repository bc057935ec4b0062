#version 450 core
// Attribute-less: one 4-point patch per (tile, patch) instance; the patch's corners in tile samples.
#include "stream.glsl"

flat out int vTile;
flat out ivec2 vPatch;

void main() {
  int perEdge = stream.shape.z;
  int perTile = perEdge * perEdge;
  vTile = gl_InstanceID / perTile;
  int p = gl_InstanceID - vTile * perTile;
  vPatch = ivec2(p % perEdge, p / perEdge);
  gl_Position = vec4(float(gl_VertexID & 1), 0.0, float(gl_VertexID >> 1), 1.0);
}
