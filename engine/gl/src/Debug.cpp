#include <sylva/gl/Debug.hpp>

#include <sylva/core/Log.hpp>

namespace sylva::gl {

namespace {

thread_local std::vector<DebugMessage> tErrors;

void GLAPIENTRY onMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                          const GLchar* message, const void*) {
  std::string text(message,
                   length >= 0 ? static_cast<std::size_t>(length) : std::char_traits<char>::length(message));
  // Compiler and linker diagnostics also arrive as errors; gl::Program reports them with file names instead.
  if (type == GL_DEBUG_TYPE_ERROR && source == GL_DEBUG_SOURCE_SHADER_COMPILER) {
    log::debug("GL shader compiler: {}", text);
  } else if (type == GL_DEBUG_TYPE_ERROR) {
    log::error("GL error {}: {}", id, text);
    tErrors.push_back({source, type, id, severity, text});
  } else if (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM) {
    log::warn("GL: {}", text);
  } else {
    log::debug("GL: {}", text);
  }
}

} // namespace

bool enableDebugOutput() {
  if (!epoxy_has_gl_extension("GL_KHR_debug") && epoxy_gl_version() < 43) {
    return false;
  }
  glEnable(GL_DEBUG_OUTPUT);
  glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  glDebugMessageCallback(onMessage, nullptr);
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
  // Notifications (buffer placement hints and the like) are noise at every level but trace.
  glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DEBUG_SEVERITY_NOTIFICATION, 0, nullptr, GL_FALSE);
  return true;
}

const std::vector<DebugMessage>& debugErrors() {
  return tErrors;
}
void clearDebugErrors() {
  tErrors.clear();
}

const char* glEnumName(GLenum value) {
  switch (value) {
  case GL_NO_ERROR:
    return "GL_NO_ERROR";
  case GL_INVALID_ENUM:
    return "GL_INVALID_ENUM";
  case GL_INVALID_VALUE:
    return "GL_INVALID_VALUE";
  case GL_INVALID_OPERATION:
    return "GL_INVALID_OPERATION";
  case GL_INVALID_FRAMEBUFFER_OPERATION:
    return "GL_INVALID_FRAMEBUFFER_OPERATION";
  case GL_OUT_OF_MEMORY:
    return "GL_OUT_OF_MEMORY";
  case GL_FRAMEBUFFER_UNDEFINED:
    return "GL_FRAMEBUFFER_UNDEFINED";
  case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
    return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
  case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
    return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
  case GL_FRAMEBUFFER_UNSUPPORTED:
    return "GL_FRAMEBUFFER_UNSUPPORTED";
  case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
    return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
  default:
    return "unknown GL enum";
  }
}

std::vector<std::string> drainGlErrors() {
  std::vector<std::string> errors;
  for (GLenum e = glGetError(); e != GL_NO_ERROR && errors.size() < 16; e = glGetError()) {
    errors.emplace_back(glEnumName(e));
  }
  return errors;
}

} // namespace sylva::gl
