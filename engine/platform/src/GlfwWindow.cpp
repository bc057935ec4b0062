#include <sylva/platform/GlfwWindow.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Debug.hpp>

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <thread>

namespace sylva::platform {

namespace {

std::string gLastGlfwError;

void onGlfwError(int code, const char* description) {
  gLastGlfwError = fmt::format("{} (0x{:x})", description, code);
  log::debug("GLFW: {}", gLastGlfwError);
}

int gWindowCount = 0;

bool ensureGlfw() {
  glfwSetErrorCallback(onGlfwError);
  // A busy X server (Xvfb while another client's windows close) can refuse a connection for a moment: seen
  // once as "Failed to open display" in a CI run whose display was up. Try a few times before giving up.
  for (int attempt = 0; attempt < 4; ++attempt) {
    if (glfwInit() == GLFW_TRUE) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
  }
  return false;
}

} // namespace

bool displayAvailable() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((x11 == nullptr || *x11 == '\0') && (wayland == nullptr || *wayland == '\0')) {
    return false;
  }
  if (!ensureGlfw()) {
    return false;
  }
  if (gWindowCount == 0) {
    glfwTerminate();
  }
  return true;
}

GlfwWindow::GlfwWindow(int width, int height, const std::string& title, bool visible,
                       const ContextOptions& options) {
  if (!ensureGlfw()) {
    fail("cannot open a window: {} (set DISPLAY, or run under xvfb-run)",
         gLastGlfwError.empty() ? "GLFW initialisation failed" : gLastGlfwError);
  }
  glfwDefaultWindowHints();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE);
  mWindow = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (mWindow == nullptr) {
    if (gWindowCount == 0) {
      glfwTerminate();
    }
    fail("cannot open a {}x{} OpenGL 4.5 core window: {}", width, height, gLastGlfwError);
  }
  ++gWindowCount;
  if (const char* frameFile = std::getenv("SYLVA_FRAME_FILE"); frameFile != nullptr && *frameFile != '\0') {
    mFrameFile = frameFile;
  }
  glfwSetWindowUserPointer(mWindow, this);
  glfwMakeContextCurrent(mWindow);
  glfwSetScrollCallback(mWindow, [](GLFWwindow* w, double, double dy) {
    static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w))->mInput.scrollDelta += dy;
  });
  glfwSetKeyCallback(mWindow, [](GLFWwindow* w, int key, int, int action, int mods) {
    auto* self = static_cast<GlfwWindow*>(glfwGetWindowUserPointer(w));
    if (action == GLFW_PRESS && self->mKeyCallback) {
      self->mKeyCallback(key, mods);
    }
  });
  gl::enableDebugOutput();
  gl::requireSylvaFeatures(gl::queryContextInfo());
}

GlfwWindow::~GlfwWindow() {
  if (mWindow != nullptr) {
    glfwDestroyWindow(mWindow);
    if (--gWindowCount == 0) {
      glfwTerminate();
    }
  }
}

void GlfwWindow::makeCurrent() {
  glfwMakeContextCurrent(mWindow);
}

std::string GlfwWindow::description() const {
  return fmt::format("GLFW {} window", glfwGetVersionString());
}

void GlfwWindow::swapBuffers() {
  glfwSwapBuffers(mWindow);
  ++mFramesShown;
  if (!mFrameFile.empty()) {
    // Written whole and renamed into place, so a reader never sees a partial number.
    writeTextFile(mFrameFile, fmt::format("{}\n", mFramesShown));
  }
}

bool GlfwWindow::pollEvents() {
  const glm::dvec2 previous = mInput.cursor;
  mInput.scrollDelta = 0.0;
  glfwPollEvents();
  glfwGetCursorPos(mWindow, &mInput.cursor.x, &mInput.cursor.y);
  mInput.cursorDelta = mInput.cursor - previous;
  mInput.mouseLeft = glfwGetMouseButton(mWindow, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  mInput.mouseRight = glfwGetMouseButton(mWindow, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  mInput.mouseMiddle = glfwGetMouseButton(mWindow, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  return glfwWindowShouldClose(mWindow) == GLFW_FALSE;
}

glm::ivec2 GlfwWindow::framebufferSize() const {
  glm::ivec2 size(0);
  glfwGetFramebufferSize(mWindow, &size.x, &size.y);
  return size;
}

bool GlfwWindow::keyDown(int key) const {
  return glfwGetKey(mWindow, key) == GLFW_PRESS;
}

void GlfwWindow::setVsync(bool enabled) {
  glfwSwapInterval(enabled ? 1 : 0);
}

} // namespace sylva::platform
