#version 450 core
// Tessellation levels come from the CPU LOD selection (sylva::terrain::Quadtree): the base level on every edge,
// doubled on edges bordering a finer neighbour. Levels are integers and spacing is equal, so a doubled coarse
// edge has exactly the vertices of the two finer edges beside it.
#include "terrain.glsl"

layout(vertices = 4) out;
flat in int vNode[];
// The node, once per patch: the evaluation stage runs per vertex and should not re-read the storage buffer.
patch out vec4 tcRect;
patch out vec4 tcOuter;
patch out ivec4 tcGrid;

void main() {
  gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;
  if (gl_InvocationID == 0) {
    TerrainNode node = nodes[vNode[0]];
    tcRect = node.rect;
    tcOuter = node.tessOuter;
    tcGrid = node.grid;
    if (node.grid.w < 0) {
      for (int e = 0; e < 4; ++e) {
        gl_TessLevelOuter[e] = node.tessOuter[e];
      }
      gl_TessLevelInner[0] = node.tessInner.x;
      gl_TessLevelInner[1] = node.tessInner.x;
    } else {
      // Skirt: u runs along the edge with the edge's level; v runs down with one segment.
      float level = node.tessOuter[node.grid.w];
      gl_TessLevelOuter[0] = 1.0;
      gl_TessLevelOuter[1] = level;
      gl_TessLevelOuter[2] = 1.0;
      gl_TessLevelOuter[3] = level;
      gl_TessLevelInner[0] = level;
      gl_TessLevelInner[1] = 1.0;
    }
  }
}
