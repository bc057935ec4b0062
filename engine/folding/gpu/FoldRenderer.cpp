#include <sylva/folding/gpu/FoldRenderer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/shader/Compiler.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace sylva::folding::gpu {

static_assert(SYLVA_FOLD_MAX_PROFILES == kMaxProfiles, "shared/Folding.h and Project.hpp disagree");
static_assert(SYLVA_FOLD_MAX_KNOTS == kMaxKnots, "shared/Folding.h and Project.hpp disagree");
static_assert(SYLVA_FOLD_MAX_LAYERS == kMaxJumpLayers, "shared/Folding.h and Project.hpp disagree");

namespace {

using sylva::gpu::FoldProfileGpu;
using sylva::gpu::FoldUniforms;

double sigmoid(double z) {
  return 1.0 / (1.0 + std::exp(-z));
}

FoldProfileGpu packProfile(const Profile& profile) {
  const PositionFunction& fn = profile.fn;
  FoldProfileGpu out{};
  if (fn.knots.size() > static_cast<std::size_t>(kMaxKnots)) {
    fail("fold renderer: profile '{}' has {} knots (at most {})", profile.id, fn.knots.size(), kMaxKnots);
  }
  if (!(profile.periodS > 0.0) || !std::isfinite(profile.periodS)) {
    fail("fold renderer: profile '{}' has period {} s (must be > 0)", profile.id, profile.periodS);
  }
  out.kind = glm::ivec4(static_cast<int>(fn.type), static_cast<int>(profile.loop),
                        static_cast<int>(fn.knots.size()), 0);
  switch (fn.type) {
  case PositionFunction::Type::Linear:
    out.params = glm::vec4(static_cast<float>(fn.slope), static_cast<float>(fn.delay), 0.0f, 0.0f);
    break;
  case PositionFunction::Type::Piecewise:
    break;
  case PositionFunction::Type::Exponential:
    out.params = glm::vec4(static_cast<float>(fn.k), static_cast<float>(std::expm1(fn.k)), 0.0f, 0.0f);
    break;
  case PositionFunction::Type::Sigmoid:
    out.params = glm::vec4(static_cast<float>(fn.k), static_cast<float>(fn.centre),
                           static_cast<float>(sigmoid(-fn.k * fn.centre)),
                           static_cast<float>(sigmoid(fn.k * (1.0 - fn.centre))));
    break;
  case PositionFunction::Type::Sine:
    out.params = glm::vec4(static_cast<float>(fn.amplitude), static_cast<float>(fn.frequency),
                           static_cast<float>(fn.phase), static_cast<float>(fn.offset));
    break;
  }
  for (std::size_t i = 0; i < fn.knots.size(); ++i) {
    glm::vec4& v = out.knots[i / 2];
    const glm::vec2 knot(static_cast<float>(fn.knots[i].x), static_cast<float>(fn.knots[i].y));
    if (i % 2 == 0) {
      v.x = knot.x;
      v.y = knot.y;
    } else {
      v.z = knot.x;
      v.w = knot.y;
    }
  }
  return out;
}

/** fract(t/T + σ) in double, as the CPU reference computes it. */
double basePhase(const Profile& profile, double t) {
  const double v = t / profile.periodS + profile.shift;
  return v - std::floor(v);
}

int foldMaskOf(const Textures& textures) {
  int mask = 0;
  for (std::size_t l = 0; l < textures.fold.size() && l < textures.jump.size(); ++l) {
    if (!textures.fold[l].empty()) {
      mask |= 1 << l;
    }
  }
  return mask;
}

void requireFloat4(const Image& image, int w, int h, const char* what) {
  if (image.width() != w || image.height() != h || image.channels() != 4 || image.type() != PixelType::F32) {
    fail("fold renderer: {} must be a {}x{} RGBA float image (got {}x{}, {} channels of {})", what, w, h,
         image.width(), image.height(), image.channels(), pixelTypeName(image.type()));
  }
}

/** Uploads `region` of a float RGBA image into level 0 (and `layer` for arrays) of `texture`. */
void uploadFloatRect(const gl::Texture& texture, const Image& image, Rect r, int layer, bool array) {
  const std::size_t offset = (static_cast<std::size_t>(r.min.y) * image.width() + r.min.x) * 4;
  const float* data = image.values<float>().data() + offset;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, image.width());
  if (array) {
    glTextureSubImage3D(texture.id(), 0, r.min.x, r.min.y, layer, r.width(), r.height(), 1, GL_RGBA, GL_FLOAT,
                        data);
  } else {
    glTextureSubImage2D(texture.id(), 0, r.min.x, r.min.y, r.width(), r.height(), GL_RGBA, GL_FLOAT, data);
  }
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

/** Restores a capability's enabled state when it goes out of scope. */
class CapabilityScope {
public:
  CapabilityScope(GLenum cap, bool enabled) : mCap(cap), mWas(glIsEnabled(cap) == GL_TRUE) {
    enabled ? glEnable(cap) : glDisable(cap);
  }
  ~CapabilityScope() { mWas ? glEnable(mCap) : glDisable(mCap); }
  CapabilityScope(const CapabilityScope&) = delete;
  CapabilityScope& operator=(const CapabilityScope&) = delete;

private:
  GLenum mCap;
  bool mWas;
};

} // namespace

FoldUniforms foldUniforms(const std::vector<Profile>& profiles, const std::vector<double>& jumpLayers,
                          int layers, double t) {
  if (profiles.size() > static_cast<std::size_t>(kMaxProfiles)) {
    fail("fold renderer: {} profiles (at most {})", profiles.size(), kMaxProfiles);
  }
  if (layers < 0 || layers > kMaxJumpLayers) {
    fail("fold renderer: {} jump layers (at most {})", layers, kMaxJumpLayers);
  }
  if (layers > 1 && jumpLayers.size() != static_cast<std::size_t>(layers) + 1) {
    fail("fold renderer: {} jump layers need {} breakpoints (got {})", layers, layers + 1, jumpLayers.size());
  }
  FoldUniforms u{};
  u.info = glm::ivec4(static_cast<int>(profiles.size()), layers, 0, 0);
  for (std::size_t i = 0; i < jumpLayers.size() && i < 8; ++i) {
    u.breaks[i / 4][static_cast<int>(i % 4)] = static_cast<float>(jumpLayers[i]);
  }
  for (std::size_t k = 0; k < profiles.size(); ++k) {
    u.profiles[k] = packProfile(profiles[k]);
    u.phases[k / 4][static_cast<int>(k % 4)] = static_cast<float>(basePhase(profiles[k], t));
  }
  return u;
}

FoldRenderer::FoldRenderer(const shader::Library& library) : mUniformBuffer(sizeof(FoldUniforms)) {
  reloadShaders(library);
}

void FoldRenderer::reloadShaders(const shader::Library& library) {
  gl::Program program = shader::compileProgram(
      library, {"fold",
                {"folding/fold.vert", "folding/fold.frag"},
                {{"FOLD_LAYERS", std::to_string(mLayers)}, {"FOLD_FOLD_MASK", std::to_string(mFoldMask)}}});
  mLibrary = library;
  mProgram = std::move(program);
  mProgramLayers = mLayers;
  mProgramFoldMask = mFoldMask;
}

const gl::Program& FoldRenderer::program() {
  if (mProgramLayers != mLayers || mProgramFoldMask != mFoldMask) {
    reloadShaders(mLibrary);
  }
  return mProgram;
}

void FoldRenderer::upload(const Textures& textures, const std::vector<Profile>& profiles,
                          const std::vector<double>& jumpLayers) {
  const int layers = static_cast<int>(textures.jump.size());
  // Validate the profiles and layers before touching any GL object.
  (void)foldUniforms(profiles, jumpLayers, layers, 0.0);
  uploadAll(textures);
  mProfiles = profiles;
  mJumpLayers = jumpLayers;
}

void FoldRenderer::setProfiles(const std::vector<Profile>& profiles) {
  (void)foldUniforms(profiles, mJumpLayers, mLayers, 0.0);
  mProfiles = profiles;
}

void FoldRenderer::uploadAll(const Textures& textures) {
  const int w = textures.width();
  const int h = textures.height();
  const int layers = static_cast<int>(textures.jump.size());
  if (w <= 0 || h <= 0) {
    fail("fold renderer: empty textures");
  }
  if (layers > kMaxJumpLayers) {
    fail("fold renderer: {} jump layers (at most {})", layers, kMaxJumpLayers);
  }
  const Image& color = textures.atlas.color;
  if (color.width() != w || color.height() != h || color.channels() != 4 || color.type() != PixelType::U8) {
    fail("fold renderer: the colour atlas must be a {}x{} RGBA8 image (got {}x{}, {} channels of {})", w, h,
         color.width(), color.height(), color.channels(), pixelTypeName(color.type()));
  }
  requireFloat4(textures.init, w, h, "init");
  for (const Image& j : textures.jump) {
    requireFloat4(j, w, h, "jump");
  }
  const int mask = foldMaskOf(textures);
  for (int l = 0; l < layers; ++l) {
    if ((mask & (1 << l)) != 0) {
      requireFloat4(textures.fold[static_cast<std::size_t>(l)], w, h, "fold");
    }
  }

  gl::Texture colorTex = gl::Texture::create2D(GL_RGBA8, w, h);
  colorTex.upload(color);
  gl::Texture init = gl::Texture::create2D(GL_RGBA32F, w, h);
  gl::Texture jump = gl::Texture::create2DArray(GL_RGBA32F, w, h, std::max(layers, 1));
  gl::Texture fold = gl::Texture::create2DArray(GL_RGBA32F, w, h, std::max(layers, 1));
  const Rect all{{0, 0}, {w, h}};
  uploadFloatRect(init, textures.init, all, 0, false);
  for (int l = 0; l < layers; ++l) {
    uploadFloatRect(jump, textures.jump[static_cast<std::size_t>(l)], all, l, true);
    if ((mask & (1 << l)) != 0) {
      uploadFloatRect(fold, textures.fold[static_cast<std::size_t>(l)], all, l, true);
    }
  }
  if (layers == 0) {
    const float still[4] = {0.0f, 0.0f, 1.0f, 1.0f};
    glClearTexImage(jump.id(), 0, GL_RGBA, GL_FLOAT, still);
  }
  if (mask == 0) {
    const float empty[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearTexImage(fold.id(), 0, GL_RGBA, GL_FLOAT, empty);
  }
  for (gl::Texture* t : {&colorTex, &init, &jump, &fold}) {
    t->setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  }
  gl::setLabel(GL_TEXTURE, colorTex.id(), "fold colour atlas");
  gl::setLabel(GL_TEXTURE, init.id(), "fold init");
  gl::setLabel(GL_TEXTURE, jump.id(), "fold jump");
  gl::setLabel(GL_TEXTURE, fold.id(), "fold fold");
  mColor = std::move(colorTex);
  mInit = std::move(init);
  mJump = std::move(jump);
  mFold = std::move(fold);
  if (w != mWidth || h != mHeight) {
    mTarget = gl::Framebuffer(gl::NoCreate);
    mTargetColor = gl::Texture(gl::NoCreate);
  }
  mWidth = w;
  mHeight = h;
  mLayers = layers;
  mFoldMask = mask;
}

void FoldRenderer::updateRegion(const Textures& textures, Rect region) {
  if (!mColor || textures.width() != mWidth || textures.height() != mHeight ||
      static_cast<int>(textures.jump.size()) != mLayers || foldMaskOf(textures) != mFoldMask) {
    uploadAll(textures);
    return;
  }
  region.min = glm::max(region.min, glm::ivec2(0));
  region.max = glm::min(region.max, glm::ivec2(mWidth, mHeight));
  if (region.empty()) {
    return;
  }
  requireFloat4(textures.init, mWidth, mHeight, "init");
  uploadFloatRect(mInit, textures.init, region, 0, false);
  for (int l = 0; l < mLayers; ++l) {
    requireFloat4(textures.jump[static_cast<std::size_t>(l)], mWidth, mHeight, "jump");
    uploadFloatRect(mJump, textures.jump[static_cast<std::size_t>(l)], region, l, true);
    if ((mFoldMask & (1 << l)) != 0) {
      requireFloat4(textures.fold[static_cast<std::size_t>(l)], mWidth, mHeight, "fold");
      uploadFloatRect(mFold, textures.fold[static_cast<std::size_t>(l)], region, l, true);
    }
  }
  // The colour atlas does not change with a re-synthesis of the same layout, but keep it in step anyway.
  const Image& color = textures.atlas.color;
  const std::size_t offset = (static_cast<std::size_t>(region.min.y) * color.width() + region.min.x) * 4;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, color.width());
  glTextureSubImage2D(mColor.id(), 0, region.min.x, region.min.y, region.width(), region.height(), GL_RGBA,
                      GL_UNSIGNED_BYTE, reinterpret_cast<const std::uint8_t*>(color.data()) + offset);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

void FoldRenderer::draw(double t, Rect atlasRegion) {
  if (!mColor) {
    fail("fold renderer: draw() before upload()");
  }
  if (atlasRegion.empty()) {
    atlasRegion = {{0, 0}, {mWidth, mHeight}};
  }
  atlasRegion.min = glm::clamp(atlasRegion.min, glm::ivec2(0), glm::ivec2(mWidth - 1, mHeight - 1));
  atlasRegion.max = glm::clamp(atlasRegion.max, atlasRegion.min + 1, glm::ivec2(mWidth, mHeight));
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, viewport);

  FoldUniforms u = foldUniforms(mProfiles, mJumpLayers, mLayers, t);
  u.info.z = mFoldMask;
  u.atlas = glm::ivec4(mWidth, mHeight, 0, 0);
  u.region = glm::vec4(atlasRegion.min.x, atlasRegion.min.y, atlasRegion.width(), atlasRegion.height());
  u.viewport = glm::vec4(viewport[0], viewport[1], viewport[2], viewport[3]);
  mUniformBuffer.setSubData(0, sizeof(u), &u);
  mUniformBuffer.bindBase(GL_UNIFORM_BUFFER, SYLVA_FOLD_BINDING);
  mColor.bind(SYLVA_FOLD_COLOR_UNIT);
  mInit.bind(SYLVA_FOLD_INIT_UNIT);
  mJump.bind(SYLVA_FOLD_JUMP_UNIT);
  mFold.bind(SYLVA_FOLD_FOLD_UNIT);
  const CapabilityScope depth(GL_DEPTH_TEST, false);
  const CapabilityScope blend(GL_BLEND, false);
  const CapabilityScope cull(GL_CULL_FACE, false);
  program().use();
  mVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

const gl::Framebuffer& FoldRenderer::offscreenTarget() {
  if (!mColor) {
    fail("fold renderer: offscreen target before upload()");
  }
  if (!mTarget) {
    mTargetColor = gl::Texture::create2D(GL_RGBA8, mWidth, mHeight);
    mTargetColor.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
    gl::Framebuffer target;
    target.attachColor(0, mTargetColor);
    target.checkComplete();
    mTarget = std::move(target);
  }
  return mTarget;
}

Image FoldRenderer::render(double t) {
  const gl::Framebuffer& target = offscreenTarget();
  GLint previous = 0;
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  glGetIntegerv(GL_VIEWPORT, viewport);
  target.bindForDraw(mWidth, mHeight);
  draw(t, {{0, 0}, {mWidth, mHeight}});
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  Image image = mTargetColor.download(4, PixelType::U8);
  image.flipVertically();
  return image;
}

GpuBenchResult benchmarkGpu(FoldRenderer& renderer, int frames) {
  frames = std::max(frames, 1);
  const gl::Framebuffer& target = renderer.offscreenTarget();
  GLint previous = 0;
  GLint viewport[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous);
  glGetIntegerv(GL_VIEWPORT, viewport);
  target.bindForDraw(renderer.width(), renderer.height());
  constexpr double kStep = 1.0 / 60.0;
  for (int i = 0; i < 3; ++i) {
    renderer.draw(i * kStep);
  }
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    renderer.draw((i + 3) * kStep);
    // Each frame is flushed, as a swap would: llvmpipe drops the queued work of an earlier frame when the
    // next opaque full-target draw covers it, so unflushed back-to-back frames measure a fraction of the
    // work.
    glFlush();
  }
  glFinish();
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previous));
  glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  GpuBenchResult result;
  result.frames = frames;
  result.width = renderer.width();
  result.height = renderer.height();
  result.msPerFrame = ms / frames;
  result.fps = result.msPerFrame > 0.0 ? 1000.0 / result.msPerFrame : 0.0;
  return result;
}

} // namespace sylva::folding::gpu
