#version 450 core
// Attribute-less: one patch of 4 control points per node; the node comes from the storage buffer.
#include "terrain.glsl"

flat out int vNode;
// First node of this draw: gl_InstanceID starts at 0 in every draw (no gl_BaseInstance before GL 4.6).
uniform int uNodeOffset;

void main() {
  vNode = gl_InstanceID + uNodeOffset;
  TerrainNode node = nodes[vNode];
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
  gl_Position = vec4(node.rect.x + corner.x * node.rect.y, 0.0, node.rect.z + corner.y * node.rect.y, 1.0);
}
