#pragma once

#include <sylva/platform/GlContext.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <glm/glm.hpp>

struct GLFWwindow;

namespace sylva::platform {

/** Input state of one frame, in window pixels (origin top-left). */
struct InputState {
  glm::dvec2 cursor{0.0};      ///< cursor position, window pixels
  glm::dvec2 cursorDelta{0.0}; ///< cursor movement since the last frame, window pixels
  double scrollDelta = 0.0;    ///< vertical wheel steps since the last frame (positive: away from the user)
  bool mouseLeft = false;      ///< left button held
  bool mouseRight = false;     ///< right button held
  bool mouseMiddle = false;    ///< middle button held
};

/** A window with an OpenGL 4.5 core context (GLFW). Requires a display (X11/Wayland, or Xvfb headless). */
class GlfwWindow : public GlContext {
public:
  /** Opens a window of `width`×`height` screen pixels; `visible` = false for tests. Throws on failure. */
  GlfwWindow(int width, int height, const std::string& title, bool visible = true,
             const ContextOptions& options = {});
  ~GlfwWindow() override;
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  void makeCurrent() override;
  std::string description() const override;
  /**
   * Shows the frame. When the environment variable SYLVA_FRAME_FILE names a file, the number of frames shown
   * so far is written there after each swap (atomically): GUI tests wait for drawn frames through it instead
   * of sleeping for a fixed time.
   */
  void swapBuffers() override;
  bool headless() const override { return false; }

  /** Processes events; returns false once the user asked to close the window. */
  bool pollEvents();
  /** Framebuffer size in pixels (may differ from window size on HiDPI). */
  glm::ivec2 framebufferSize() const;
  /** This frame's input (updated by pollEvents()). */
  const InputState& input() const { return mInput; }
  /** True while `key` (GLFW_KEY_*) is held. */
  bool keyDown(int key) const;
  /** Called on key press with the GLFW key code. */
  void setKeyCallback(std::function<void(int key, int mods)> callback) { mKeyCallback = std::move(callback); }
  /** Waits for the display's vertical refresh on swapBuffers() (true) or not. */
  void setVsync(bool enabled);
  /** The underlying GLFW handle, for the ImGui backend only. */
  GLFWwindow* handle() const { return mWindow; }

private:
  GLFWwindow* mWindow = nullptr;
  InputState mInput;
  std::function<void(int, int)> mKeyCallback;
  std::uint64_t mFramesShown = 0;
  std::string mFrameFile;
};

/** True when GLFW can connect to a display (DISPLAY or WAYLAND_DISPLAY set and reachable). */
bool displayAvailable();

} // namespace sylva::platform
