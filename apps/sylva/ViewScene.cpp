// `sylva view SCENE.json`: the interactive scene viewer (docs/scenes.md "Viewer"). The frame is drawn by
// SceneWorld exactly as `sylva render SCENE.json` draws it, into an offscreen target of the window's size (so
// the sun flare can test the depth), then blitted to the window under the ImGui panel.
#include "ViewScene.hpp"

#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/ui/ImGuiLayer.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/GpuTimers.hpp>
#include <sylva/render/RenderTarget.hpp>
#include <sylva/scene/SceneFile.hpp>

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

constexpr int kPassCount = static_cast<int>(scene::Pass::Count);
/** Eye height above the ground while walking (G), metres. */
constexpr float kEyeHeight = 1.8f;
/** Radius of a thrown ball (SceneWorld::spawnBall's), metres. */
constexpr float kBallRadius = 0.35f;

/** Seconds of the end of the scene's timeline: its output range or its longest camera path. */
double timelineEnd(const scene::SceneDesc& desc) {
  double end = static_cast<double>(desc.output.lastFrame + 1) / desc.output.fps;
  for (const auto& [name, camera] : desc.cameras) {
    if (!camera.keys.empty()) {
      end = std::max(end, camera.keys.back().time);
    }
  }
  return end;
}

/** Fly-controller angles and position that reproduce `camera`'s view. */
void syncFly(render::FlyController& fly, const render::Camera& camera) {
  fly.position = camera.position;
  const glm::vec3 d = glm::normalize(camera.target - camera.position);
  fly.yaw = std::atan2(d.x, d.z);
  fly.pitch = std::asin(std::clamp(d.y, -1.0f, 1.0f));
}

/** The viewer's state besides the world: the camera choice, time, toggles and messages. */
struct SceneViewer {
  std::vector<std::string> cameraNames; ///< the file's cameras; index size() is "free"
  int cameraIndex = 0;
  int lastFileCamera = 0; ///< where F goes back to from the free camera
  bool walk = false;
  float flySpeed = 15.0f; ///< metres per second
  float walkSpeed = 4.0f; ///< metres per second
  bool paused = false;
  double time = 0.0; ///< scene seconds
  bool showUi = true;
  bool throwRequested = false;
  bool reloadRequested = false;
  std::string status;

  bool free() const { return cameraIndex == static_cast<int>(cameraNames.size()); }
  /** The free (fly/walk) camera, starting from `current`. */
  void goFree(render::FlyController& fly, const render::Camera& current) {
    if (!free()) {
      lastFileCamera = cameraIndex;
      syncFly(fly, current);
      cameraIndex = static_cast<int>(cameraNames.size());
    }
  }
};

/**
 * Throws a ball from `camera`: 1 m ahead of the eye (at least resting on the ground when the camera looks
 * steeply down), 8 m/s along the view and 1 m/s up. Returns the status line.
 */
std::string throwBall(scene::SceneWorld& world, const render::Camera& camera) {
  const glm::vec3 forward = camera.forward();
  glm::vec3 at = camera.position + forward;
  const float ground = world.groundHeight(at.x, at.z);
  if (!std::isnan(ground)) {
    at.y = std::max(at.y, ground + kBallRadius);
  }
  if (!world.spawnBall(at, 8.0f * forward + glm::vec3(0.0f, 1.0f, 0.0f))) {
    return "B: this scene has no physics (bodies need a grass layer with \"simulate\": true)";
  }
  log::info("ball thrown at ({:.1f}, {:.1f}, {:.1f}) m: {} bodies", at.x, at.y, at.z, world.bodies());
  return fmt::format("ball thrown: {} bodies", world.bodies());
}

/** The per-pass CPU and GPU times of the last measured frame (GPU: "-" until its query has come back). */

} // namespace

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

void runSceneViewer(const SceneViewOptions& o) {
  const auto startup = std::chrono::steady_clock::now();
  scene::SceneDesc desc = scene::loadScene(o.file);
  platform::GlfwWindow window(o.width, o.height, fmt::format("Sylva viewer: {}", desc.name));
  window.setVsync(o.frames == 0);
  const gl::ContextInfo info = gl::queryContextInfo();
  const shader::Library library(o.shaderDir); // outlives the world (it rebuilds its simulation from it)
  scene::SceneWorld world(library, std::move(desc));
  scene::ScenePasses& passes = world.passes();

  SceneViewer v;
  for (const auto& [name, camera] : world.desc().cameras) {
    v.cameraNames.push_back(name);
  }
  v.cameraIndex =
      static_cast<int>(std::find(v.cameraNames.begin(), v.cameraNames.end(), world.desc().output.camera) -
                       v.cameraNames.begin());
  v.lastFileCamera = v.cameraIndex;
  v.time = world.frameTime(world.desc().output.firstFrame);
  v.showUi = !o.noUi;
  v.status = "F: fly  G: walk  B: throw a ball  Space: pause  1-8: passes  F5: reload shaders  Tab: panel";
  const double end = timelineEnd(world.desc());
  // Trees rise above the terrain's highest point: keep their crowns between the free camera's clip planes.
  Aabb box = world.terrain().bounds();
  box.max.y += 60.0f;

  render::FlyController fly;
  render::Camera camera = world.camera(v.cameraNames[static_cast<std::size_t>(v.cameraIndex)], v.time,
                                       static_cast<float>(o.width) / static_cast<float>(o.height));
  syncFly(fly, camera);

  window.setKeyCallback([&](int key, int) {
    if (ImGui::GetIO().WantCaptureKeyboard) {
      return;
    }
    if (key == GLFW_KEY_F5) {
      v.reloadRequested = true;
    } else if (key == GLFW_KEY_F) {
      if (v.free()) {
        v.cameraIndex = v.lastFileCamera;
        v.walk = false;
      } else {
        v.goFree(fly, camera);
      }
    } else if (key == GLFW_KEY_G) {
      v.goFree(fly, camera);
      v.walk = !v.walk;
    } else if (key == GLFW_KEY_B) {
      v.throwRequested = true; // thrown once the frame's camera is known
    } else if (key == GLFW_KEY_SPACE) {
      v.paused = !v.paused;
    } else if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + kPassCount) {
      const auto pass = static_cast<scene::Pass>(key - GLFW_KEY_1);
      if (passes.present(pass)) {
        passes.setEnabled(pass, !passes.enabled(pass));
        log::info("pass {} {}", scene::passName(pass), passes.enabled(pass) ? "on" : "off");
      }
    } else if (key == GLFW_KEY_TAB) {
      v.showUi = !v.showUi;
    } else if (key == GLFW_KEY_ESCAPE) {
      glfwSetWindowShouldClose(window.handle(), GLFW_TRUE);
    }
  });

  ui::ImGuiLayer ui(window);
  std::optional<render::RenderTarget> target;
  render::GpuTimers timers;
  render::FrameClock clock(o.fixedStep);
  std::deque<float> frameTimes;
  int frame = 0;
  long long shownFrames = 0;
  while (window.pollEvents()) {
    // Frame 0 shows the start time; later frames advance by the clock (the fixed step when scripted, so
    // screenshots repeat; a long real-time hitch counts as 0.1 s so the physics does not catch up at once).
    const double dt = clock.tick();
    const glm::ivec2 size = window.framebufferSize();
    if (size.x == 0 || size.y == 0) {
      continue;
    }
    const float aspect = static_cast<float>(size.x) / static_cast<float>(size.y);
    if (v.reloadRequested) {
      v.reloadRequested = false;
      // From the source tree unless a directory was given: the point is editing shaders live.
      const shader::Library disk(o.shaderDir.empty() ? shader::Library::sourceDirectory()
                                                     : std::filesystem::path(o.shaderDir));
      try {
        world.reloadShaders(disk);
        v.status = "shaders reloaded from " + disk.directory().string();
      } catch (const Error& e) {
        v.status = e.what();
        log::error("{}", e.what());
      }
    }

    // The camera: a file camera at the scene time, or the fly/walk camera.
    const platform::InputState& in = window.input();
    const bool mouseFree = !ImGui::GetIO().WantCaptureMouse;
    const glm::vec3 move = ui::flyKeys(window, !v.walk);
    const bool look = mouseFree && in.mouseLeft && (in.cursorDelta.x != 0.0 || in.cursorDelta.y != 0.0);
    if (move != glm::vec3(0.0f) || look) {
      v.goFree(fly, camera); // flying or looking around leaves the file's camera
    }
    if (v.free()) {
      fly.speed = v.walk ? v.walkSpeed : v.flySpeed;
      fly.update(move, look ? static_cast<float>(in.cursorDelta.x) : 0.0f,
                 look ? static_cast<float>(in.cursorDelta.y) : 0.0f, static_cast<float>(dt));
      if (v.walk) {
        const float ground = world.groundHeight(fly.position.x, fly.position.z);
        if (!std::isnan(ground)) {
          fly.position.y = ground + kEyeHeight;
        }
      }
      const float fovY = camera.fovY;
      camera = render::Camera{};
      fly.apply(camera);
      camera.fovY = fovY;
      render::fitClipPlanes(camera, box);
      if (!world.desc().grass.empty()) {
        camera.nearPlane = std::min(camera.nearPlane, 0.05f); // blades right below the eye
      }
    } else {
      camera = world.camera(v.cameraNames[static_cast<std::size_t>(v.cameraIndex)], v.time, aspect);
      syncFly(fly, camera); // flying starts where the file camera is
    }

    timers.beginFrame();
    if (v.throwRequested) {
      v.throwRequested = false;
      v.status = throwBall(world, camera);
    }
    timers.begin("simulation");
    world.advanceTo(v.time);
    timers.end();
    if (!target || target->width() != size.x || target->height() != size.y) {
      target.emplace(size.x, size.y);
    }
    target->begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    world.draw(camera, size.x, size.y, v.time, &target->depth(), &timers);
    timers.begin("blit");
    gl::blitToWindow(target->framebuffer(), size);
    timers.end();
    gl::bindDefaultFramebuffer(size.x, size.y);

    if (v.showUi) {
      timers.begin("ui");
      ui.begin();
      const float avg = ui::beginPanel("Sylva scene", info.renderer, frameTimes);
      ImGui::Text("%s  (%s)", world.desc().name.c_str(),
                  std::filesystem::path(world.desc().path).filename().c_str());
      ImGui::Text("frame %.2f ms (%.0f fps)", avg, avg > 0.0f ? 1000.0f / avg : 0.0f);
      ImGui::Text("trees %zu   bodies %zu   GPU memory %.1f MB", world.treeCount(), world.bodies(),
                  static_cast<double>(world.gpuBytes()) / 1e6);
      ImGui::Separator();
      if (ImGui::BeginTable("pass toggles", 4, ImGuiTableFlags_SizingFixedFit)) {
        for (int i = 0; i < kPassCount; ++i) {
          const auto pass = static_cast<scene::Pass>(i);
          if (!passes.present(pass)) {
            continue;
          }
          ImGui::TableNextColumn();
          bool on = passes.enabled(pass);
          if (ImGui::Checkbox(fmt::format("{} ({})", scene::passName(pass), i + 1).c_str(), &on)) {
            passes.setEnabled(pass, on);
          }
        }
        ImGui::EndTable();
      }
      ImGui::Separator();
      std::vector<const char*> labels;
      for (const std::string& name : v.cameraNames) {
        labels.push_back(name.c_str());
      }
      labels.push_back("free (F: fly, G: walk)");
      const int before = v.cameraIndex;
      if (ImGui::Combo("camera", &v.cameraIndex, labels.data(), static_cast<int>(labels.size()))) {
        if (v.free()) {
          v.cameraIndex = before; // goFree remembers the file camera it leaves
          v.goFree(fly, camera);
        } else {
          v.walk = false;
        }
      }
      if (ImGui::Checkbox("walk (G)", &v.walk) && v.walk) {
        v.goFree(fly, camera);
      }
      ImGui::SameLine(118.0f);
      ImGui::Checkbox("pause (Space)", &v.paused);
      float t = static_cast<float>(v.time);
      if (ImGui::SliderFloat("scene time (s)", &t, 0.0f, static_cast<float>(std::max(end, v.time)), "%.2f",
                             ImGuiSliderFlags_AlwaysClamp)) {
        v.time = t; // earlier: the simulations restart from time 0 and step there
      }
      ImGui::SliderFloat("fly speed (m/s)", &v.flySpeed, 1.0f, 200.0f, "%.0f",
                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
      const float ground = world.groundHeight(camera.position.x, camera.position.z);
      ImGui::Text("camera %.0f, %.0f m, %.1f m above ground", camera.position.x, camera.position.z,
                  std::isnan(ground) ? 0.0f : camera.position.y - ground);
      ImGui::Separator();
      if (ImGui::Button("reload shaders (F5)")) {
        v.reloadRequested = true;
      }
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 420.0f);
      ImGui::TextUnformatted(v.status.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopItemWidth();
      ImGui::End();
      // The timings in a window of their own, top right: the table's rows come and go with the passes.
      ImGui::SetNextWindowPos(ImVec2(static_cast<float>(size.x) - 10.0f, 10.0f), ImGuiCond_Always,
                              ImVec2(1.0f, 0.0f));
      ImGui::SetNextWindowBgAlpha(0.8f);
      ImGui::Begin("Timings", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
      std::vector<float> plot(frameTimes.begin(), frameTimes.end());
      ImGui::PlotLines("##frametimes", plot.data(), static_cast<int>(plot.size()), 0, nullptr, 0.0f, 50.0f,
                       ImVec2(220, 36));
      passTimingTable(timers);
      ImGui::End();
      ui.end();
      timers.end();
    }
    timers.endFrame();
    const bool last = ui::endWindowFrame(window, size, o.screenshot, o.frames, frame, dt, frameTimes);
    // One line a frame at debug level, once swapped: the GUI end-to-end test waits on it (frames take
    // seconds on llvmpipe).
    log::debug("scene viewer: frame {} shown, scene time {:.3f} s", shownFrames, v.time);
    if (shownFrames++ == 0) {
      log::info("scene viewer: first frame shown after {:.1f} s",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - startup).count());
    }
    if (last) {
      break;
    }
    if (!v.paused) {
      v.time += clock.fixed() ? dt : std::min(dt, 0.1);
    }
  }
}

} // namespace sylva::app
