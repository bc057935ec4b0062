// Folding-texture frame evaluation (docs/folding.md, "Frame evaluation") as plain GLSL functions with no
// bindings and no includes, so the same text serves the renderer (folding/fold.frag) and the exported snippet
// (sylva::folding::gpu::exportShader pastes this file into folding.glsl). The CPU reference is
// sylva::folding::renderFrame (engine/folding/src/Renderer.cpp): these functions repeat its float operations in
// the same order, so the two agree within float rounding (≤ 2/255 per channel).
//
// Spaces: atlas pixels, x right, y down, texel (i, j) covers [i, i+1) × [j, j+1), centre (i + ½, j + ½); texel
// (i, j) is texelFetch(…, ivec2(i, j)) when the images are uploaded top row first. Progress s and the fold
// thresholds t0, t1 are unitless; phases φ are in cycles [0, 1). Colours are in 0..255 until foldOutput().
#pragma once

// Position function types and loop modes: the order of sylva::folding::PositionFunction::Type and LoopMode.
const int FOLD_LINEAR = 0;
const int FOLD_PIECEWISE = 1;
const int FOLD_EXPONENTIAL = 2;
const int FOLD_SIGMOID = 3;
const int FOLD_SINE = 4;
const int FOLD_LOOP_NONE = 0;
const int FOLD_LOOP_PING_PONG = 1;
const int FOLD_LOOP_CROSSFADE = 2;
const int FOLD_MAX_KNOTS = 16;  // piecewise knots
const int FOLD_MAX_LAYERS = 4;  // jump layers K
const int FOLD_MAX_BREAKS = 5;  // breakpoints b_0..b_K

// A profile's position function p(φ) and loop mode. `params` by type:
//   linear:      (slope a, delay d, -, -)          p = clamp(a (φ − d), 0, 1)
//   piecewise:   unused; `knotCount` knots (φ_i, p_i) from foldKnot(profile, i) (none: p = φ)
//   exponential: (k, e^k − 1, -, -)                 p = (e^{kφ} − 1) / (e^k − 1); |k| < 1e-6 gives φ
//   sigmoid:     (k, c, σ(−kc), σ(k(1 − c)))        p = (σ(k(φ − c)) − σ(−kc)) / (σ(k(1 − c)) − σ(−kc))
//   sine:        (A, f, ψ, B)                       p = A (1 − cos(2π f φ + ψ)) / 2 + B
// The constants e^k − 1 and σ(·) are computed in double on the host.
struct FoldFunction {
  int type;
  int loop;
  int knotCount;
  int profile; // index passed to foldKnot
  vec4 params;
};

// Knot i (φ_i, p_i) of profile `profile`'s piecewise function, i < FOLD_MAX_KNOTS. Declared here and defined by
// the file that includes this one (from a uniform block, a constant array, ...), so no knot array is copied.
vec2 foldKnot(int profile, int i);

// What one texel of the folding textures holds (decoded): base read texel, phase offset, profile, and per
// jump layer the jump (Jx, Jy, t0, t1) and the extra fold intervals (t0', t1', t0'', t1'').
struct FoldTexel {
  vec2 base;  // (x0, y0): base read texel index (atlas pixels)
  float dt;   // phase offset (cycles)
  int layers; // K, jump layers used (1..FOLD_MAX_LAYERS)
  int foldMask; // bit k set: fold[k] holds intervals
  vec4 jump[FOLD_MAX_LAYERS];
  vec4 fold[FOLD_MAX_LAYERS];
};

float foldFract(float v) {
  return v - floor(v);
}

// glm::mix as the CPU computes it (the crossfade): x (1 − a) + y a.
vec4 foldMix(vec4 x, vec4 y, float a) {
  return x * (1.0 - a) + y * a;
}

// Linear interpolation as the CPU's bilinear read computes it: x + (y − x) a.
vec4 foldLerp(vec4 x, vec4 y, float a) {
  return x + (y - x) * a;
}

// e^x − 1 without the cancellation of exp(x) − 1 near 0 (GLSL has no expm1).
float foldExpm1(float x) {
  if (abs(x) < 1e-2) {
    return x * (1.0 + x * (0.5 + x * (1.0 / 6.0 + x * (1.0 / 24.0))));
  }
  return exp(x) - 1.0;
}

// p(φ) for φ in [0, 1), without loop remapping (PositionFunction::evaluate).
float foldPosition(FoldFunction f, float phi) {
  if (f.type == FOLD_LINEAR) {
    return clamp(f.params.x * (phi - f.params.y), 0.0, 1.0);
  }
  if (f.type == FOLD_PIECEWISE) {
    if (f.knotCount <= 0) {
      return phi;
    }
    vec2 first = foldKnot(f.profile, 0);
    if (phi <= first.x) {
      return first.y;
    }
    vec2 previous = first;
    vec2 next = first;
    // Constant bounds so compilers unroll (llvmpipe keeps dynamic loops scalar per lane); the segment is found
    // with one break, not a return from inside the loop (which llvmpipe masks lane by lane to the end).
    for (int i = 1; i < FOLD_MAX_KNOTS; ++i) {
      if (i >= f.knotCount) {
        break;
      }
      next = foldKnot(f.profile, i);
      if (phi <= next.x) {
        break;
      }
      previous = next;
    }
    if (phi > next.x) {
      return previous.y;
    }
    float t = (phi - previous.x) / (next.x - previous.x);
    return previous.y + t * (next.y - previous.y);
  }
  if (f.type == FOLD_EXPONENTIAL) {
    if (abs(f.params.x) < 1e-6) {
      return phi;
    }
    return foldExpm1(f.params.x * phi) / f.params.y;
  }
  if (f.type == FOLD_SIGMOID) {
    float sigma = 1.0 / (1.0 + exp(-(f.params.x * (phi - f.params.y))));
    return (sigma - f.params.z) / (f.params.w - f.params.z);
  }
  // FOLD_SINE
  return f.params.x * (1.0 - cos(6.2831853071795864 * f.params.y * phi + f.params.z)) * 0.5 + f.params.w;
}

// φ = fract(base + dt) with the ping-pong remap φ' = 1 − |1 − 2φ| when asked. `base` = fract(t/T + σ) from the
// host (double precision there, so large t keeps its precision).
float foldPhase(int loop, float base, float dt) {
  float phi = foldFract(base + dt);
  if (loop == FOLD_LOOP_PING_PONG) {
    phi = 1.0 - abs(1.0 - 2.0 * phi);
  }
  return phi;
}

// The fold test a = [t0 < s ≤ t1]: thresholds compare with progress, not time.
bool foldIn(float s, float t0, float t1) {
  return t0 < s && s <= t1;
}

// Progress of jump layer `layer` of K: s itself when K = 1 (unclamped), else clamp((s − b_k)/(b_k+1 − b_k), 0, 1).
float foldLayerProgress(float s, int layer, int layers, float breaks[FOLD_MAX_BREAKS]) {
  if (layers == 1) {
    return s;
  }
  return clamp((s - breaks[layer]) / (breaks[layer + 1] - breaks[layer]), 0.0, 1.0);
}

// Read point p = (x0, y0) + ½ + Σ_k a_k s_k J_k (continuous atlas pixels) for progress s.
vec2 foldReadPoint(FoldTexel x, float s, float breaks[FOLD_MAX_BREAKS]) {
  vec2 p = vec2(x.base.x + 0.5, x.base.y + 0.5);
  for (int k = 0; k < FOLD_MAX_LAYERS; ++k) {
    if (k >= x.layers) {
      break;
    }
    float sk = foldLayerProgress(s, k, x.layers, breaks);
    vec4 j = x.jump[k];
    bool a = foldIn(sk, j.z, j.w);
    if ((x.foldMask & (1 << k)) != 0) {
      vec4 f = x.fold[k];
      a = a || foldIn(sk, f.x, f.y) || foldIn(sk, f.z, f.w);
    }
    if (a) {
      p += sk * j.xy;
    }
  }
  return p;
}

// One colour atlas texel in 0..255 (exact integers for an RGBA8 UNORM texture; bind it without sRGB decoding).
vec4 foldTexel255(sampler2D atlas, ivec2 texel) {
  return round(texelFetch(atlas, texel, 0) * 255.0);
}

// Bilinear colour (0..255) at continuous atlas pixel p, from four texelFetch reads (the texture unit's
// filtering weights have only 8 fractional bits), p clamped to the atlas shrunk by ½ texel.
vec4 foldBilinear(sampler2D atlas, vec2 p) {
  ivec2 size = textureSize(atlas, 0);
  p = clamp(p, vec2(0.5), vec2(size) - 0.5);
  vec2 f = p - 0.5;
  vec2 f0 = floor(f);
  vec2 t = f - f0;
  ivec2 i0 = ivec2(f0);
  ivec2 i1 = min(i0 + 1, size - 1);
  vec4 top = foldLerp(foldTexel255(atlas, i0), foldTexel255(atlas, ivec2(i1.x, i0.y)), t.x);
  vec4 bottom = foldLerp(foldTexel255(atlas, ivec2(i0.x, i1.y)), foldTexel255(atlas, i1), t.x);
  return foldLerp(top, bottom, t.y);
}

// The colour (0..255) of a moving texel at a frame whose profile has base phase `base` = fract(t/T + σ):
// φ, s = p(φ), read point, bilinear read; crossfade profiles mix the phases φ1 = fract(base + dt) and
// φ2 = fract(φ1 + ½) with weight w = 1 − |1 − 2φ1| on φ1.
vec4 foldEvaluate(sampler2D atlas, FoldTexel x, FoldFunction f, float base, float breaks[FOLD_MAX_BREAKS]) {
  if (f.loop == FOLD_LOOP_CROSSFADE) {
    float phi1 = foldFract(base + x.dt);
    float phi2 = foldFract(phi1 + 0.5);
    float s1 = foldPosition(f, phi1);
    float s2 = foldPosition(f, phi2);
    float w = 1.0 - abs(1.0 - 2.0 * phi1);
    return foldMix(foldBilinear(atlas, foldReadPoint(x, s2, breaks)),
                   foldBilinear(atlas, foldReadPoint(x, s1, breaks)), w);
  }
  float s = foldPosition(f, foldPhase(f.loop, base, x.dt));
  return foldBilinear(atlas, foldReadPoint(x, s, breaks));
}

// 0..255 colour to what an RGBA8 target stores: round half up (as the CPU), then normalised to [0, 1].
vec4 foldOutput(vec4 c255) {
  return clamp(floor(c255 + 0.5), 0.0, 255.0) / 255.0;
}
