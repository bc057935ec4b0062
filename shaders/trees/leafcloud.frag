#version 450
// Pass 1 of the foliage: lit, alpha-tested leaves; rgb = srgb(lit · scale), a = the depth code of the nearest
// leaf (the bake's depth buffer keeps the nearest). Lighting is in world axes (the cloud is not turned per
// anchor): sun on the front, light through the leaf from behind, sky from above, and less of both deeper in
// the cloud and on its side away from the sun (cheap self-shadowing).
#include "foliage.glsl"
#include "../common/lighting.glsl"

layout(binding = SYLVA_TREE_LEAF_UNIT) uniform sampler2D leafTexture;

in vec3 vCloud;
in vec3 vNormal;
in vec2 vUv;
in vec3 vTint;
in float vT;

layout(location = 0) out vec4 outColour;

void main() {
  // Leaf uv has (0, 0) at the image's bottom left; the texture holds the image top row first.
  vec4 leaf = foliage.up.w > 0.5 ? texture(leafTexture, vec2(vUv.x, 1.0 - vUv.y)) : vec4(1.0);
  if (leaf.a < 0.5) {
    discard;
  }
  vec3 n = normalize(vNormal);
  if (dot(n, foliage.forward.xyz) > 0.0) {
    n = -n; // two-sided: the side the viewer sees
  }
  vec3 sun = normalize(foliage.sun.xyz);
  float ndl = dot(n, sun);
  float direct = (ndl > 0.0 ? ndl : -0.4 * ndl) * foliage.sun.w;
  float sunSide = clamp(0.55 + 0.6 * dot(vCloud, sun), 0.15, 1.0);
  float depthIn = mix(0.55, 1.0, clamp(length(vCloud), 0.0, 1.0));
  float sky = 0.5 + 0.5 * n.y;
  vec3 light = direct * sunSide * vec3(1.0, 0.96, 0.88) +
               depthIn * mix(vec3(0.18, 0.16, 0.14), vec3(0.32, 0.38, 0.48), sky);
  vec3 lit = leaf.rgb * vTint * light;
  outColour = vec4(toSrgb(clamp(lit * foliage.right.w, 0.0, 1.0)), encodeFoliageDepth(vT));
}
