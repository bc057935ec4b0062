#include <sylva/ui/ImGuiLayer.hpp>

#include <sylva/core/Image.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <cstdio>

namespace sylva::ui {

ImGuiLayer::ImGuiLayer(platform::GlfwWindow& window) {
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window.handle(), true);
  ImGui_ImplOpenGL3_Init("#version 450 core");
}

ImGuiLayer::~ImGuiLayer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

void ImGuiLayer::begin() {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void ImGuiLayer::end() {
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

float beginPanel(const char* title, const std::string& renderer, const std::deque<float>& frameTimes) {
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

glm::vec3 flyKeys(const platform::GlfwWindow& window, bool vertical) {
  glm::vec3 move(0.0f);
  if (ImGui::GetCurrentContext() != nullptr && ImGui::GetIO().WantCaptureKeyboard) {
    return move;
  }
  const auto key = [&window](int k) { return window.keyDown(k) ? 1.0f : 0.0f; };
  move.z = key(GLFW_KEY_W) - key(GLFW_KEY_S);
  move.x = key(GLFW_KEY_D) - key(GLFW_KEY_A);
  if (vertical) {
    move.y = key(GLFW_KEY_E) - key(GLFW_KEY_Q);
  }
  return move;
}

void passTimingTable(const render::GpuTimers& timers) {
  if (!ImGui::BeginTable("passes", 3, ImGuiTableFlags_SizingFixedFit)) {
    return;
  }
  ImGui::TableSetupColumn("pass");
  ImGui::TableSetupColumn("CPU ms");
  ImGui::TableSetupColumn("GPU ms");
  ImGui::TableHeadersRow();
  for (const render::PassTiming& t : timers.lastFrame()) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(t.name.c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", t.cpuMs);
    ImGui::TableNextColumn();
    if (t.gpuMs >= 0.0) {
      ImGui::Text("%.3f", t.gpuMs);
    } else {
      ImGui::TextUnformatted("-");
    }
  }
  ImGui::EndTable();
}

void errorText(const std::string& message) {
  if (message.empty()) {
    return;
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 420.0f);
  ImGui::TextUnformatted(message.c_str());
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
}

void disabledTooltip(const char* text) {
  if (text != nullptr && *text != '\0' && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", text);
  }
}

} // namespace sylva::ui
