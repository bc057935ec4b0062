#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Texture.hpp>

#include <glm/glm.hpp>

namespace sylva::render {

/** An offscreen RGBA8 colour + 32-bit float depth target of `width`×`height` pixels. Move-only. */
class RenderTarget {
public:
  /** Allocates the attachments; needs a current context. */
  RenderTarget(int width, int height);

  int width() const { return mWidth; }   ///< pixels
  int height() const { return mHeight; } ///< pixels
  /** width / height, for Camera::projection. */
  float aspect() const { return static_cast<float>(mWidth) / static_cast<float>(mHeight); }
  /** Binds for drawing, sets the viewport, clears colour to `clear` and depth to 1. */
  void begin(const glm::vec4& clear);
  const gl::Framebuffer& framebuffer() const { return mFramebuffer; } ///< the framebuffer object
  const gl::Texture& color() const { return mColor; }                 ///< the RGBA8 colour attachment
  const gl::Texture& depth() const { return mDepth; }                 ///< the 32-bit float depth attachment
  /** Reads the colour attachment back as an RGBA8 image in file order (top row first). */
  Image readColor() const;
  /** Reads the depth attachment as a 1-channel float image (window depth in [0, 1], top row first). */
  Image readDepth() const;

private:
  int mWidth;
  int mHeight;
  gl::Texture mColor;
  gl::Texture mDepth;
  gl::Framebuffer mFramebuffer;
};

/** Reads the currently bound read framebuffer's colour as RGBA8 in file order (for window tests). */
Image readFramebuffer(int width, int height);

} // namespace sylva::render
