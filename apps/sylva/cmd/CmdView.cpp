// `sylva view`: its options; the viewer itself is Viewer.cpp.
#include "Commands.hpp"

#include <sylva/core/Error.hpp>

#include "view/Viewer.hpp"
#include "flags/WorldFlags.hpp"

#include <memory>
#include <string>

namespace sylva::app {

namespace {

struct ViewOptions {
  std::string file; ///< a scene file; empty: --scene
  std::string scene = "terrain";
  WorldFlags world;
  ViewerOptions window;
};

} // namespace

void registerView(CLI::App& app) {
  auto* command =
      app.add_subcommand("view", "Open the interactive viewer on a scene file (docs/scenes.md) or "
                                 "--scene (orbit: drag/right-drag/wheel; F: "
                                 "fly with WASD/QE; G: walk on the ground; "
                                 "B: throw a ball into the grass; F5: reload shaders)");
  auto o = std::make_shared<ViewOptions>();
  command
      ->add_option("file", o->file,
                   "A scene file (data/scenes/*.json): starts at its output camera; a checkbox per pass "
                   "(keys 1-8), its cameras, Space pauses, per-pass timings")
      ->check(CLI::ExistingFile);
  command->add_option("--scene", o->scene, "terrain, or demo (the small built-in pipeline test scene)")
      ->check(CLI::IsMember({"terrain", "demo"}))
      ->capture_default_str();
  o->world.add(*command);
  command->add_option("--width", o->window.width, "Window width")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  command->add_option("--height", o->window.height, "Window height")
      ->check(CLI::Range(64, 16384))
      ->capture_default_str();
  command
      ->add_option("--shader-dir", o->window.shaderDir,
                   "Load shaders from this directory (default: embedded; F5 reloads from the source tree)")
      ->check(CLI::ExistingDirectory);
  addScriptedWindowOptions(*command, o->window.frames, o->window.screenshot, o->window.fixedStep);
  command->add_flag("--no-ui", o->window.noUi, "Start with the ImGui panel hidden");
  command->callback([o] {
    if (!o->file.empty()) {
      if (o->world.grass.enabled || o->world.trees.enabled || o->world.simulation.enabled()) {
        fail("--grass, --trees and --physics: a scene file says what it holds ({})", o->file);
      }
      viewSceneFile(o->file, o->window);
      return;
    }
    // Checked even for what was not asked for: the panel can turn grass, trees and a simulation on.
    o->world.check(true);
    if (o->scene != "terrain") {
      if (o->world.grass.enabled) {
        fail("--grass: grass grows on a terrain (--scene terrain), not on the {} scene", o->scene);
      }
      if (o->world.trees.enabled) {
        fail("--trees: trees grow on a terrain (--scene terrain), not on the {} scene", o->scene);
      }
      viewDemo(o->window);
      return;
    }
    viewWorld(o->world, o->window);
  });
}

} // namespace sylva::app
