#version 450
// Shades a far tree's impostor (docs/trees.md "Far field"): the view ray through the pixel is met with the
// planes of the three baked views nearest to the viewing direction (parallax-correct: each view is sampled
// where the ray crosses its own plane, then once more where it crosses the baked depth), their coverage,
// albedo, normal and depth blended by barycentric weight; alpha-tested, lit like the pieces, its depth written
// from the baked depth, and dissolved with the complement of the pieces' mask in the far range's band. A tree
// leaning in the wind is looked up along the un-sheared ray (impostorLean).
#include "impostor.glsl"
#include "fade.glsl"
#include "../common/frame.glsl"
#include "../common/lighting.glsl"

layout(binding = SYLVA_TREE_IMPOSTOR_UNIT) uniform sampler2DArray impostorColour;
layout(binding = SYLVA_TREE_IMPOSTOR_NORMAL_UNIT) uniform sampler2DArray impostorNormal;

in vec3 vWorld;
flat in uint vInstance;
flat in vec4 vSphere;
flat in vec2 vCells[3];
flat in vec3 vWeights;
flat in vec3 vForward[3];
flat in vec3 vRight[3];
flat in vec3 vUp[3];
flat in vec2 vLean;
flat in float vBaseY;

layout(location = 0) out vec4 outColour;
layout(depth_greater) out float gl_FragDepth;

void main() {
  // A pixel's footprint on the billboard (metres), taken before any discard: the atlas is sampled at an
  // explicit level of detail, as derivatives after a (dissolve) discard are undefined.
  float pixelSize = max(length(dFdx(vWorld)), length(dFdy(vWorld)));
  ImpostorInstanceGpu t = impostors[vInstance];
  uint tree = t.info.x;
  bool farOnly = (t.info.w & SYLVA_TREE_IMPOSTOR_FAR_ONLY) != 0u;
  float h = t.placement.w;
  vec3 eyeWorld = frame.cameraPos.xyz;
  if (!farOnly) {
    // The complement of piece.frag's mask, same distance, same tree index.
    float d = distance(eyeWorld, t.placement.xyz + vec3(0.0, 0.5 * h, 0.0));
    if (!impostorKeeps(farBlend(d, impostor.far.xy), uvec2(gl_FragCoord.xy), tree)) {
      discard;
    }
  }
  uint species = min(t.info.y, uint(SYLVA_TREE_MAX_SPECIES - 1));
  float yaw = uintBitsToFloat(t.info.z);
  vec3 centre = vSphere.xyz;
  float radius = vSphere.w;
  float views = impostor.atlas.x;
  float layer = float(species);
  // The leaning tree is the upright one sheared about its base (p + lean · (p.y − base)): rays stay straight
  // under a shear, so the pixel's ray is un-sheared and met with the upright tree's views.
  vec3 shear = vec3(vLean.x, 0.0, vLean.y);
  vec3 eye = eyeWorld - shear * (eyeWorld.y - vBaseY);
  vec3 rayWorld = vWorld - eyeWorld;
  vec3 ray = normalize(rayWorld - shear * rayWorld.y);
  // Texels of a cell per pixel at the sphere's centre (the billboard stands a radius nearer).
  float distanceToCentre = distance(eye, centre);
  float footprint = pixelSize * distanceToCentre / max(distanceToCentre - radius, 1e-3);
  float lod = max(log2(footprint * impostor.atlas.y / (2.0 * radius)), 0.0);
  // First each view where the ray meets its plane through the centre; a view uncovered there contributes
  // nothing, so a pixel no view covers is discarded after three fetches.
  vec2 uv[3];
  vec4 c[3];
  float any_ = 0.0;
  for (int k = 0; k < 3; ++k) {
    c[k] = vec4(0.0);
    uv[k] = vec2(0.0);
    float denom = dot(ray, vForward[k]);
    if (vWeights[k] <= 0.0 || denom > -1e-4) {
      continue;
    }
    float along = dot(centre - eye, vForward[k]) / denom;
    vec3 p = eye + ray * along - centre;
    vec2 local = vec2(dot(p, vRight[k]), dot(p, vUp[k])) / radius;
    if (any(greaterThan(abs(local), vec2(1.0)))) {
      continue;
    }
    uv[k] = (vCells[k] + 0.5 + 0.5 * local) / views;
    c[k] = textureLod(impostorColour, vec3(uv[k], layer), lod);
    any_ += c[k].a;
  }
  if (any_ <= 0.0) {
    discard;
  }
  vec4 colour = vec4(0.0);
  vec4 normalDepth = vec4(0.0);
  for (int k = 0; k < 3; ++k) {
    if (c[k].a <= 0.0) {
      continue;
    }
    vec4 nd = textureLod(impostorNormal, vec3(uv[k], layer), lod);
    if (impostor.atlas.w != 0.0) {
      // Parallax: again where the ray meets the plane at the baked depth found there.
      float offset = (nd.a / c[k].a * 2.0 - 1.0) * radius;
      float along = dot(centre + vForward[k] * offset - eye, vForward[k]) / dot(ray, vForward[k]);
      vec3 p = eye + ray * along - centre;
      vec2 local = vec2(dot(p, vRight[k]), dot(p, vUp[k])) / radius;
      if (any(greaterThan(abs(local), vec2(1.0)))) {
        continue;
      }
      vec3 at = vec3((vCells[k] + 0.5 + 0.5 * local) / views, layer);
      c[k] = textureLod(impostorColour, at, lod);
      nd = textureLod(impostorNormal, at, lod);
    }
    colour += vWeights[k] * c[k];
    normalDepth += vWeights[k] * nd;
  }
  if (colour.a < impostor.atlas.z) {
    discard;
  }
  vec3 albedo = colour.rgb / colour.a;
  vec3 n = normalize(yawRotate(normalDepth.rgb / colour.a * 2.0 - 1.0, yaw));
  float depthOffset = (normalDepth.a / colour.a * 2.0 - 1.0) * radius;
  // The surface point: on the ray, depthOffset in front of the centre along the viewing direction.
  vec3 v = normalize(eye - centre);
  float along = dot(centre + v * depthOffset - eye, v) / dot(ray, v);
  vec3 world = eye + ray * along;
  world += shear * (world.y - vBaseY); // back onto the pixel's ray
  vec4 clip = frame.viewProj * vec4(world, 1.0);
  float depth = clip.z / clip.w * 0.5 + 0.5;
  gl_FragDepth = clamp(max(depth, gl_FragCoord.z), 0.0, 1.0);
  outColour = vec4(toSrgb(shadeOutdoor(albedo, n, world)), 1.0);
}
