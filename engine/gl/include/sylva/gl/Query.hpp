#pragma once

#include <sylva/gl/Object.hpp>

#include <cstdint>
#include <optional>

namespace sylva::gl {

/** Query object (GL_TIMESTAMP, GL_TIME_ELAPSED, GL_PRIMITIVES_GENERATED, GL_SAMPLES_PASSED, ...). Move-only.
 */
class Query : public Object<detail::deleteQuery> {
public:
  /** An empty wrapper (no GL object; no context needed), to be assigned later. */
  explicit Query(NoCreateT) {}
  /** A query of kind `target` (GL_TIME_ELAPSED, GL_SAMPLES_PASSED, …). */
  explicit Query(GLenum target);

  /** The query's kind. */
  GLenum target() const { return mTarget; }
  /** Starts counting (glBeginQuery). */
  void begin() const;
  /** Stops counting (glEndQuery). */
  void end() const;
  /** Records the GPU timestamp (nanoseconds) when previous commands complete; target must be GL_TIMESTAMP. */
  void timestamp() const;
  /** Whether the result is ready (never waits). */
  bool available() const;
  /** The result, waiting for it if `wait`; nullopt when not ready and not waiting. */
  std::optional<std::uint64_t> result(bool wait = true) const;

private:
  GLenum mTarget = GL_TIMESTAMP;
};

/** Fence sync. Move-only. */
class Sync {
public:
  Sync() = default;
  ~Sync();
  Sync(const Sync&) = delete;
  Sync& operator=(const Sync&) = delete;
  /** Takes `other`'s fence; `other` is left empty. */
  Sync(Sync&& other) noexcept;
  /** Deletes the fence held, then takes `other`'s. */
  Sync& operator=(Sync&& other) noexcept;

  /** Inserts a fence after all commands issued so far. */
  static Sync fence();
  /** Waits up to `timeoutNs` nanoseconds (flushing); true when signalled. */
  bool clientWait(std::uint64_t timeoutNs) const;
  /** Whether a fence is held. */
  explicit operator bool() const { return mSync != nullptr; }

private:
  GLsync mSync = nullptr;
};

} // namespace sylva::gl
