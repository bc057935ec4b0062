#pragma once

#include <sylva/gl/Object.hpp>
#include <sylva/gl/Texture.hpp>

#include <glm/glm.hpp>

namespace sylva::gl {

/** Framebuffer object with DSA attachments. Move-only; does not own attached textures. */
class Framebuffer : public Object<detail::deleteFramebuffer> {
public:
  /** An empty wrapper (no GL object; no context needed), to be assigned later. */
  explicit Framebuffer(NoCreateT) {}
  Framebuffer();

  /** Attaches `texture` level 0 to GL_COLOR_ATTACHMENT0 + index and enables it as a draw buffer. */
  void attachColor(int index, const Texture& texture, int level = 0);
  /** Attaches a depth (or depth-stencil) texture. */
  void attachDepth(const Texture& texture);
  /** Throws sylva::Error with the GL status name if the framebuffer is incomplete. */
  void checkComplete() const;
  /** Binds for drawing and sets the viewport to `width`×`height` pixels. */
  void bindForDraw(int width, int height) const;
  /** Clears colour attachment `index` to `color`. */
  void clearColor(int index, const glm::vec4& color) const;
  /** Clears the depth attachment to `depth` (1 = far). */
  void clearDepth(float depth = 1.0f) const;

private:
  GLenum mDrawBuffers[8] = {GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE, GL_NONE};
  int mDrawBufferCount = 0;
};

/** Binds the window-system framebuffer (0) with a viewport of `width`×`height` pixels. */
void bindDefaultFramebuffer(int width, int height);

} // namespace sylva::gl
