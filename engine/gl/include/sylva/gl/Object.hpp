#pragma once

#include <epoxy/gl.h>

#include <utility>

namespace sylva::gl {

/** Tag for constructing a wrapper that owns no GL object yet (no GL call is made, no context needed). */
struct NoCreateT {
  explicit constexpr NoCreateT() = default;
};
/** Pass to a wrapper's constructor for an empty wrapper (no GL object). */
inline constexpr NoCreateT NoCreate{};

/**
 * Base of the move-only RAII wrappers: owns one GL object name and deletes it through `Deleter` when
 * destroyed. Wrappers never copy; moving transfers ownership and leaves the source in the NoCreate state. The
 * name is exposed only to the gl layer and to driver-facing code (`id()`); module APIs pass wrapper
 * references.
 */
template <void (*Deleter)(GLuint)> class Object {
public:
  Object() = default;
  /** Takes ownership of GL name `id`. */
  explicit Object(GLuint id) : mId(id) {}
  ~Object() { reset(); }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  /** Takes `other`'s object; `other` is left empty. */
  Object(Object&& other) noexcept : mId(std::exchange(other.mId, 0)) {}
  /** Deletes the object held, then takes `other`'s; `other` is left empty. */
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      mId = std::exchange(other.mId, 0);
    }
    return *this;
  }

  /** The GL name, 0 in the NoCreate state. For the gl layer and debug labels only. */
  GLuint id() const { return mId; }
  /** Whether an object is held (not the NoCreate state). */
  explicit operator bool() const { return mId != 0; }

protected:
  /** Deletes the object held, if any. */
  void reset() {
    if (mId != 0) {
      Deleter(mId);
      mId = 0;
    }
  }

private:
  GLuint mId = 0;
};

namespace detail {
inline void deleteBuffer(GLuint id) {
  glDeleteBuffers(1, &id);
}
inline void deleteTexture(GLuint id) {
  glDeleteTextures(1, &id);
}
inline void deleteFramebuffer(GLuint id) {
  glDeleteFramebuffers(1, &id);
}
inline void deleteVertexArray(GLuint id) {
  glDeleteVertexArrays(1, &id);
}
inline void deleteQuery(GLuint id) {
  glDeleteQueries(1, &id);
}
inline void deleteProgram(GLuint id) {
  glDeleteProgram(id);
}
inline void deleteShader(GLuint id) {
  glDeleteShader(id);
}
} // namespace detail

/** Attaches a human-readable label for debuggers and KHR_debug messages. */
void setLabel(GLenum identifier, GLuint id, const char* label);

} // namespace sylva::gl
