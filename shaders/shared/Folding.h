// Folding-texture GPU layouts, shared by C++ (sylva::folding::gpu::FoldRenderer) and shaders/folding/fold.frag.
#ifndef SYLVA_SHARED_FOLDING_H
#define SYLVA_SHARED_FOLDING_H

#include "Prelude.h"

SYLVA_GPU_BEGIN

#define SYLVA_FOLD_BINDING 6       // uniform block FoldUniforms
#define SYLVA_FOLD_MAX_PROFILES 16 // = sylva::folding::kMaxProfiles
#define SYLVA_FOLD_MAX_KNOTS 16    // = sylva::folding::kMaxKnots (two knots per vec4)
#define SYLVA_FOLD_MAX_LAYERS 4    // = sylva::folding::kMaxJumpLayers

// Texture units of the fold pass.
#define SYLVA_FOLD_COLOR_UNIT 0 // rgba8 colour atlas, texelFetch only
#define SYLVA_FOLD_INIT_UNIT 1  // rgba32f init = (x0, y0, dt, profile k or -1)
#define SYLVA_FOLD_JUMP_UNIT 2  // rgba32f array, layer k = (Jx, Jy, t0, t1) in atlas pixels / progress
#define SYLVA_FOLD_FOLD_UNIT 3  // rgba32f array, layer k = (t0', t1', t0'', t1'')

// One motion profile (sylva::folding::Profile) with its position function. See folding/fold.glsl for the
// meaning of `params` per function type.
struct FoldProfileGpu {
  ivec4 kind;  // x: function type (FOLD_LINEAR..FOLD_SINE), y: loop mode (FOLD_LOOP_*), z: knot count, w: 0
  vec4 params; // function parameters (FoldFunction.params)
  vec4 knots[SYLVA_FOLD_MAX_KNOTS / 2]; // (φ_i, p_i, φ_i+1, p_i+1)
};
SYLVA_ASSERT_SIZE(FoldProfileGpu, 160);

struct FoldUniforms {
  ivec4 info;     // x: profile count, y: jump layer count K, z: bit k set = layer k has fold intervals, w: 0
  ivec4 atlas;    // x, y: atlas size (texels); z, w: 0
  vec4 region;    // atlas sub-rectangle shown: x, y min texel, z, w size (texels)
  vec4 viewport;  // the viewport the quad covers: x, y origin, z, w size (window pixels)
  vec4 breaks[2]; // jump-layer breakpoints b_0..b_K (progress), packed in order
  vec4 phases[SYLVA_FOLD_MAX_PROFILES / 4]; // per profile: fract(t / T_k + σ_k), computed in double on the CPU
  FoldProfileGpu profiles[SYLVA_FOLD_MAX_PROFILES];
};
SYLVA_ASSERT_SIZE(FoldUniforms, 160 + 16 * 160);

SYLVA_GPU_END

#endif
