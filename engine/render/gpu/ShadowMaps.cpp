#include <sylva/render/gpu/ShadowMaps.hpp>

#include <sylva/core/Error.hpp>

#include <shared/Frame.h>

namespace sylva::render {

ShadowMaps::ShadowMaps(int size, int cascades) : mSize(size), mCascades(cascades) {
  if (size < 16 || size > 16384) {
    fail("ShadowMaps: size must be 16..16384 texels (got {})", size);
  }
  if (cascades < 1 || cascades > 4) {
    fail("ShadowMaps: cascades must be 1..4 (got {})", cascades);
  }
  mDepth = gl::Texture::create2DArray(GL_DEPTH_COMPONENT32F, size, size, cascades);
  const GLuint id = mDepth.id();
  glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
  glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
  const float border[4] = {1.0f, 1.0f, 1.0f, 1.0f};
  glTextureParameterfv(id, GL_TEXTURE_BORDER_COLOR, border);
  glTextureParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(id, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  mFramebuffers.reserve(static_cast<std::size_t>(cascades));
  for (int i = 0; i < cascades; ++i) {
    gl::Framebuffer& fb = mFramebuffers.emplace_back();
    glNamedFramebufferTextureLayer(fb.id(), GL_DEPTH_ATTACHMENT, id, 0, i);
    glNamedFramebufferDrawBuffer(fb.id(), GL_NONE);
    glNamedFramebufferReadBuffer(fb.id(), GL_NONE);
    fb.checkComplete();
  }
}

void ShadowMaps::begin(int cascade, float slopeBias, float unitsBias) {
  if (cascade < 0 || cascade >= mCascades) {
    fail("ShadowMaps::begin: cascade {} out of range 0..{}", cascade, mCascades - 1);
  }
  if (mActive) {
    fail("ShadowMaps::begin: cascade pass already active (missing end())");
  }
  mActive = true;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &mSaved.framebuffer);
  glGetIntegerv(GL_VIEWPORT, mSaved.viewport);
  glGetBooleanv(GL_COLOR_WRITEMASK, mSaved.colorMask);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &mSaved.depthMask);
  glGetIntegerv(GL_DEPTH_FUNC, &mSaved.depthFunc);
  mSaved.depthTest = glIsEnabled(GL_DEPTH_TEST);
  mSaved.polygonOffset = glIsEnabled(GL_POLYGON_OFFSET_FILL);
  glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &mSaved.offsetFactor);
  glGetFloatv(GL_POLYGON_OFFSET_UNITS, &mSaved.offsetUnits);

  unbind();
  const gl::Framebuffer& fb = mFramebuffers[static_cast<std::size_t>(cascade)];
  fb.bindForDraw(mSize, mSize);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glDepthMask(GL_TRUE);
  fb.clearDepth(1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(slopeBias, unitsBias);
}

void ShadowMaps::end() {
  if (!mActive) {
    fail("ShadowMaps::end: no cascade pass active");
  }
  mActive = false;
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(mSaved.framebuffer));
  glViewport(mSaved.viewport[0], mSaved.viewport[1], mSaved.viewport[2], mSaved.viewport[3]);
  glColorMask(mSaved.colorMask[0], mSaved.colorMask[1], mSaved.colorMask[2], mSaved.colorMask[3]);
  glDepthMask(mSaved.depthMask);
  glDepthFunc(static_cast<GLenum>(mSaved.depthFunc));
  if (mSaved.depthTest) {
    glEnable(GL_DEPTH_TEST);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  if (mSaved.polygonOffset) {
    glEnable(GL_POLYGON_OFFSET_FILL);
  } else {
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  glPolygonOffset(mSaved.offsetFactor, mSaved.offsetUnits);
}

void ShadowMaps::bind() const {
  mDepth.bind(SYLVA_SHADOW_MAP_UNIT);
}

void ShadowMaps::unbind() {
  glBindTextureUnit(SYLVA_SHADOW_MAP_UNIT, 0);
}

Image ShadowMaps::downloadDepth(int cascade) const {
  if (cascade < 0 || cascade >= mCascades) {
    fail("ShadowMaps::downloadDepth: cascade {} out of range 0..{}", cascade, mCascades - 1);
  }
  Image image(mSize, mSize, 1, PixelType::F32);
  glGetTextureSubImage(mDepth.id(), 0, 0, 0, cascade, mSize, mSize, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                       static_cast<GLsizei>(image.byteSize()), image.data());
  return image;
}

} // namespace sylva::render
