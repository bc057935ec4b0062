#version 450 core
// One flare sprite, added to the sRGB colour (render::flareSpriteProfile): the halo falls off from its
// centre, a ghost is a soft-edged disc brightening towards its rim.
in vec2 vCorner;
in vec3 vColour;
flat in int vHalo;
layout(location = 0) out vec4 outColor;

void main() {
  float r = length(vCorner);
  if (r >= 1.0) {
    discard;
  }
  float profile = vHalo != 0 ? (1.0 - r) * (1.0 - r) : (1.0 - smoothstep(0.8, 1.0, r)) * (0.4 + 0.6 * r * r);
  outColor = vec4(vColour * profile, 1.0);
}
