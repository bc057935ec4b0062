#include <sylva/gl/State.hpp>

#include <epoxy/gl.h>

namespace sylva::gl {

void finish() {
  glFinish();
}

void bindWindowFramebuffer() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void setViewport(glm::ivec2 origin, glm::ivec2 size) {
  glViewport(origin.x, origin.y, size.x, size.y);
}

void clear(const glm::vec4& colour, bool depth) {
  glClearColor(colour.r, colour.g, colour.b, colour.a);
  glClear(GL_COLOR_BUFFER_BIT | (depth ? GL_DEPTH_BUFFER_BIT : 0));
}

void setDepthTest(bool on) {
  if (on) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
}

void blitToWindow(const Framebuffer& source, glm::ivec2 size) {
  blitToWindow(source, size, size);
}

void blitToWindow(const Framebuffer& source, glm::ivec2 sourceSize, glm::ivec2 size) {
  glBlitNamedFramebuffer(source.id(), 0, 0, 0, sourceSize.x, sourceSize.y, 0, 0, size.x, size.y,
                         GL_COLOR_BUFFER_BIT, sourceSize == size ? GL_NEAREST : GL_LINEAR);
}

} // namespace sylva::gl
