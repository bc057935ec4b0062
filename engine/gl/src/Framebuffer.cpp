#include <sylva/gl/Framebuffer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/gl/Debug.hpp>

namespace sylva::gl {

Framebuffer::Framebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  static_cast<Object&>(*this) = Object(id);
}

void Framebuffer::attachColor(int index, const Texture& texture, int level) {
  if (index < 0 || index >= 8) {
    fail("gl::Framebuffer: colour attachment {} out of range", index);
  }
  glNamedFramebufferTexture(id(), GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(index), texture.id(), level);
  mDrawBuffers[index] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(index);
  mDrawBufferCount = std::max(mDrawBufferCount, index + 1);
  glNamedFramebufferDrawBuffers(id(), mDrawBufferCount, mDrawBuffers);
}

void Framebuffer::attachDepth(const Texture& texture) {
  const bool stencil =
      texture.internalFormat() == GL_DEPTH24_STENCIL8 || texture.internalFormat() == GL_DEPTH32F_STENCIL8;
  glNamedFramebufferTexture(id(), stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, texture.id(),
                            0);
}

void Framebuffer::checkComplete() const {
  const GLenum status = glCheckNamedFramebufferStatus(id(), GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    fail("gl::Framebuffer: incomplete ({})", glEnumName(status));
  }
}

void Framebuffer::bindForDraw(int width, int height) const {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, id());
  glViewport(0, 0, width, height);
}

void Framebuffer::clearColor(int index, const glm::vec4& color) const {
  glClearNamedFramebufferfv(id(), GL_COLOR, index, &color.x);
}

void Framebuffer::clearDepth(float depth) const {
  glClearNamedFramebufferfv(id(), GL_DEPTH, 0, &depth);
}

void bindDefaultFramebuffer(int width, int height) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  glViewport(0, 0, width, height);
}

} // namespace sylva::gl
