#version 450 core
// Attribute-less patch corners: 4 vertices per instance, positions from gl_VertexID / gl_InstanceID.
#include "demo.glsl"

out vec2 vWorldXz;

void main() {
  vWorldXz = demoPatchCorner(gl_InstanceID, gl_VertexID % 4);
  gl_Position = vec4(vWorldXz.x, 0.0, vWorldXz.y, 1.0);
}
