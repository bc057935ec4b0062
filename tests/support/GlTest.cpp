#include "GlTest.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Debug.hpp>

#include <cstdlib>

namespace sylva::test {

platform::GlContext* sharedContext(std::string* why) {
  static std::string sWhy;
  static std::unique_ptr<platform::GlContext> sContext = [] {
    try {
      return platform::createHeadlessContext();
    } catch (const Error& e) {
      sWhy = e.what();
      return std::unique_ptr<platform::GlContext>();
    }
  }();
  if (why != nullptr) {
    *why = sWhy;
  }
  return sContext.get();
}

void GlTest::SetUp() {
  std::string why;
  if (sharedContext(&why) == nullptr) {
    const char* require = std::getenv("SYLVA_REQUIRE_GL");
    if (require != nullptr && std::string(require) == "1") {
      FAIL() << "no headless OpenGL 4.5 context, and SYLVA_REQUIRE_GL=1: " << why;
    }
    GTEST_SKIP() << "no headless OpenGL 4.5 context (" << why << "); GL tests skipped";
  }
  sharedContext()->makeCurrent();
  gl::drainGlErrors();
  gl::clearDebugErrors();
}

void GlTest::TearDown() {
  if (sharedContext() == nullptr) {
    return;
  }
  glFinish();
  for (const gl::DebugMessage& message : gl::debugErrors()) {
    ADD_FAILURE() << "GL debug error: " << message.text;
  }
  for (const std::string& error : gl::drainGlErrors()) {
    ADD_FAILURE() << "glGetError: " << error;
  }
  gl::clearDebugErrors();
}

const shader::Library& GlTest::shaders() {
  static const shader::Library kLibrary;
  return kLibrary;
}

bool GlTest::onLlvmpipe() {
  return gl::queryContextInfo().deviceClass() == "llvmpipe";
}

} // namespace sylva::test
