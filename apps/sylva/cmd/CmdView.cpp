// `sylva view`: its options; the viewer itself is Viewer.cpp.
#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/scene/Quality.hpp>

#include "flags/StreamFlags.hpp"
#include "view/Viewer.hpp"
#include "flags/WorldFlags.hpp"

#include <memory>
#include <string>
#include <vector>

namespace sylva::app {

namespace {

/** auto, full and the ladder's steps by number. */
std::vector<std::string> qualityNames() {
  std::vector<std::string> names{"auto", "full"};
  for (std::size_t i = 0; i < scene::qualityLadder().size(); ++i) {
    names.push_back(std::to_string(i));
  }
  return names;
}

struct ViewOptions {
  std::string file; ///< a scene file; empty: --scene
  std::string scene = "terrain";
  WorldFlags world;
  StreamFlags stream;
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
  o->stream.add(*command);
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
  command
      ->add_option(
          "--quality", o->window.quality,
          "Frame quality of a scene: auto (steps resolution, grass distance and shadows down until "
          "frames reach --target-fps, and back up; shown in the panel, R toggles), full (the scene as "
          "described) or a step of the ladder by number, 0 being full (docs/scenes.md). Default: "
          "auto; full for runs with --fixed-step or --screenshot, so their frames repeat")
      ->check(CLI::IsMember(qualityNames()));
  command->add_option("--target-fps", o->window.targetFps, "Frames per second auto quality keeps to")
      ->check(CLI::Range(1.0, 240.0))
      ->capture_default_str();
  command->callback([o] {
    o->stream.check();
    if (o->stream.enabled()) {
      if (!o->file.empty() || o->world.grass.enabled || o->world.trees.enabled) {
        fail("--procedural-world and --pyramid draw streamed terrain alone (no scene file, --grass or "
             "--trees)");
      }
      viewStreamed(o->stream.source(o->world.terrain.source.seed), o->stream.options(), o->window);
      return;
    }
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
