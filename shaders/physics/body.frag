#version 450
// Bodies: a red and cream checker (it shows them roll), lit like the terrain.
#include "../common/lighting.glsl"

in vec3 vWorld;
in vec3 vNormal;
in vec2 vUv;

layout(location = 0) out vec4 outColor;

void main() {
  ivec2 check = ivec2(floor(vUv * vec2(8.0, 4.0)));
  vec3 albedo = ((check.x + check.y) & 1) == 0 ? vec3(0.75, 0.12, 0.08) : vec3(0.85, 0.8, 0.68);
  vec3 lit = shadeOutdoor(albedo, normalize(vNormal), vWorld);
  vec3 view = normalize(frame.cameraPos.xyz - vWorld);
  vec3 halfway = normalize(normalize(frame.sunDirection.xyz) + view);
  lit += 0.25 * pow(max(dot(normalize(vNormal), halfway), 0.0), 40.0) * frame.sunDirection.w;
  outColor = vec4(toSrgb(lit), 1.0);
}
