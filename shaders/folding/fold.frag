#version 450 core
// The fold pass: every fragment of the viewport shows one texel of an atlas sub-rectangle (nearest texel, row 0
// of the atlas at the top of the viewport), evaluated with folding/fold.glsl from the float textures that
// sylva::folding::gpu::FoldRenderer uploads. CPU reference: sylva::folding::renderFrame.
#include "../shared/Folding.h"
#include "fold.glsl"

layout(std140, binding = SYLVA_FOLD_BINDING) uniform FoldBlock {
  FoldUniforms fold;
};

layout(binding = SYLVA_FOLD_COLOR_UNIT) uniform sampler2D colorAtlas;  // rgba8, atlas pixels
layout(binding = SYLVA_FOLD_INIT_UNIT) uniform sampler2D initMap;      // rgba32f (x0, y0, dt, profile)
layout(binding = SYLVA_FOLD_JUMP_UNIT) uniform sampler2DArray jumpMaps; // rgba32f (Jx, Jy, t0, t1) per layer
layout(binding = SYLVA_FOLD_FOLD_UNIT) uniform sampler2DArray foldMaps; // rgba32f (t0', t1', t0'', t1'')

layout(location = 0) out vec4 fragColor;

vec2 foldKnot(int profile, int i) {
  vec4 v = fold.profiles[profile].knots[i >> 1];
  return (i & 1) == 0 ? v.xy : v.zw;
}

FoldFunction profileFunction(int k) {
  ivec4 kind = fold.profiles[k].kind;
  return FoldFunction(kind.x, kind.y, kind.z, k, fold.profiles[k].params);
}

void main() {
  // Viewport pixel → atlas texel: x to the right, y from the top of the viewport.
  vec2 v = (gl_FragCoord.xy - fold.viewport.xy) / fold.viewport.zw;
  vec2 a = vec2(fold.region.x + v.x * fold.region.z, fold.region.y + (1.0 - v.y) * fold.region.w);
  ivec2 lo = ivec2(fold.region.xy);
  ivec2 texel = clamp(ivec2(floor(a)), lo, lo + ivec2(fold.region.zw) - 1);

  vec4 init = texelFetch(initMap, texel, 0);
  int k = int(init.w);
  if (init.w < 0.0 || k >= fold.info.x) {
    fragColor = texelFetch(colorAtlas, texel, 0); // a still texel shows itself
    return;
  }
  FoldTexel x;
  x.base = init.xy;
  x.dt = init.z;
#ifdef FOLD_LAYERS
  // The renderer builds one program per layer count and fold mask: constant loop bounds below and in
  // foldReadPoint, so every array index is a constant.
  x.layers = FOLD_LAYERS;
  x.foldMask = FOLD_FOLD_MASK;
#else
  x.layers = fold.info.y;
  x.foldMask = fold.info.z;
#endif
  // Fetch only the layers in use: the bounds are uniform, so no lane fetches what it will not read (a ?: here
  // would fetch all FOLD_MAX_LAYERS of both arrays on llvmpipe, where both operands are evaluated).
  for (int l = 0; l < FOLD_MAX_LAYERS; ++l) {
    x.jump[l] = vec4(0.0, 0.0, 1.0, 1.0);
    x.fold[l] = vec4(1.0);
  }
  for (int l = 0; l < FOLD_MAX_LAYERS; ++l) {
    if (l >= x.layers) {
      break;
    }
    x.jump[l] = texelFetch(jumpMaps, ivec3(texel, l), 0);
    if ((x.foldMask & (1 << l)) != 0) {
      x.fold[l] = texelFetch(foldMaps, ivec3(texel, l), 0);
    }
  }
  float breaks[FOLD_MAX_BREAKS] =
      float[FOLD_MAX_BREAKS](fold.breaks[0].x, fold.breaks[0].y, fold.breaks[0].z, fold.breaks[0].w,
                             fold.breaks[1].x);
  float base = fold.phases[k >> 2][k & 3];
  fragColor = foldOutput(foldEvaluate(colorAtlas, x, profileFunction(k), base, breaks));
}
