#pragma once
// The options `sylva render` and `sylva view` share to describe a world without a scene file: terrain,
// camera, grass, simulation and forest. They fill a scene description the engine builds (scene::SceneWorld),
// so a render, the viewer and a scene file draw through the same frame.

#include <sylva/render/Camera.hpp>
#include <sylva/scene/SceneFile.hpp>

#include "flags/GrassFlags.hpp"
#include "flags/GrassSim.hpp"
#include "flags/TerrainFlags.hpp"
#include "flags/TreeFlags.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace sylva::scene {
class SceneWorld;
}

namespace sylva::app {

/** The terrain, camera, grass, simulation and forest options, and the world and start camera they describe.
 */
struct WorldFlags {
  TerrainFlags terrain;
  CameraFlags camera;
  GrassFlags grass;
  SimulationFlags simulation;
  TreeFlags trees;

  /** Adds the terrain, camera, grass, simulation and forest options, in that order. */
  void add(CLI::App& command);
  /**
   * Throws naming the option when a value or a combination is wrong, before any work (--physics needs
   * --grass). `everything`: also checks the settings of subsystems not asked for (the viewer's panels can
   * turn them on later).
   */
  void check(bool everything) const;
  /**
   * The world the options describe: the terrain, a grass layer with --grass (simulated with --physics), a
   * forest with --trees, the wind and the fog. Errors while building it name the options; its path is
   * "sylva <command>". `simulation`: the simulation settings even without --physics (the viewer starts one
   * on demand).
   */
  scene::SceneDesc desc(const std::string& command, bool simulation) const;
  /**
   * The first camera on `world` (built from desc()) for `aspect` (width / height): --camera-pos/--view-from,
   * or without --camera-pos the ground-level grass camera (--grass) or the forest camera (--trees). With
   * --physics drops the balls into `world` near that camera and, without --camera-pos, watches them roll.
   */
  render::Camera start(scene::SceneWorld& world, float aspect) const;
};

} // namespace sylva::app
