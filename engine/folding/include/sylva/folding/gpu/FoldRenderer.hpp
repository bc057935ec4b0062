#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/shader/Library.hpp>

#include <shared/Folding.h>

#include <vector>

namespace sylva::folding::gpu {

/**
 * Fills the fold pass's uniform block for time `t` (seconds): profiles (function parameters, with e^k − 1 and
 * the sigmoid's end values computed in double), per-profile base phases fract(t/T_k + σ_k) computed in double
 * (so large t loses no precision in the shader's float), and the jump-layer breakpoints. `region` and
 * `viewport` are left zero. Throws sylva::Error when the counts exceed kMaxProfiles, kMaxKnots or
 * kMaxJumpLayers. Pure CPU.
 */
sylva::gpu::FoldUniforms foldUniforms(const std::vector<Profile>& profiles,
                                      const std::vector<double>& jumpLayers, int layers, double t);

/**
 * The GLSL folding renderer (shaders/folding/fold.frag over folding/fold.glsl). It evaluates exactly the
 * equations of the CPU reference renderFrame, in float: φ = fract(t/T + σ + dt), loop remap, s = p(φ), the
 * multi-jump read point (x0, y0) + ½ + Σ a_k s_k J_k and a four-fetch bilinear read of the colour atlas, so
 * its frames match renderFrame within 2/255 per channel. Textures live on the GPU as an RGBA8 colour atlas
 * and RGBA32F init / jump / fold maps (jump and fold as 2D arrays, one slice per jump layer). Needs a current
 * GL 4.5 context for every call, including construction and destruction. Not thread-safe.
 */
class FoldRenderer {
public:
  /** Compiles the fold program from `library`; upload() must come before draw() or render(). */
  explicit FoldRenderer(const shader::Library& library);

  /**
   * Recompiles the program (viewer hot reload); keeps the old one and throws on error. The program is built
   * for the uploaded textures' jump-layer count and fold layers (FOLD_LAYERS, FOLD_FOLD_MASK: constant loop
   * bounds, every array index constant; a loop to a uniform bound kept the layer arrays in per-lane memory on
   * llvmpipe, a fifth of the frame), and rebuilt when they change.
   */
  void reloadShaders(const shader::Library& library);

  /**
   * Uploads everything: colour atlas, init, the K jump layers and the fold layers (if any), and the profiles
   * and breakpoints (`jumpLayers`: K + 1 progress values b_0 = 0 < … < b_K = 1; ignored when K = 1). Throws
   * sylva::Error when sizes disagree or a limit (kMaxProfiles, kMaxKnots, kMaxJumpLayers) is exceeded.
   */
  void upload(const Textures& textures, const std::vector<Profile>& profiles,
              const std::vector<double>& jumpLayers);
  /** Replaces the profiles (live slider changes); same count limits as upload(). */
  void setProfiles(const std::vector<Profile>& profiles);
  /**
   * Re-uploads the texels of `region` (atlas pixels, clipped to the atlas) of every texture, after
   * resynthesize(). If the layout changed (size, layer count, or fold layers appearing or going), uploads
   * everything instead.
   */
  void updateRegion(const Textures& textures, Rect region);

  /**
   * Draws the frame at time `t` (seconds) of the atlas sub-rectangle `atlasRegion` (atlas pixels, clipped to
   * the atlas; empty = whole atlas) as one full-viewport triangle into the bound framebuffer and viewport:
   * each fragment shows its nearest atlas texel, row 0 of the region at the top. Writes colour only (no
   * depth, no blending state changed); for an RGBA8 target the values equal renderFrame's.
   */
  void draw(double t, Rect atlasRegion = {});
  /**
   * Renders the whole atlas at time `t` (seconds) into an atlas-sized RGBA8 offscreen target and reads it
   * back (row 0 at the top), directly comparable with renderFrame(textures, profiles, jumpLayers, t).
   * Restores the default framebuffer binding afterwards.
   */
  Image render(double t);

  /** Atlas size in texels (0 × 0 before upload()). */
  int width() const { return mWidth; }
  /** Atlas height in texels (0 before upload()). */
  int height() const { return mHeight; }
  /** The atlas-sized RGBA8 offscreen target render() draws into (created on first use). */
  const gl::Framebuffer& offscreenTarget();

private:
  void uploadAll(const Textures& textures);
  void uploadRect(const Textures& textures, Rect region);
  /** The program for the current layer count and fold mask (compiled when they change). */
  const gl::Program& program();

  shader::Library mLibrary;
  gl::Program mProgram{gl::NoCreate};
  /** (layers, fold mask) mProgram was built for; −1: none yet. */
  int mProgramLayers = -1;
  int mProgramFoldMask = -1;
  gl::VertexArray mVao;
  gl::Buffer mUniformBuffer;
  gl::Texture mColor{gl::NoCreate};
  gl::Texture mInit{gl::NoCreate};
  gl::Texture mJump{gl::NoCreate};
  gl::Texture mFold{gl::NoCreate};
  gl::Texture mTargetColor{gl::NoCreate};
  gl::Framebuffer mTarget{gl::NoCreate};
  std::vector<Profile> mProfiles;
  std::vector<double> mJumpLayers;
  int mWidth = 0;
  int mHeight = 0;
  int mLayers = 0;
  int mFoldMask = 0;
};

/** Timing of benchmarkGpu: the atlas-sized frame, averaged over `frames` frames after a warm-up. */
struct GpuBenchResult {
  double msPerFrame = 0.0; ///< wall milliseconds per frame (glFinish-bounded)
  double fps = 0.0;        ///< 1000 / msPerFrame
  int width = 0;           ///< frame size, texels (the atlas)
  /** Frame height, texels. */
  int height = 0;
  int frames = 0; ///< frames timed
};

/**
 * Times `frames` full-atlas frames (t advancing by 1/60 s) into the renderer's offscreen target: a warm-up of
 * a few frames and glFinish, then the timed frames and one glFinish. The renderer must have textures
 * uploaded.
 */
GpuBenchResult benchmarkGpu(FoldRenderer& renderer, int frames);

} // namespace sylva::folding::gpu
