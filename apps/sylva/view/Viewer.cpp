// `sylva view`: one window loop for scene files, the options' world and the demo scene (Viewer.hpp).
#include "view/Viewer.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/gpu/DemoScene.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/CameraPath.hpp>
#include <sylva/scene/Quality.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>
#include <sylva/ui/CameraRig.hpp>
#include <sylva/ui/WindowShell.hpp>

#include "view/ViewerPanels.hpp"

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

constexpr int kPassCount = static_cast<int>(scene::Pass::Count);

/** What a viewer shows: a world (scene file or options) or the demo scene, and where it starts. */
struct ViewerContent {
  std::unique_ptr<scene::SceneWorld> world;
  std::unique_ptr<render::DemoScene> demo;
  /** The first camera when the world has no file cameras (orbit from there). */
  render::Camera start;
  /** Scene seconds of the first frame. */
  double time = 1.0;
  /** The options the world was described by (the sections' defaults for what they add); null: a file. */
  const WorldFlags* flags = nullptr;
};

/** The scene panel's world lines: pass toggles, trees and bodies, GPU memory. */
void passToggles(scene::SceneWorld& world) {
  ImGui::Text("trees %zu   bodies %zu   GPU memory %.1f MB", world.treeCount(), world.bodies(),
              static_cast<double>(world.gpuBytes()) / 1e6);
  scene::ScenePasses& passes = world.passes();
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
}

/** The viewer's quality: the governor's step (auto) or one chosen in the panel or on the command line. */
struct ViewerQuality {
  bool automatic = true;
  int manual = 0;
  int shown = 0; ///< the step the last frame was drawn at (logged when it changes)
  scene::QualityGovernor governor;

  explicit ViewerQuality(const ViewerOptions& o) : governor(settings(o)) {
    const bool repeatable = o.fixedStep > 0.0 || !o.screenshot.empty();
    const std::string& q = o.quality.empty() ? std::string(repeatable ? "full" : "auto") : o.quality;
    automatic = q == "auto";
    manual = q == "auto" || q == "full" ? 0 : std::stoi(q);
  }
  static scene::GovernorSettings settings(const ViewerOptions& o) {
    scene::GovernorSettings s;
    s.targetMs = 1000.0 / o.targetFps;
    return s;
  }
  int step() const { return automatic ? governor.step() : manual; }
  /** The panel's lines: the auto checkbox, the step and what it gives up. */
  void show(glm::ivec2 output) {
    const int last = static_cast<int>(scene::qualityLadder().size()) - 1;
    if (ImGui::Checkbox("auto quality (R)", &automatic) && automatic) {
      governor.reset(manual);
    }
    ImGui::SameLine();
    int s = step();
    ImGui::BeginDisabled(automatic);
    ImGui::SetNextItemWidth(120.0f);
    if (ImGui::SliderInt("step", &s, 0, last, "%d", ImGuiSliderFlags_AlwaysClamp)) {
      manual = s;
    }
    ImGui::EndDisabled();
    const scene::QualityStep& q = scene::qualityLadder()[static_cast<std::size_t>(step())];
    const glm::ivec2 drawn = scene::renderSize(output, q.renderScale);
    ImGui::Text("quality: %s (%d×%d)", scene::describe(q).c_str(), drawn.x, drawn.y);
  }
};

/**
 * The window loop: `build` makes the content once the window (and its GL context) exists. Keys: F5 reload
 * shaders, F fly, G walk, B throw a ball, Space pause, 1-8 passes, R auto quality, Tab panel, Esc quit.
 */
void runViewer(const ViewerOptions& o, const std::string& title,
               const std::function<ViewerContent(const shader::Library&, float aspect)>& build) {
  ui::ShellOptions shellOptions;
  shellOptions.width = o.width;
  shellOptions.height = o.height;
  shellOptions.title = title;
  shellOptions.frames = o.frames;
  shellOptions.screenshot = o.screenshot;
  shellOptions.fixedStep = o.fixedStep;
  shellOptions.panelShown = !o.noUi;
  shellOptions.logName = "viewer";
  ui::WindowShell shell(shellOptions);
  const shader::Library library(o.shaderDir); // outlives the world (it rebuilds its simulation from it)
  const float startAspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  ViewerContent content = build(library, startAspect);
  scene::SceneWorld* world = content.world.get();
  render::DemoScene* demo = content.demo.get();

  double time = content.time;
  double end = time;
  std::vector<std::string> cameraNames;
  std::optional<TerrainPanel> terrainPanel;
  std::optional<GrassPanel> grassPanel;
  std::optional<TreesPanel> treesPanel;
  const WorldFlags defaults;
  if (world != nullptr) {
    for (const auto& [name, path] : world->desc().cameras) {
      cameraNames.push_back(name);
    }
    end = std::max(end, scene::timelineEnd(world->desc()));
    const WorldFlags& flags = content.flags != nullptr ? *content.flags : defaults;
    terrainPanel.emplace(*world);
    grassPanel.emplace(*world, flags);
    treesPanel.emplace(*world, flags.trees);
    // A scene file opens with its sections closed (the panel stays short over the view); the options' world
    // with the sections of what they turned on open (the terrain's alone).
    grassPanel->open = grassPanel->open && content.flags != nullptr;
    treesPanel->open = treesPanel->open && content.flags != nullptr;
    terrainPanel->open = content.flags != nullptr && !grassPanel->open && !treesPanel->open;
  }
  ui::CameraRig::World answers;
  if (world != nullptr) {
    answers.namedCamera = [&](const std::string& name, float aspect) {
      return world->camera(name, time, aspect);
    };
    answers.groundHeight = [world](float x, float z) { return world->groundHeight(x, z); };
  }
  ui::CameraRig rig(cameraNames, world != nullptr ? world->desc().output.camera : std::string(),
                    content.start, answers, startAspect);
  if (world != nullptr) {
    // Zoom out until the whole terrain is a small part of the view, in until a few samples fill it.
    const Aabb box = world->terrain().bounds();
    const terrain::HeightField& field = world->terrain().field();
    rig.setOrbitLimits(std::max(0.5f, 2.0f * std::min(field.spacingX(), field.spacingZ())),
                       std::max(4.0f * rig.orbitDistance(), 2.0f * glm::length(box.max - box.min)));
  }
  rig.flySpeed = std::clamp(0.05f * rig.orbitDistance(), 10.0f, 200.0f);
  render::Camera camera = rig.camera();
  bool paused = false;
  bool throwRequested = false;
  bool reloadRequested = false;
  std::string status = world != nullptr
                           ? "F: fly  G: walk  B: throw a ball  Space: pause  1-8: passes  R: auto quality  "
                             "F5: reload shaders  Tab: panel"
                           : "F5: reload shaders  Space: pause  Tab: panel";
  bool wireframe = false; // the demo's
  ViewerQuality quality(o);

  shell.setKeyHandler([&](int key, int) {
    if (key == GLFW_KEY_F5) {
      reloadRequested = true;
    } else if (key == GLFW_KEY_F && rig.flyAllowed()) {
      rig.toggleFly();
    } else if (key == GLFW_KEY_G && rig.flyAllowed()) {
      rig.toggleWalk();
    } else if (key == GLFW_KEY_B) {
      throwRequested = world != nullptr; // thrown once the frame's camera is known
    } else if (key == GLFW_KEY_SPACE) {
      paused = !paused;
    } else if (key == GLFW_KEY_R && world != nullptr) {
      quality.automatic = !quality.automatic;
      if (quality.automatic) {
        quality.governor.reset(quality.manual);
      } else {
        quality.manual = quality.governor.step(); // stays where auto had it
      }
      log::info("auto quality {}", quality.automatic ? "on" : "off");
    } else if (key >= GLFW_KEY_1 && key < GLFW_KEY_1 + kPassCount && world != nullptr) {
      scene::ScenePasses& passes = world->passes();
      const auto pass = static_cast<scene::Pass>(key - GLFW_KEY_1);
      if (passes.present(pass)) {
        passes.setEnabled(pass, !passes.enabled(pass));
        log::info("pass {} {}", scene::passName(pass), passes.enabled(pass) ? "on" : "off");
      }
    } else {
      return false;
    }
    return true;
  });

  std::optional<render::RenderTarget> target;
  render::GpuTimers timers;
  shell.run([&](const ui::ShellFrame& f) {
    const double dt = f.dt;
    const glm::ivec2 size = f.size;
    const float aspect = f.aspect;
    if (reloadRequested) {
      reloadRequested = false;
      // From the source tree unless a directory was given: the point is editing shaders live.
      const shader::Library disk(o.shaderDir.empty() ? shader::Library::sourceDirectory()
                                                     : std::filesystem::path(o.shaderDir));
      try {
        if (world != nullptr) {
          world->reloadShaders(disk);
        } else {
          demo->reloadShaders(disk);
        }
        status = "shaders reloaded from " + disk.directory().string();
      } catch (const Error& e) {
        status = e.what();
        log::error("{}", e.what());
      }
    }

    // The camera: a file camera at the scene time, the orbit, or the fly/walk camera.
    camera = rig.update(shell.window().input(), ui::flyKeys(shell.window(), !rig.walking()),
                        !ImGui::GetIO().WantCaptureMouse, static_cast<float>(dt), aspect);
    if (!rig.named() && world != nullptr) {
      render::fitClipPlanes(camera, world->bounds()); // wherever the orbit or fly camera went
      if (grassPanel->active(*world)) {
        camera.nearPlane = std::min(camera.nearPlane, 0.05f); // blades right below the eye
      }
    }

    timers.beginFrame();
    if (throwRequested) {
      throwRequested = false;
      status = grassPanel->throwBall(*world, camera)
                   ? fmt::format("ball thrown: {} bodies", world->bodies())
                   : "B: no physics here (bodies need a grass layer: turn grass on)";
    }
    // The quality of this frame: the governor hears how long the last one took (real time, whatever the
    // clock).
    glm::ivec2 drawn = size;
    if (world != nullptr) {
      if (quality.automatic && f.index > 0) {
        quality.governor.update(1000.0 * f.wallDt);
      }
      const scene::QualityStep& step = scene::qualityLadder()[static_cast<std::size_t>(quality.step())];
      if (quality.step() != quality.shown) {
        log::info("quality step {}: {}", quality.step(), scene::describe(step));
        quality.shown = quality.step();
      }
      world->setQuality(step);
      drawn = scene::renderSize(size, step.renderScale);
    }
    if (!target || target->width() != drawn.x || target->height() != drawn.y) {
      target.emplace(drawn.x, drawn.y);
    }
    if (world != nullptr) {
      {
        const render::GpuTimerScope timed(&timers, "simulation");
        world->advanceTo(time);
      }
      target->begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      world->draw(camera, drawn.x, drawn.y, time, &target->depth(), &timers);
    } else {
      target->begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
      demo->render(camera, size.x, size.y, time, &timers, wireframe);
    }
    {
      const render::GpuTimerScope timed(&timers, "blit");
      ui::WindowShell::present(*target, drawn, size);
    }

    if (shell.panelShown()) {
      const render::GpuTimerScope timed(&timers, "ui");
      if (world != nullptr) {
        if (grassPanel->active(*world) && grassPanel->open) {
          grassPanel->counters = world->grass(0).readCounters();
        }
        treesPanel->readCounts(*world);
      }
      shell.beginUi();
      const float avg = ui::beginPanel("Sylva", shell.renderer(), shell.frameTimes());
      if (world != nullptr && content.flags == nullptr) {
        ImGui::Text("%s  (%s)", world->desc().name.c_str(),
                    std::filesystem::path(world->desc().path).filename().c_str());
      }
      ImGui::Text("frame %.2f ms (%.0f fps)", avg, avg > 0.0f ? 1000.0f / avg : 0.0f);
      if (world != nullptr) {
        quality.show(size);
        passToggles(*world);
        ImGui::Separator();
        rig.selector();
        ImGui::SameLine(118.0f);
      }
      ImGui::Checkbox("pause (Space)", &paused);
      float t = static_cast<float>(time);
      if (ImGui::SliderFloat("scene time (s)", &t, 0.0f, static_cast<float>(std::max(end, time)), "%.2f",
                             ImGuiSliderFlags_AlwaysClamp)) {
        time = t; // earlier: the simulations restart from time 0 and step there
      }
      if (world != nullptr) {
        ImGui::SliderFloat("fly speed (m/s)", &rig.flySpeed, 1.0f, 200.0f, "%.0f",
                           ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
        const float ground = world->groundHeight(camera.position.x, camera.position.z);
        ImGui::Text("camera %.0f, %.0f m, %.1f m above ground", camera.position.x, camera.position.z,
                    std::isnan(ground) ? 0.0f : camera.position.y - ground);
        terrainPanel->show(*world, camera, aspect, rig);
        grassPanel->show(*world);
        grassPanel->showSimulation(*world, camera);
        treesPanel->show(*world, timers);
      } else {
        ImGui::Checkbox("wireframe", &wireframe);
      }
      ImGui::Separator();
      if (ImGui::Button("reload shaders (F5)")) {
        reloadRequested = true;
      }
      ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 420.0f);
      ImGui::TextUnformatted(status.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopItemWidth();
      ImGui::End();
      // The timings in a window of their own, top right: the table's rows come and go with the passes.
      ImGui::SetNextWindowPos(ImVec2(static_cast<float>(size.x) - 10.0f, 10.0f), ImGuiCond_Always,
                              ImVec2(1.0f, 0.0f));
      ImGui::SetNextWindowBgAlpha(0.8f);
      ImGui::Begin("Timings", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
      std::vector<float> plot(shell.frameTimes().begin(), shell.frameTimes().end());
      ImGui::PlotLines("##frametimes", plot.data(), static_cast<int>(plot.size()), 0, nullptr, 0.0f, 50.0f,
                       ImVec2(220, 36));
      ui::passTimingTable(timers);
      ImGui::End();
      shell.endUi();
    }
    timers.endFrame();
    shell.setFrameNote(fmt::format(", scene time {:.3f} s", time));
    // The next frame shows a later time (the fixed step when scripted, so screenshots repeat; a long
    // real-time hitch counts as 0.1 s so the physics does not catch up at once).
    if (!paused) {
      time += f.fixedClock ? dt : std::min(dt, 0.1);
    }
  });
}

} // namespace

void viewSceneFile(const std::string& file, const ViewerOptions& options) {
  auto desc = std::make_shared<scene::SceneDesc>(scene::loadScene(file)); // errors before the window opens
  runViewer(options, fmt::format("Sylva viewer: {}", desc->name), [&](const shader::Library& library, float) {
    ViewerContent content;
    content.world = std::make_unique<scene::SceneWorld>(library, std::move(*desc));
    content.time = content.world->frameTime(content.world->desc().output.firstFrame);
    return content;
  });
}

void viewWorld(const WorldFlags& flags, const ViewerOptions& options) {
  runViewer(options, "Sylva viewer", [&](const shader::Library& library, float aspect) {
    ViewerContent content;
    content.world = std::make_unique<scene::SceneWorld>(library, flags.desc("view", true));
    content.start = flags.start(*content.world, aspect);
    scene::SceneDrawOptions draw;
    draw.grassView = flags.grass.grassView();
    draw.treeView = flags.trees.treeView();
    draw.treeLod = flags.trees.lod;
    content.world->setDrawOptions(draw);
    content.flags = &flags;
    return content;
  });
}

void viewDemo(const ViewerOptions& options) {
  runViewer(options, "Sylva viewer", [](const shader::Library& library, float) {
    ViewerContent content;
    content.demo = std::make_unique<render::DemoScene>(library);
    content.start = content.demo->defaultCamera();
    return content;
  });
}

} // namespace sylva::app
