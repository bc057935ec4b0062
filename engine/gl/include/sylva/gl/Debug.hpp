#pragma once

#include <epoxy/gl.h>

#include <functional>
#include <string>
#include <vector>

namespace sylva::gl {

/** One KHR_debug message. */
struct DebugMessage {
  GLenum source = 0;
  GLenum type = 0;
  GLuint id = 0;
  GLenum severity = 0;
  std::string text;
};

/**
 * Routes KHR_debug messages of the current context to the log (errors as error, performance/portability as
 * debug), synchronously so a message's stack is the offending call's. Returns false if the context lacks
 * KHR_debug. Also stores the messages for inspection by tests (see debugErrors()).
 */
bool enableDebugOutput();

/** Messages of type GL_DEBUG_TYPE_ERROR recorded since the last clearDebugErrors(); thread-local. */
const std::vector<DebugMessage>& debugErrors();
void clearDebugErrors();

/** Human-readable name of a glGetError code or framebuffer status. */
const char* glEnumName(GLenum value);

/** Drains glGetError and returns the names of errors seen (empty if none). */
std::vector<std::string> drainGlErrors();

} // namespace sylva::gl
