#version 450 core
// Height-coloured, lit, fogged demo surface; normals from central differences of the height texture.
#include "demo.glsl"
#include "../common/lighting.glsl"

in vec3 teWorldPos;
layout(location = 0) out vec4 outColor;
layout(binding = 0) uniform sampler2D heights;

void main() {
  vec2 texel = 1.0 / vec2(demo.field.xy);
  vec2 uv = demoUv(teWorldPos.xz);
  float spacing = demo.grid.y * texel.x;
  float dx = textureLod(heights, uv + vec2(texel.x, 0.0), 0.0).r - textureLod(heights, uv - vec2(texel.x, 0.0), 0.0).r;
  float dz = textureLod(heights, uv + vec2(0.0, texel.y), 0.0).r - textureLod(heights, uv - vec2(0.0, texel.y), 0.0).r;
  vec3 normal = normalize(vec3(-dx, 2.0 * spacing, -dz));
  float t = clamp(teWorldPos.y / demo.grid.z * 0.5 + 0.5, 0.0, 1.0);
  vec3 low = vec3(0.10, 0.22, 0.06);
  vec3 mid = vec3(0.30, 0.26, 0.14);
  vec3 high = vec3(0.80, 0.80, 0.82);
  vec3 albedo = t < 0.6 ? mix(low, mid, t / 0.6) : mix(mid, high, (t - 0.6) / 0.4);
  outColor = vec4(toSrgb(shadeOutdoor(albedo, normal, teWorldPos)), 1.0);
}
