#version 450 core
// Multi-textured terrain: splat weights blend per-layer albedo textures; Lambert sun, sky ambient, distance fog.
// Fragments outside the data (beyond the extent, or where the source sample is nodata) are discarded.
#include "terrain.glsl"
#include "../common/lighting.glsl"

in vec3 teWorldPos;
flat in int teLevel;
flat in int teSkirt;
layout(location = 0) out vec4 outColor;

vec3 lodColour(int level) {
  const vec3 colours[8] = vec3[8](vec3(0.90, 0.30, 0.25), vec3(0.95, 0.65, 0.20), vec3(0.90, 0.90, 0.30),
                                  vec3(0.40, 0.80, 0.35), vec3(0.30, 0.75, 0.85), vec3(0.35, 0.45, 0.90),
                                  vec3(0.65, 0.40, 0.90), vec3(0.90, 0.45, 0.75));
  return colours[level % 8];
}

// Ground tint (TerrainDrawOptions::groundTint): rgb colour and strength (0 = off); the map's inverse
// sample spacing (x, z, 1/m) and size in samples.
uniform vec4 uGroundTint;
uniform vec4 uGroundTintMap;
layout(binding = 5) uniform sampler2D groundTintMap;

void main() {
#ifdef SYLVA_TERRAIN_DEPTH_ONLY
  // TerrainView::Depth on a field without holes: nothing to discard, no colour kept (shadow casters).
  outColor = vec4(0.0);
  return;
#endif
  vec2 xz = teWorldPos.xz;
  if (any(lessThan(xz, vec2(0.0))) || any(greaterThan(xz, terrain.extent.xy))) {
    discard;
  }
  ivec2 nearest = clamp(ivec2(floor(xz / terrain.spacing.xy + 0.5)), ivec2(0), terrain.field.xy - 1);
  if (texelFetch(validMask, nearest, 0).r < 0.5) {
    discard;
  }
  int view = int(terrain.extent.z + 0.5);
  if (view >= 4) { // WorldPosition, or Depth where it must discard
    outColor = vec4(teWorldPos, 1.0);
    return;
  }
  if (teSkirt != 0) {
    outColor = vec4(1.0, 0.0, 1.0, 1.0); // visible only through a crack
    return;
  }
  vec2 uv = terrainUv(xz);
  vec2 nxz = texture(normalMap, uv).xy; // rg16_snorm (x, z), filtered
  vec3 normal = normalize(vec3(nxz.x, sqrt(max(0.0, 1.0 - dot(nxz, nxz))), nxz.y));
  if (view == 2) {
    outColor = vec4(normal * 0.5 + 0.5, 1.0);
    return;
  }
  vec3 albedo = vec3(0.0);
  float total = 0.0;
  vec3 splatTint = vec3(0.0);
  for (int page = 0; page < terrain.field.z; ++page) {
    vec4 w = texture(splatMap, vec3(uv, float(page)));
    for (int c = 0; c < 4; ++c) {
      int layer = page * 4 + c;
      if (layer >= terrain.field.w || w[c] <= 0.0) {
        continue;
      }
      vec3 tex = texture(layerAlbedo, vec3(xz / terrain.spacing.z, float(layer))).rgb;
      albedo += w[c] * tex;
      splatTint += w[c] * lodColour(layer);
      total += w[c];
    }
  }
  albedo = total > 0.0 ? albedo / total : vec3(0.3);
  if (uGroundTint.a > 0.0) {
    // The far representation of a grass field: the ground takes the field's average colour where it grows.
    vec2 tintUv = (xz * uGroundTintMap.xy + 0.5) / uGroundTintMap.zw;
    albedo = mix(albedo, uGroundTint.rgb, uGroundTint.a * texture(groundTintMap, tintUv).r);
  }
  if (view == 1) {
    albedo = mix(albedo, lodColour(teLevel), 0.7);
  } else if (view == 3) {
    albedo = total > 0.0 ? splatTint / total : vec3(0.0);
  }
  outColor = vec4(toSrgb(shadeOutdoor(albedo, normal, teWorldPos)), 1.0);
}
