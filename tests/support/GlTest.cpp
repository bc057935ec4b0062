#include "GlTest.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Debug.hpp>

#include <cstdlib>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <link.h>

namespace sylva::test {

namespace {

/**
 * Pins the GL driver libraries in memory (RTLD_NODELETE). Mesa unloads its driver at eglTerminate, and
 * LeakSanitizer, which checks at exit, can then neither name the library of the allocations Mesa keeps for
 * the process lifetime nor match them with tests/sanitizers/lsan.supp; they would be reported against our
 * binary.
 */
void pinGlDrivers() {
  std::vector<std::string> paths;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        const std::string name = info->dlpi_name != nullptr ? info->dlpi_name : "";
        if (name.find("/dri/") != std::string::npos || name.find("libgallium") != std::string::npos ||
            name.find("libEGL_mesa") != std::string::npos || name.find("libLLVM") != std::string::npos ||
            name.find("libglapi") != std::string::npos) {
          static_cast<std::vector<std::string>*>(data)->push_back(name);
        }
        return 0;
      },
      &paths);
  for (const std::string& path : paths) {
    // A second reference that is never closed, on a library already loaded.
    (void)dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
  }
}

} // namespace

platform::GlContext* sharedContext(std::string* why) {
  static std::string sWhy;
  static std::unique_ptr<platform::GlContext> sContext = [] {
    try {
      auto context = platform::createHeadlessContext();
      pinGlDrivers();
      return context;
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
