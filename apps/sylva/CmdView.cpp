#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/DemoScene.hpp>
#include <sylva/render/GpuTimers.hpp>
#include <sylva/render/RenderTarget.hpp>

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <cstdio>
#include <deque>

namespace sylva::app {

namespace {

struct ViewOptions {
  int width = 1280;
  int height = 720;
  std::string shaderDir;
  int frames = 0;
  std::string screenshot;
  bool noUi = false;
  double fixedStep = 0.0;
};

/** ImGui context bound to a window; torn down in reverse order. */
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
  void begin() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
  }
  void end() {
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  }
};

void runViewer(const ViewOptions& o) {
  platform::GlfwWindow window(o.width, o.height, "Sylva viewer");
  window.setVsync(o.frames == 0);
  const gl::ContextInfo info = gl::queryContextInfo();
  shader::Library library(o.shaderDir);
  render::DemoSettings settings;
  render::DemoScene scene(library, settings);
  render::OrbitController orbit;
  orbit.distance = 0.55f * settings.worldSize;
  render::FlyController fly;
  bool flyMode = false;
  bool wireframe = false;
  bool paused = false;
  std::string status = "F5: reload shaders  F: fly/orbit  Tab: hide panel";
  bool showUi = !o.noUi;
  render::GpuTimers timers;
  render::FrameClock clock(o.fixedStep);
  std::deque<float> frameTimes;
  double sceneTime = 1.0;

  auto reload = [&] {
    // Reload from the source tree unless a directory was given: the point is editing shaders live.
    shader::Library disk(o.shaderDir.empty() ? shader::Library::sourceDirectory()
                                             : std::filesystem::path(o.shaderDir));
    try {
      scene.reloadShaders(disk);
      status = "shaders reloaded from " + disk.directory().string();
    } catch (const Error& e) {
      status = e.what();
      log::error("{}", e.what());
    }
  };
  window.setKeyCallback([&](int key, int) {
    if (ImGui::GetIO().WantCaptureKeyboard) {
      return;
    }
    if (key == GLFW_KEY_F5) {
      reload();
    } else if (key == GLFW_KEY_F) {
      flyMode = !flyMode;
    } else if (key == GLFW_KEY_TAB) {
      showUi = !showUi;
    } else if (key == GLFW_KEY_ESCAPE) {
      glfwSetWindowShouldClose(window.handle(), GLFW_TRUE);
    }
  });

  ImGuiLayer ui(window);
  int frame = 0;
  while (window.pollEvents()) {
    const double dt = clock.tick();
    if (!paused) {
      sceneTime += dt;
    }
    const glm::ivec2 size = window.framebufferSize();
    if (size.x == 0 || size.y == 0) {
      continue;
    }
    const platform::InputState& in = window.input();
    const bool mouseFree = !ImGui::GetIO().WantCaptureMouse;
    render::Camera camera = scene.defaultCamera();
    if (flyMode) {
      glm::vec3 move(0.0f);
      move.z += window.keyDown(GLFW_KEY_W) ? 1.0f : 0.0f;
      move.z -= window.keyDown(GLFW_KEY_S) ? 1.0f : 0.0f;
      move.x += window.keyDown(GLFW_KEY_D) ? 1.0f : 0.0f;
      move.x -= window.keyDown(GLFW_KEY_A) ? 1.0f : 0.0f;
      move.y += window.keyDown(GLFW_KEY_E) ? 1.0f : 0.0f;
      move.y -= window.keyDown(GLFW_KEY_Q) ? 1.0f : 0.0f;
      const bool look = mouseFree && in.mouseLeft;
      fly.update(move, look ? static_cast<float>(in.cursorDelta.x) : 0.0f,
                 look ? static_cast<float>(in.cursorDelta.y) : 0.0f, static_cast<float>(dt));
      fly.apply(camera);
    } else {
      if (mouseFree && in.mouseLeft) {
        orbit.rotate(static_cast<float>(in.cursorDelta.x), static_cast<float>(in.cursorDelta.y));
      }
      if (mouseFree && (in.mouseRight || in.mouseMiddle)) {
        orbit.pan(static_cast<float>(in.cursorDelta.x), static_cast<float>(in.cursorDelta.y));
      }
      if (mouseFree) {
        orbit.zoom(static_cast<float>(in.scrollDelta));
      }
      orbit.apply(camera);
      fly.position = camera.position; // switching to fly mode starts where the orbit camera is
    }

    timers.beginFrame();
    gl::bindDefaultFramebuffer(size.x, size.y);
    glEnable(GL_DEPTH_TEST);
    glClearColor(0.62f, 0.72f, 0.85f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    scene.render(camera, size.x, size.y, sceneTime, &timers, wireframe);
    if (showUi) {
      timers.begin("ui");
      ui.begin();
      ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
      ImGui::SetNextWindowBgAlpha(0.8f);
      ImGui::Begin("Sylva");
      ImGui::Text("%s", info.renderer.c_str());
      float sum = 0.0f;
      for (float t : frameTimes) {
        sum += t;
      }
      const float avg = frameTimes.empty() ? 0.0f : sum / static_cast<float>(frameTimes.size());
      ImGui::Text("frame %.2f ms (%.0f fps)", avg, avg > 0.0f ? 1000.0f / avg : 0.0f);
      std::vector<float> plot(frameTimes.begin(), frameTimes.end());
      ImGui::PlotLines("##frametimes", plot.data(), static_cast<int>(plot.size()), 0, nullptr, 0.0f, 50.0f,
                       ImVec2(260, 40));
      if (ImGui::BeginTable("passes", 3)) {
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
          ImGui::Text("%.3f", t.gpuMs);
        }
        ImGui::EndTable();
      }
      ImGui::Separator();
      ImGui::Checkbox("wireframe", &wireframe);
      ImGui::Checkbox("pause time", &paused);
      ImGui::Checkbox("fly camera (F)", &flyMode);
      if (ImGui::Button("reload shaders (F5)")) {
        reload();
      }
      ImGui::TextWrapped("%s", status.c_str());
      ImGui::End();
      ui.end();
      timers.end();
    }
    timers.endFrame();
    if (!o.screenshot.empty() && o.frames > 0 && frame + 1 == o.frames) {
      glFinish();
      glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
      saveImage(o.screenshot, render::readFramebuffer(size.x, size.y));
      std::printf("%s\n", o.screenshot.c_str());
    }
    window.swapBuffers();
    frameTimes.push_back(static_cast<float>(dt * 1000.0));
    if (frameTimes.size() > 120) {
      frameTimes.pop_front();
    }
    if (o.frames > 0 && ++frame >= o.frames) {
      break;
    }
  }
}

} // namespace

void registerView(CLI::App& app) {
  auto* command = app.add_subcommand(
      "view",
      "Open the interactive viewer (orbit: drag/right-drag/wheel; F: fly with WASD/QE; F5: reload shaders)");
  auto o = std::make_shared<ViewOptions>();
  command->add_option("--width", o->width, "Window width")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  command->add_option("--height", o->height, "Window height")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  command
      ->add_option("--shader-dir", o->shaderDir,
                   "Load shaders from this directory (default: embedded; F5 reloads from the source tree)")
      ->check(CLI::ExistingDirectory);
  command->add_option("--frames", o->frames, "Quit after this many frames (0: run until closed)")
      ->check(CLI::Range(0, 1000000));
  command->add_option("--screenshot", o->screenshot, "Save the last frame (with --frames) to this PNG");
  command->add_option("--fixed-step", o->fixedStep,
                      "Advance time by this many seconds per frame (deterministic)");
  command->add_flag("--no-ui", o->noUi, "Start with the ImGui panel hidden");
  command->callback([o] { runViewer(*o); });
}

} // namespace sylva::app
