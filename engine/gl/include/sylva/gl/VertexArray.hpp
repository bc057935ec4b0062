#pragma once

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Object.hpp>

namespace sylva::gl {

/**
 * Vertex array object with DSA attribute setup. An empty one serves attribute-less draws (positions generated
 * from gl_VertexID / gl_InstanceID), which core profile still requires to be bound. Move-only.
 */
class VertexArray : public Object<detail::deleteVertexArray> {
public:
  /** An empty wrapper (no GL object; no context needed), to be assigned later. */
  explicit VertexArray(NoCreateT) {}
  VertexArray();

  /** Binds `buffer` at binding point `binding` with `stride` bytes; `divisor` > 0 makes it per-instance. */
  void setVertexBuffer(GLuint binding, const Buffer& buffer, std::size_t offset, int stride,
                       GLuint divisor = 0);
  /** Float attribute `location` with `components` components of `type` at `offset` within binding. */
  void setAttribute(GLuint location, GLuint binding, int components, GLenum type, GLuint offset,
                    bool normalized = false);
  /** Uses `buffer` as the index buffer of indexed draws. */
  void setElementBuffer(const Buffer& buffer);
  /** Binds for drawing. */
  void bind() const;
};

} // namespace sylva::gl
