#pragma once

#include <epoxy/gl.h>

#include <functional>
#include <string>
#include <vector>

namespace sylva::gl {

/** One KHR_debug message. */
struct DebugMessage {
  GLenum source = 0;   ///< GL_DEBUG_SOURCE_*
  GLenum type = 0;     ///< GL_DEBUG_TYPE_*
  GLuint id = 0;       ///< the implementation's message id
  GLenum severity = 0; ///< GL_DEBUG_SEVERITY_*
  std::string text;    ///< the message
};

/**
 * Routes KHR_debug messages of the current context to the log (errors as error, performance/portability as
 * debug), synchronously so a message's stack is the offending call's. Returns false if the context lacks
 * KHR_debug. Also stores the messages for inspection by tests (see debugErrors()).
 */
bool enableDebugOutput();

/** Messages of type GL_DEBUG_TYPE_ERROR recorded since the last clearDebugErrors(); thread-local. */
const std::vector<DebugMessage>& debugErrors();
/** Forgets the errors recorded so far (this thread). */
void clearDebugErrors();

/** Human-readable name of a glGetError code or framebuffer status. */
const char* glEnumName(GLenum value);

/** Drains glGetError and returns the names of errors seen (empty if none). */
std::vector<std::string> drainGlErrors();

} // namespace sylva::gl
