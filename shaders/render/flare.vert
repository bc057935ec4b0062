#version 450 core
// Lens-flare ghosts (render::flareGhosts): instance i is a quad centred at sunNdc · (1 − t_i) on the line
// from the sun through the screen centre, radius r_i in NDC y units (round on screen), colour scaled by the
// sun's visibility from flare_visibility.comp, the sun's intensity and uStrength. Invisible flares collapse.
#include "../common/frame.glsl"

layout(std430, binding = 0) readonly buffer FlareState {
  vec4 sunPixel;
  vec4 result;
} state;
uniform float uStrength;

out vec2 vCorner;
out vec3 vColour;
flat out int vHalo;

// t, radius, halo flag; colours below. Keep in step with render::flareGhostTable().
const vec3 kGhosts[8] = vec3[8](vec3(0.0, 0.30, 1.0), vec3(0.30, 0.045, 0.0), vec3(0.55, 0.09, 0.0),
                                vec3(0.80, 0.03, 0.0), vec3(1.10, 0.14, 0.0), vec3(1.35, 0.06, 0.0),
                                vec3(1.65, 0.10, 0.0), vec3(2.00, 0.20, 0.0));
const vec3 kGhostColours[8] = vec3[8](vec3(0.32, 0.27, 0.20), vec3(0.22, 0.14, 0.07), vec3(0.08, 0.16, 0.10),
                                      vec3(0.14, 0.17, 0.28), vec3(0.06, 0.05, 0.12), vec3(0.20, 0.09, 0.07),
                                      vec3(0.07, 0.12, 0.16), vec3(0.05, 0.08, 0.10));

void main() {
  vec3 ghost = kGhosts[gl_InstanceID];
  vec2 corner = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  float visibility = state.result.x;
  vec2 centre = state.result.yz * (1.0 - ghost.x);
  float aspect = frame.viewport.x * frame.viewport.w;
  vCorner = corner;
  vColour = kGhostColours[gl_InstanceID] * (visibility * frame.sunDirection.w * uStrength);
  vHalo = int(ghost.z);
  if (visibility <= 0.0) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0); // outside the clip volume: nothing drawn
    return;
  }
  gl_Position = vec4(centre + corner * ghost.y * vec2(1.0 / aspect, 1.0), 0.0, 1.0);
}
