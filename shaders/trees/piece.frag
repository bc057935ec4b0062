#version 450
// Shades a tree surface: bark colour with a little per-quad variation, sun and sky light and fog; debug views
// show piece types, skinning weights of the root joint (paper Fig. 5) and tessellation levels.
#include "trees.glsl"
#include "../common/lighting.glsl"
#include "../common/hash.glsl"
#include "../common/frame.glsl"
#include "fade.glsl"

layout(binding = SYLVA_TREE_BARK_COLOUR_UNIT) uniform sampler2DArray barkColour;
layout(binding = SYLVA_TREE_BARK_NORMAL_UNIT) uniform sampler2DArray barkNormal;

in vec3 fWorld;
in vec3 fNormal;
in vec2 fUv;
in float fRootWeight;
flat in uint fInstance;
flat in uint fPatch;
flat in float fLevel;
in vec2 fTile;             // x across the quad in [0, 1], y along its grain in [0, fTileRepeat]
flat in uint fTileRepeat;  // tiles stacked along the grain
flat in uint fTileClass; // the quad table entry x (piece.tese)
flat in uint fTileEdges;

/** The tangent-space normal `tn` (x along the tile's x, y along its y) in world space: the cotangent frame of
 * the tile coordinates from screen-space derivatives (no stored tangents). */
vec3 perturb(vec3 n, vec3 tn) {
  vec3 dp1 = dFdx(fWorld);
  vec3 dp2 = dFdy(fWorld);
  vec2 dt1 = dFdx(fTile);
  vec2 dt2 = dFdy(fTile);
  vec3 perp2 = cross(dp2, n);
  vec3 perp1 = cross(n, dp1);
  vec3 t = perp2 * dt1.x + perp1 * dt2.x;
  vec3 b = perp2 * dt1.y + perp1 * dt2.y;
  float len = max(dot(t, t), dot(b, b));
  if (!(len > 0.0)) {
    return n;
  }
  float s = inversesqrt(len);
  return normalize(mat3(t * s, b * s, n) * tn);
}

layout(location = 0) out vec4 outColour;

const vec3 kTypeColours[8] = vec3[8](vec3(0.85, 0.3, 0.25), vec3(0.3, 0.75, 0.3), vec3(0.3, 0.45, 0.9),
                                     vec3(0.9, 0.75, 0.2), vec3(0.8, 0.35, 0.85), vec3(0.3, 0.8, 0.85),
                                     vec3(0.6, 0.6, 0.6), vec3(0.9, 0.55, 0.3));

void main() {
  vec3 n = normalize(gl_FrontFacing ? fNormal : -fNormal);
  uvec4 inst = instances[fInstance].joints;
  uint tree = inst.w & 0xffffffu;
  if (trees.far.y > trees.far.x) {
    // Far field: dissolve into the impostor with the complementary mask of its pass.
    if (!piecesKeep(farBlend(crownDistance(tree, frame.cameraPos.xyz), trees.far.xy), uvec2(gl_FragCoord.xy), tree)) {
      discard;
    }
  }
#ifdef SYLVA_TREE_DEPTH_ONLY
  // TreeView::Depth (shadow casters): the depth is all that is kept.
  outColour = vec4(0.0);
  return;
#endif
  uint view = trees.info.z;
  vec3 albedo;
  if (view == 1u) {
    if (!gl_FrontFacing) {
      // The inside, seen only through a crack or a fold: pure magenta, unlit, easy to find.
      outColour = vec4(1.0, 0.0, 1.0, 1.0);
      return;
    }
    albedo = kTypeColours[SYLVA_TREE_INSTANCE_TYPE(inst.z) & 7u];
  } else if (view == 2u) {
    albedo = vec3(fRootWeight);
  } else if (view == 3u) {
    // Levels 1 … 64 on a log scale: blue (coarse) to red (fine).
    float t = clamp(log2(max(fLevel, 1.0)) / 6.0, 0.0, 1.0);
    albedo = mix(vec3(0.15, 0.3, 0.9), vec3(0.95, 0.2, 0.1), t);
  } else if (view == 4u) {
    // Tile ids: tile, quad, the sub-tile along the grain (high 3 bits) with the instance's low 5 bits, and
    // 1 + the instance's high bits (0: nothing drawn).
    uint sub = subTileOf(fTile.y, fTileRepeat);
    uint tile = trees.bark.x > 0.0 ? barkTile(inst.x, fPatch, fTileClass, fTileEdges, sub, fTileRepeat) : 0u;
    outColour = vec4(float(tile & 255u), float(fPatch & 255u), float((fInstance & 31u) | ((sub & 7u) << 5)),
                     float(1u + min(fInstance >> 5, 254u))) / 255.0;
    return;
  } else if (trees.bark.x > 0.0) {
    // Bark tiles: this quad's sub-tile in its class with its edge colours, per piece instance (seed 000
    // §5.1); quads take as many tiles along their grain as keep the tiles' shape (tileRepeat).
    uint species = min(inst.w >> 24, uint(SYLVA_TREE_MAX_SPECIES - 1));
    uint sub = subTileOf(fTile.y, fTileRepeat);
    uint tile = barkTile(inst.x, fPatch, fTileClass, fTileEdges, sub, fTileRepeat);
    float layer = trees.colours[species].w * trees.bark.x + float(tile);
    // Edge lines of the quad sample the tiles' shared outermost texels. The gradients are the continuous
    // coordinate's, so the mip level does not jump where one sub-tile ends and the next begins.
    float size = trees.bark.y;
    vec2 scale = vec2((size - 1.0) / size);
    vec3 st = vec3((vec2(fTile.x, fTile.y - float(sub)) * (size - 1.0) + 0.5) / size, layer);
    vec2 gx = dFdx(fTile) * scale;
    vec2 gy = dFdy(fTile) * scale;
    albedo = textureGrad(barkColour, st, gx, gy).rgb;
    if (trees.bark.z > 0.0) {
      n = perturb(n, textureGrad(barkNormal, st, gx, gy).xyz * 2.0 - 1.0);
    }
  } else {
    uint h = lowbias32(fPatch * 747796405u ^ lowbias32((inst.w & 0xffffffu) * 2891336453u + fInstance));
    float grain = 0.82 + 0.18 * float(h & 255u) / 255.0;
    albedo = trees.colours[min(inst.w >> 24, uint(SYLVA_TREE_MAX_SPECIES - 1))].rgb * grain;
  }
  outColour = vec4(toSrgb(shadeOutdoor(albedo, n, fWorld)), 1.0);
}
