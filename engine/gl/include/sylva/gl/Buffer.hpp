#pragma once

#include <sylva/gl/Object.hpp>

#include <cstddef>
#include <span>
#include <vector>

namespace sylva::gl {

/**
 * Immutable-storage buffer object (glNamedBufferStorage). Size is fixed at creation; contents are updated
 * with setSubData() (needs GL_DYNAMIC_STORAGE_BIT, set by default) or by GPU writes. Move-only.
 */
class Buffer : public Object<detail::deleteBuffer> {
public:
  /** An empty wrapper (no GL object; no context needed), to be assigned later. */
  explicit Buffer(NoCreateT) {}
  /** Allocates `bytes` bytes, optionally initialised from `data`; `flags` are glBufferStorage flags. */
  explicit Buffer(std::size_t bytes, const void* data = nullptr, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT);
  /** Allocates and uploads a typed span. */
  template <typename T>
  explicit Buffer(std::span<const T> values, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT)
      : Buffer(values.size_bytes(), values.data(), flags) {}

  /** Size, bytes. */
  std::size_t size() const { return mSize; }
  /** Uploads `bytes` at `offset`; the range must lie inside the buffer. */
  void setSubData(std::size_t offset, std::size_t bytes, const void* data);
  /** Uploads a typed span at byte `offset`. */
  template <typename T> void setSubData(std::span<const T> values, std::size_t offset = 0) {
    setSubData(offset, values.size_bytes(), values.data());
  }
  /** Fills the buffer with zero bytes. */
  void clear();
  /** Binds to an indexed target (GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER, ...) at `index`. */
  void bindBase(GLenum target, GLuint index) const;
  /** Binds a range to an indexed target. */
  void bindRange(GLenum target, GLuint index, std::size_t offset, std::size_t bytes) const;
  /** Binds to a non-indexed target (GL_DRAW_INDIRECT_BUFFER, ...). */
  void bind(GLenum target) const;
  /** Reads `bytes` from `offset` back to the CPU (synchronous). */
  void getSubData(std::size_t offset, std::size_t bytes, void* out) const;
  /** The whole buffer read back as values of T (synchronous). */
  template <typename T> std::vector<T> read() const {
    std::vector<T> out(mSize / sizeof(T));
    getSubData(0, out.size() * sizeof(T), out.data());
    return out;
  }

private:
  std::size_t mSize = 0;
};

} // namespace sylva::gl
