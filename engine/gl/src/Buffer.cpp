#include <sylva/gl/Buffer.hpp>

#include <sylva/core/Error.hpp>

namespace sylva::gl {

void setLabel(GLenum identifier, GLuint id, const char* label) {
  if (id != 0 && label != nullptr && epoxy_has_gl_extension("GL_KHR_debug")) {
    glObjectLabel(identifier, id, -1, label);
  }
}

Buffer::Buffer(std::size_t bytes, const void* data, GLbitfield flags) : mSize(bytes) {
  if (bytes == 0) {
    fail("gl::Buffer: zero-sized buffer");
  }
  GLuint id = 0;
  glCreateBuffers(1, &id);
  static_cast<Object&>(*this) = Object(id);
  glNamedBufferStorage(id, static_cast<GLsizeiptr>(bytes), data, flags);
}

void Buffer::setSubData(std::size_t offset, std::size_t bytes, const void* data) {
  if (offset + bytes > mSize) {
    fail("gl::Buffer: update of {} bytes at {} exceeds size {}", bytes, offset, mSize);
  }
  if (bytes > 0) {
    glNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
  }
}

void Buffer::clear() {
  glClearNamedBufferData(id(), GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, nullptr);
}

void Buffer::bindBase(GLenum target, GLuint index) const {
  glBindBufferBase(target, index, id());
}

void Buffer::bindRange(GLenum target, GLuint index, std::size_t offset, std::size_t bytes) const {
  glBindBufferRange(target, index, id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes));
}

void Buffer::bind(GLenum target) const {
  glBindBuffer(target, id());
}

void Buffer::getSubData(std::size_t offset, std::size_t bytes, void* out) const {
  if (offset + bytes > mSize) {
    fail("gl::Buffer: read of {} bytes at {} exceeds size {}", bytes, offset, mSize);
  }
  glGetNamedBufferSubData(id(), static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
}

} // namespace sylva::gl
