#include <sylva/render/gpu/RenderTarget.hpp>

namespace sylva::render {

RenderTarget::RenderTarget(int width, int height)
    : mWidth(width), mHeight(height), mColor(gl::Texture::create2D(GL_RGBA8, width, height)),
      mDepth(gl::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height)) {
  mColor.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  mDepth.setSampler({GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE});
  mFramebuffer.attachColor(0, mColor);
  mFramebuffer.attachDepth(mDepth);
  mFramebuffer.checkComplete();
}

void RenderTarget::begin(const glm::vec4& clear) {
  mFramebuffer.bindForDraw(mWidth, mHeight);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  mFramebuffer.clearColor(0, clear);
  mFramebuffer.clearDepth(1.0f);
}

Image RenderTarget::readColor() const {
  Image image = mColor.download(4, PixelType::U8);
  image.flipVertically();
  return image;
}

Image RenderTarget::readDepth() const {
  Image image(mWidth, mHeight, 1, PixelType::F32);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(mDepth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(image.byteSize()),
                    image.data());
  image.flipVertically();
  return image;
}

Image readFramebuffer(int width, int height) {
  Image image(width, height, 4, PixelType::U8);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.data());
  image.flipVertically();
  return image;
}

} // namespace sylva::render
