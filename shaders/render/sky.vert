#version 450 core
// The sky pass: one triangle over the whole viewport at the far plane (window depth 1), carrying the
// world-space view ray of each corner (render::skyViewDirection: for a symmetric perspective P · V the ray is
// linear in NDC).
#include "../common/frame.glsl"

out vec3 vRay;

void main() {
  vec2 ndc = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  mat4 vp = frame.viewProj;
  float p00 = length(vec3(vp[0][0], vp[1][0], vp[2][0]));
  float p11 = length(vec3(vp[0][1], vp[1][1], vp[2][1]));
  vRay = transpose(mat3(frame.view)) * vec3(ndc.x / p00, ndc.y / p11, -1.0);
  gl_Position = vec4(ndc, 1.0, 1.0);
}
