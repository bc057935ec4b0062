#pragma once

// Dear ImGui bound to a GLFW window (GLFW + OpenGL 3 backends), and the end of a frame, shared by the
// windowed commands (view, fold view).

#include <sylva/core/Image.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/RenderTarget.hpp>

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <cstdio>
#include <deque>
#include <string>

namespace sylva::app {

/** An ImGui context bound to `window` for its lifetime; torn down in reverse order. One per window. */
class ImGuiLayer {
public:
  explicit ImGuiLayer(platform::GlfwWindow& window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
  }
  ~ImGuiLayer() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;
  /** Starts an ImGui frame (call after polling events). */
  void begin() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
  }
  /** Renders the frame's widgets into the bound framebuffer. */
  void end() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }
};

/**
 * Opens the viewer-style panel: top-left, translucent, sized to its content (labels are never cut off), 220
 * px controls, the GL renderer string first. Returns the mean of `frameTimes` (ms, 0 when empty). Close it
 * with ImGui::PopItemWidth() and ImGui::End().
 */
inline float beginPanel(const char* title, const std::string& renderer, const std::deque<float>& frameTimes) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.8f);
  ImGui::Begin(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  ImGui::PushItemWidth(220.0f);
  ImGui::Text("%s", renderer.c_str());
  float sum = 0.0f;
  for (float ms : frameTimes) {
    sum += ms;
  }
  return frameTimes.empty() ? 0.0f : sum / static_cast<float>(frameTimes.size());
}

/**
 * Ends one frame of a windowed command: with `screenshot` set, saves the default framebuffer (size pixels)
 * after the last of `frames` scripted frames and prints its path; swaps; keeps the last 120 frame times (ms)
 * in `frameTimes`. Returns true when `frames` > 0 frames have been shown (the command should stop).
 */
inline bool endWindowFrame(platform::GlfwWindow& window, glm::ivec2 size, const std::string& screenshot,
                           int frames, int& frame, double dtSeconds, std::deque<float>& frameTimes) {
  if (!screenshot.empty() && frames > 0 && frame + 1 == frames) {
    gl::finish();
    gl::bindWindowFramebuffer();
    saveImage(screenshot, render::readFramebuffer(size.x, size.y));
    std::printf("%s\n", screenshot.c_str());
  }
  window.swapBuffers();
  frameTimes.push_back(static_cast<float>(dtSeconds * 1000.0));
  if (frameTimes.size() > 120) {
    frameTimes.pop_front();
  }
  return frames > 0 && ++frame >= frames;
}

} // namespace sylva::app
