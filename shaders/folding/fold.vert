#version 450 core
// Attribute-less full-viewport triangle for the fold pass (folding/fold.frag); draw 3 vertices with any VAO.
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
