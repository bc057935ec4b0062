#include <sylva/gl/VertexArray.hpp>

namespace sylva::gl {

VertexArray::VertexArray() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  static_cast<Object&>(*this) = Object(id);
}

void VertexArray::setVertexBuffer(GLuint binding, const Buffer& buffer, std::size_t offset, int stride,
                                  GLuint divisor) {
  glVertexArrayVertexBuffer(id(), binding, buffer.id(), static_cast<GLintptr>(offset), stride);
  glVertexArrayBindingDivisor(id(), binding, divisor);
}

void VertexArray::setAttribute(GLuint location, GLuint binding, int components, GLenum type, GLuint offset,
                               bool normalized) {
  glEnableVertexArrayAttrib(id(), location);
  glVertexArrayAttribFormat(id(), location, components, type, normalized ? GL_TRUE : GL_FALSE, offset);
  glVertexArrayAttribBinding(id(), location, binding);
}

void VertexArray::setElementBuffer(const Buffer& buffer) {
  glVertexArrayElementBuffer(id(), buffer.id());
}

void VertexArray::bind() const {
  glBindVertexArray(id());
}

} // namespace sylva::gl
