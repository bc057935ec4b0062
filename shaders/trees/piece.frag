#version 450
// Shades a tree surface: bark colour with a little per-quad variation, sun and sky light and fog; debug views
// show piece types, skinning weights of the root joint (paper Fig. 5) and tessellation levels.
#include "trees.glsl"
#include "../common/lighting.glsl"
#include "../common/hash.glsl"

in vec3 fWorld;
in vec3 fNormal;
in vec2 fUv;
in float fRootWeight;
flat in uint fInstance;
flat in uint fPatch;
flat in float fLevel;

layout(location = 0) out vec4 outColour;

const vec3 kTypeColours[8] = vec3[8](vec3(0.85, 0.3, 0.25), vec3(0.3, 0.75, 0.3), vec3(0.3, 0.45, 0.9),
                                     vec3(0.9, 0.75, 0.2), vec3(0.8, 0.35, 0.85), vec3(0.3, 0.8, 0.85),
                                     vec3(0.6, 0.6, 0.6), vec3(0.9, 0.55, 0.3));

void main() {
  vec3 n = normalize(gl_FrontFacing ? fNormal : -fNormal);
  uvec4 inst = instances[fInstance].joints;
  uint view = trees.info.z;
  vec3 albedo;
  if (view == 1u) {
    if (!gl_FrontFacing) {
      // The inside, seen only through a crack or a fold: pure magenta, unlit, easy to find.
      outColour = vec4(1.0, 0.0, 1.0, 1.0);
      return;
    }
    albedo = kTypeColours[(inst.z >> 8) & 7u];
  } else if (view == 2u) {
    albedo = vec3(fRootWeight);
  } else if (view == 3u) {
    // Levels 1 … 64 on a log scale: blue (coarse) to red (fine).
    float t = clamp(log2(max(fLevel, 1.0)) / 6.0, 0.0, 1.0);
    albedo = mix(vec3(0.15, 0.3, 0.9), vec3(0.95, 0.2, 0.1), t);
  } else {
    uint h = lowbias32(fPatch * 747796405u ^ lowbias32((inst.w & 0xffffffu) * 2891336453u + fInstance));
    float grain = 0.82 + 0.18 * float(h & 255u) / 255.0;
    albedo = trees.colours[min(inst.w >> 24, uint(SYLVA_TREE_MAX_SPECIES - 1))].rgb * grain;
  }
  outColour = vec4(toSrgb(shadeOutdoor(albedo, n, fWorld)), 1.0);
}
