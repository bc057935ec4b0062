#pragma once
// The ui module (docs/engine.md): Dear ImGui bound to a GLFW window (the GLFW and OpenGL 3 backends) and the
// widgets the windowed commands share (the viewer-style panel, fly keys, the pass timing table). Their window
// loop is ui::WindowShell (WindowShell.hpp).

#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>

#include <glm/glm.hpp>

#include <deque>
#include <string>

namespace sylva::ui {

/** An ImGui context bound to `window` for its lifetime; torn down in reverse order. One per window. */
class ImGuiLayer {
public:
  /** Creates the ImGui context and its GLFW and OpenGL 3 backends for `window` (its context current). */
  explicit ImGuiLayer(platform::GlfwWindow& window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;
  /** Starts an ImGui frame (call after polling events). */
  void begin();
  /** Renders the frame's widgets into the bound framebuffer. */
  void end();
};

/**
 * Opens the viewer-style panel: top-left, translucent, sized to its content (labels are never cut off), 220
 * px controls, the GL renderer string first. Returns the mean of `frameTimes` (ms, 0 when empty). Close it
 * with ImGui::PopItemWidth() and ImGui::End().
 */
float beginPanel(const char* title, const std::string& renderer, const std::deque<float>& frameTimes);

/**
 * The fly keys as a move in camera axes (x right, y up, z forward, each −1, 0 or 1): W/S forward and back,
 * D/A right and left, E/Q up and down (with `vertical`; walking keeps to the ground). Zero while an ImGui
 * widget has the keyboard, so typing into the panel does not move the camera.
 */
glm::vec3 flyKeys(const platform::GlfwWindow& window, bool vertical = true);

/** The per-pass CPU and GPU milliseconds of `timers`' last complete frame as a table (GPU "-" until its
 * query has come back). */
void passTimingTable(const render::GpuTimers& timers);

/** Red text wrapped at 420 px for an error message (nothing when empty). */
void errorText(const std::string& message);

/** The last item's tooltip, shown even while it is disabled (nothing for null or empty `text`). */
void disabledTooltip(const char* text);

} // namespace sylva::ui
