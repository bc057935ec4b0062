// `sylva view --procedural-world` / `--pyramid DIR`: a window on streamed terrain (docs/terrain-data.md,
// "Streaming"). The engine's StreamedTerrain does the work; this file flies the camera and shows the budgets.
#include "view/Viewer.hpp"

#include <sylva/core/Log.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/gpu/StreamedTerrain.hpp>
#include <sylva/ui/CameraRig.hpp>
#include <sylva/ui/ImGuiLayer.hpp>
#include <sylva/ui/WindowShell.hpp>

#include <fmt/format.h>
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace sylva::app {

double streamViewDepth(const terrain::TileSource& source) {
  const terrain::PyramidInfo& l = source.layout();
  const double extent = std::max((l.width - 1) * static_cast<double>(l.spacingX),
                                 (l.height - 1) * static_cast<double>(l.spacingZ));
  return dynamic_cast<const terrain::ProceduralWorld*>(&source) != nullptr ? 30000.0 : 5.0 * extent;
}

render::Camera streamStartCamera(const terrain::TileSource& source, float fovY) {
  const terrain::PyramidInfo& l = source.layout();
  const double extentX = (l.width - 1) * static_cast<double>(l.spacingX);
  const double extentZ = (l.height - 1) * static_cast<double>(l.spacingZ);
  render::Camera c;
  c.fovY = fovY;
  if (const auto* world = dynamic_cast<const terrain::ProceduralWorld*>(&source)) {
    // A glider's view over the middle of the world: 250 m above the ground, looking ahead and down.
    const double x = 0.5 * extentX;
    const double z = 0.5 * extentZ;
    c.position = glm::vec3(static_cast<float>(x), world->heightAt(x, z) + 250.0f, static_cast<float>(z));
    c.target = c.position + glm::vec3(100.0f, -22.0f, 35.0f);
  } else {
    // The whole pyramid from the south-west, as `sylva render` frames a DEM.
    const glm::vec3 centre(static_cast<float>(0.5 * extentX), 0.5f * (l.minHeight + l.maxHeight),
                           static_cast<float>(0.5 * extentZ));
    const float size = static_cast<float>(std::max(extentX, extentZ));
    c.position = centre + glm::vec3(-0.55f * size, 0.45f * size + (l.maxHeight - l.minHeight), 0.55f * size);
    c.target = centre;
    c.nearPlane = std::max(0.5f, 1.0e-5f * size);
    c.farPlane = 3.0f * size + 10.0f * (l.maxHeight - l.minHeight);
    return c;
  }
  c.nearPlane = 0.5f;
  c.farPlane = 60000.0f;
  return c;
}

void viewStreamed(std::shared_ptr<const terrain::TileSource> source,
                  const terrain::StreamedTerrainOptions& streamOptions, const ViewerOptions& o) {
  ui::ShellOptions shellOptions;
  shellOptions.width = o.width;
  shellOptions.height = o.height;
  shellOptions.title = "Sylva viewer: streamed terrain";
  shellOptions.frames = o.frames;
  shellOptions.screenshot = o.screenshot;
  shellOptions.fixedStep = o.fixedStep;
  shellOptions.panelShown = !o.noUi;
  shellOptions.logName = "viewer";
  ui::WindowShell shell(shellOptions);
  const shader::Library library(o.shaderDir);
  terrain::StreamedTerrain terrain(library, source, streamOptions);
  log::info("streaming {}: GPU {} tiles ({:.0f} MB), RAM budget {:.0f} MB", source->describe(),
            terrain.layers(),
            static_cast<double>(terrain.layers()) * static_cast<double>(terrain.layerBytes()) / 1.0e6,
            static_cast<double>(streamOptions.ramBudget) / 1.0e6);
  const float startAspect = static_cast<float>(o.width) / static_cast<float>(o.height);
  const render::Camera start = streamStartCamera(*source, glm::radians(50.0f));
  ui::CameraRig::World answers;
  answers.groundHeight = [&terrain](float x, float z) { return terrain.drawnHeightAt(x, z); };
  ui::CameraRig rig({}, std::string(), start, answers, startAspect);
  rig.toggleFly(); // a world this size is for flying over
  rig.flySpeed = 300.0f;
  const double extent = std::max(terrain.layout().width, terrain.layout().height) *
                        static_cast<double>(terrain.layout().spacingX);
  bool levelColours = false;
  std::optional<render::RenderTarget> target;
  glm::dvec3 lastEye(start.position);
  bool completeLogged = false;
  shell.setKeyHandler([&](int key, int) {
    if (key == GLFW_KEY_L) {
      levelColours = !levelColours;
    } else if (key == GLFW_KEY_G) {
      rig.toggleWalk();
    } else {
      return false;
    }
    return true;
  });
  shell.run([&](const ui::ShellFrame& f) {
    render::Camera camera = rig.update(shell.window().input(), ui::flyKeys(shell.window(), !rig.walking()),
                                       !ImGui::GetIO().WantCaptureMouse, static_cast<float>(f.dt), f.aspect);
    camera.farPlane = static_cast<float>(std::clamp(extent * 1.5, 20000.0, 2.0e6));
    camera.nearPlane = std::max(0.5f, camera.farPlane * 1e-5f);
    const glm::dvec3 eye(camera.position);
    const glm::dvec3 velocity = f.dt > 0.0 ? (eye - lastEye) / f.dt : glm::dvec3(0.0);
    lastEye = eye;
    const terrain::StreamedFrame frame =
        terrain.update(eye, glm::dvec3(camera.target), velocity, camera.fovY, f.aspect, camera.farPlane);
    // Logged at each change from streaming to complete (GUI tests wait for it).
    if (!frame.waited && !completeLogged) {
      log::info("streamed view complete: {} tiles", frame.tiles);
    }
    completeLogged = !frame.waited;
    if (!target || target->width() != f.size.x || target->height() != f.size.y) {
      target.emplace(f.size.x, f.size.y);
    }
    const render::Environment environment =
        terrain::StreamedTerrain::wideEnvironment(streamViewDepth(*source));
    target->begin(terrain::StreamedTerrain::clearColour(environment));
    terrain.draw(terrain.relativeCamera(camera.fovY, camera.nearPlane, camera.farPlane), f.size.x, f.size.y,
                 shell.clock().time(),
                 levelColours ? terrain::StreamedView::LevelColours : terrain::StreamedView::Shaded,
                 environment);
    ui::WindowShell::present(*target, f.size, f.size);
    if (shell.panelShown()) {
      shell.beginUi();
      shell.beginPanel("Streamed terrain");
      ImGui::TextWrapped("%s", source->describe().c_str());
      ImGui::Separator();
      const terrain::StreamerStats s = terrain.streamer().stats();
      ImGui::Text("tiles drawn %d, %s", frame.tiles,
                  frame.waited ? fmt::format("waiting for {}", frame.missing).c_str() : "complete");
      ImGui::Text("GPU: %d of %d layers (%.0f MB)", frame.layersUsed, terrain.layers(),
                  static_cast<double>(terrain.layers()) * static_cast<double>(terrain.layerBytes()) / 1.0e6);
      ImGui::Text("RAM: %zu tiles, %.0f of %.0f MB", s.residentTiles,
                  static_cast<double>(s.residentBytes) / 1.0e6,
                  static_cast<double>(terrain.streamer().budget()) / 1.0e6);
      ImGui::Text("loaded %llu, evicted %llu, queued %zu", static_cast<unsigned long long>(s.loaded),
                  static_cast<unsigned long long>(s.evicted), s.queued);
      const float ground = terrain.drawnHeightAt(eye.x, eye.z);
      ImGui::Text("camera %.2f, %.2f km, %.0f m above ground", eye.x / 1000.0, eye.z / 1000.0,
                  std::isnan(ground) ? 0.0 : eye.y - ground);
      ImGui::Separator();
      ImGui::SliderFloat("fly speed (m/s)", &rig.flySpeed, 1.0f, 5000.0f, "%.0f",
                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
      ImGui::Checkbox("level colours (L)", &levelColours);
      ImGui::TextUnformatted("W/A/S/D/Q/E: fly, drag: look, G: walk, Tab: panel, Esc: quit");
      ImGui::PopItemWidth();
      ImGui::End();
      shell.endUi();
    }
    shell.setFrameNote(fmt::format(", {} tiles{}", frame.tiles, frame.waited ? " (streaming)" : ""));
  });
}

} // namespace sylva::app
