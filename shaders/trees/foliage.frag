#version 450
// Pass 2 of the foliage: a billboard fragment shows the cloud texel under it; empty texels are discarded and
// covered ones write the depth of the leaf they show (specs/trees.md "2.5D impostor depth"):
// P = P_q + r·(2R·t)/dot(r, −n), projected to window depth. The quad lies on the sphere's front plane, so this
// only pushes fragments away (depth_greater keeps early depth rejection). Colour: the baked lit colour times
// the species' leaf colour, fogged at P; the far-field dissolve of the tree's pieces.
#include "foliage.glsl"
#include "../common/frame.glsl"
#include "../common/lighting.glsl"
#include "fade.glsl"

layout(depth_greater) out float gl_FragDepth;

layout(binding = SYLVA_TREE_FOLIAGE_UNIT) uniform sampler2D cloud;
layout(binding = SYLVA_TREE_NEEDLE_UNIT) uniform sampler2D needleCloud;

in vec3 fWorld;
in vec2 fUv;
flat in float fRadius;
flat in uint fTree;
flat in uint fSpecies;
flat in float fBlend;

layout(location = 0) out vec4 outColour;

void main() {
  if (!piecesKeep(fBlend, uvec2(gl_FragCoord.xy), fTree)) {
    discard;
  }
  vec4 texel = foliage.leafColours[fSpecies].w > 0.5 ? texture(needleCloud, fUv) : texture(cloud, fUv);
  uint code = uint(round(texel.a * 255.0));
  if (code == 0u) {
    discard;
  }
  float t = float(code - 1u) / 254.0;
  vec3 r = normalize(fWorld - frame.cameraPos.xyz);
  vec3 p = fWorld + r * (2.0 * fRadius * t / dot(r, foliage.forward.xyz));
  vec4 clip = frame.viewProj * vec4(p, 1.0);
  float depth = 0.5 * (gl_DepthRange.diff * (clip.z / clip.w) + gl_DepthRange.near + gl_DepthRange.far);
  // Never nearer than the quad itself (rounding), as depth_greater promises.
  gl_FragDepth = max(depth, gl_FragCoord.z);
  vec3 lit = fromSrgb(texel.rgb) / foliage.right.w * foliage.leafColours[fSpecies].rgb;
  // The bake lit the leaves by the sun; in a shadowed spot only the sky's share (about half) remains.
  lit *= mix(0.5, 1.0, sunVisibility(p, -r));
  outColour = vec4(toSrgb(applyAtmosphere(lit, p)), 1.0);
}
