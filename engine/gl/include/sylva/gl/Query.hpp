#pragma once

#include <sylva/gl/Object.hpp>

#include <cstdint>
#include <optional>

namespace sylva::gl {

/** Query object (GL_TIMESTAMP, GL_TIME_ELAPSED, GL_PRIMITIVES_GENERATED, GL_SAMPLES_PASSED, ...). Move-only.
 */
class Query : public Object<detail::deleteQuery> {
public:
  explicit Query(NoCreateT) {}
  explicit Query(GLenum target);

  GLenum target() const { return mTarget; }
  void begin() const;
  void end() const;
  /** Records the GPU timestamp (nanoseconds) when previous commands complete; target must be GL_TIMESTAMP. */
  void timestamp() const;
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
  Sync(Sync&& other) noexcept;
  Sync& operator=(Sync&& other) noexcept;

  /** Inserts a fence after all commands issued so far. */
  static Sync fence();
  /** Waits up to `timeoutNs` nanoseconds (flushing); true when signalled. */
  bool clientWait(std::uint64_t timeoutNs) const;
  explicit operator bool() const { return mSync != nullptr; }

private:
  GLsync mSync = nullptr;
};

} // namespace sylva::gl
