#include <sylva/folding_ui/Viewer.hpp>

#include <sylva/folding/ProjectFile.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/gpu/FoldRenderer.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/ui/ImageCanvas.hpp>
#include <sylva/ui/WindowShell.hpp>

#include <GLFW/glfw3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

namespace sylva::folding_ui {

namespace fs = std::filesystem;
using namespace sylva::folding;

void runViewer(const ViewerOptions& o) {
  const LoadedProject l = loadProjectFile(o.project);
  int index = imageIndexOption(l.project, "--image", o.image);
  const Textures textures = synthesizeLoaded(l);
  const glm::ivec2 first = textures.atlas.entries[static_cast<std::size_t>(index)].atlasRect().max -
                           textures.atlas.entries[static_cast<std::size_t>(index)].atlasRect().min;
  // Open at the image's size: small images zoomed up to about 960×720 (room for the panel), large ones
  // shrunk to fit a common screen.
  const double grow = std::max(1.0, std::min(960.0 / first.x, 720.0 / first.y));
  const double fit = std::min({grow, 1600.0 / first.x, 1000.0 / first.y});
  ui::ShellOptions shellOptions;
  shellOptions.width = std::max(480, static_cast<int>(first.x * fit));
  shellOptions.height = std::max(360, static_cast<int>(first.y * fit));
  shellOptions.title = "Sylva fold: " + fs::path(o.project).filename().string();
  shellOptions.frames = o.frames;
  shellOptions.screenshot = o.screenshot;
  shellOptions.fixedStep = o.fixedStep;
  shellOptions.panelShown = !o.noUi;
  ui::WindowShell shell(shellOptions);
  shader::Library library(o.shaderDir);
  folding::gpu::FoldRenderer renderer(library);
  renderer.upload(textures, l.project.profiles, l.project.jumpLayers);

  float speed = 1.0f;
  float shift = 0.0f;
  int function = 0; // 0: as in the project, else PositionFunction::Type(function - 1)
  bool paused = false;
  double t = 0.0;
  const double period = loopPeriod(l.project.profiles).seconds;
  const auto updateProfiles = [&] {
    PlaybackOptions playback;
    playback.shift = shift; // speed scales the clock below, so changing it never jumps the phase
    if (function > 0) {
      playback.function = static_cast<PositionFunction::Type>(function - 1);
    }
    renderer.setProfiles(applyPlayback(l.project.profiles, playback));
  };
  // The frame is drawn at the image's size and shown on a canvas filling the window (wheel: zoom, right or
  // middle drag: pan, Home: fit, +/-: zoom, 1: one texel per pixel).
  ui::ImageCanvas canvas;
  canvas.fitMargin = 0.0;
  canvas.fitOnWholePixels = true;
  canvas.fitZoom = o.zoom;
  canvas.showGrid = false; // a preview: the panel turns the grid on
  ui::CanvasImage frameImage;
  shell.setKeyHandler([&](int key, int) {
    if (key == GLFW_KEY_SPACE) {
      paused = !paused;
    } else if (key == GLFW_KEY_HOME) {
      canvas.requestFit();
    } else if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) {
      canvas.zoomAtCentre(2.0);
    } else if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) {
      canvas.zoomAtCentre(0.5);
    } else if (key == GLFW_KEY_1) {
      canvas.actualSize();
    } else {
      return false;
    }
    return true;
  });
  shell.run([&](const ui::ShellFrame& f) {
    if (!paused) {
      t += f.dt * speed;
    }
    const AtlasEntry& entry = textures.atlas.entries[static_cast<std::size_t>(index)];
    const Rect region = entry.atlasRect();
    frameImage.bindForDraw({region.width(), region.height()});
    renderer.draw(t, region);
    gl::bindDefaultFramebuffer(f.size.x, f.size.y);
    gl::clear(glm::vec4(0.12f, 0.12f, 0.13f, 1.0f));
    shell.beginUi();
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(f.size.x), static_cast<float>(f.size.y)));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.0f, 0.0f));
    ImGui::Begin("##frame", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoScrollWithMouse);
    ImGui::PopStyleVar();
    // draw() puts the region's first row at the top of the viewport, GL's last row: flipped on the way.
    canvas.drawPixelGrid(canvas.begin(frameImage.texture(), frameImage.size(), true));
    canvas.input();
    frameImage.showAt(canvas.view.zoom); // this frame's zoom: the texture is drawn when the frame ends
    ImGui::End();
    if (!shell.panelShown()) {
      shell.endUi();
      return;
    }
    shell.beginPanel(
        "Fold", fmt::format(", {}x{} at {:.0f}%", region.width(), region.height(), 100.0 * canvas.view.zoom));
    bool changed = false;
    ImGui::SliderFloat("speed", &speed, 0.0f, 4.0f, "%.2fx");
    changed |= ImGui::SliderFloat("shift (cycles)", &shift, 0.0f, 1.0f, "%.3f");
    const char* functions[] = {"as in the project", "linear", "piecewise", "exponential", "sigmoid", "sine"};
    changed |= ImGui::Combo("function", &function, functions, 6);
    float time = static_cast<float>(std::fmod(t, period));
    if (ImGui::SliderFloat("time (s)", &time, 0.0f, static_cast<float>(period), "%.3f")) {
      t = time;
      paused = true;
    }
    ImGui::Checkbox("pause (space)", &paused);
    ImGui::SameLine();
    ImGui::Checkbox("pixel grid", &canvas.showGrid);
    if (l.project.images.size() > 1) {
      std::vector<const char*> ids;
      for (const ImageEntry& e : l.project.images) {
        ids.push_back(e.id.c_str());
      }
      if (ImGui::Combo("image", &index, ids.data(), static_cast<int>(ids.size()))) {
        canvas.requestFit();
      }
    }
    if (changed) {
      updateProfiles();
    }
    ImGui::PopItemWidth();
    ImGui::End();
    shell.endUi();
  });
}

} // namespace sylva::folding_ui
