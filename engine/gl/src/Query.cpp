#include <sylva/gl/Query.hpp>

#include <utility>

namespace sylva::gl {

Query::Query(GLenum target) : mTarget(target) {
  GLuint id = 0;
  if (target == GL_TIMESTAMP || target == GL_TIME_ELAPSED || target == GL_SAMPLES_PASSED ||
      target == GL_ANY_SAMPLES_PASSED || target == GL_PRIMITIVES_GENERATED) {
    glCreateQueries(target, 1, &id);
  } else {
    // Mesa rejects pipeline-statistics targets in glCreateQueries; a generated name becomes one at
    // glBeginQuery.
    glGenQueries(1, &id);
  }
  static_cast<Object&>(*this) = Object(id);
}

void Query::begin() const {
  glBeginQuery(mTarget, id());
}
void Query::end() const {
  glEndQuery(mTarget);
}
void Query::timestamp() const {
  glQueryCounter(id(), GL_TIMESTAMP);
}

bool Query::available() const {
  GLint ready = GL_FALSE;
  glGetQueryObjectiv(id(), GL_QUERY_RESULT_AVAILABLE, &ready);
  return ready == GL_TRUE;
}

std::optional<std::uint64_t> Query::result(bool wait) const {
  if (!wait && !available()) {
    return std::nullopt;
  }
  GLuint64 value = 0;
  glGetQueryObjectui64v(id(), GL_QUERY_RESULT, &value);
  return value;
}

Sync::~Sync() {
  if (mSync != nullptr) {
    glDeleteSync(mSync);
  }
}

Sync::Sync(Sync&& other) noexcept : mSync(std::exchange(other.mSync, nullptr)) {}

Sync& Sync::operator=(Sync&& other) noexcept {
  if (this != &other) {
    if (mSync != nullptr) {
      glDeleteSync(mSync);
    }
    mSync = std::exchange(other.mSync, nullptr);
  }
  return *this;
}

Sync Sync::fence() {
  Sync sync;
  sync.mSync = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  return sync;
}

bool Sync::clientWait(std::uint64_t timeoutNs) const {
  const GLenum status = glClientWaitSync(mSync, GL_SYNC_FLUSH_COMMANDS_BIT, timeoutNs);
  return status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED;
}

} // namespace sylva::gl
