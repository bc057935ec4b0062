#include "flags/WorldFlags.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/scene/Viewpoints.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::app {

void WorldFlags::add(CLI::App& command) {
  terrain.add(command);
  camera.add(command);
  grass.add(command);
  simulation.add(command);
  trees.add(command);
}

void WorldFlags::check(bool everything) const {
  camera.check();
  if (grass.enabled || everything) {
    grass.check();
  }
  if (simulation.enabled() && !grass.enabled) {
    fail("--physics: needs --grass (the bodies move through the grass field)");
  }
  if (trees.enabled || everything) {
    trees.check();
  }
  if (simulation.enabled() || everything) {
    (void)simulation.solverSettings();
    (void)simulation.poolSettings();
  }
}

scene::SceneDesc WorldFlags::desc(const std::string& command, bool withSimulation) const {
  scene::SceneDesc d;
  d.path = "sylva " + command;
  d.name = command;
  d.terrain.setup = terrain.setup();
  if (grass.enabled) {
    scene::GrassLayer layer = grass.layerDesc();
    layer.simulate = simulation.enabled();
    d.grass.push_back(layer);
  }
  if (trees.enabled) {
    d.forests.push_back(trees.forestDesc());
  }
  // The wind options blow along (cos a, sin a); a scene's direction is clockwise from north: a + 90°.
  d.wind.speed = grass.windSpeed;
  d.wind.direction = std::fmod(grass.windDirection + 90.0f, 360.0f);
  d.wind.gusts = grass.gusts;
  d.wind.seed = grass.windSeed;
  d.fog.farSide = camera.fog;
  if (simulation.enabled() || withSimulation) {
    d.grassSim = simulation.settings();
  }
  d.fieldNames = [](std::string_view pointer) -> std::string {
    const auto field = [&pointer](std::string_view prefix) {
      return pointer.substr(pointer.find('/', prefix.size()) + 1);
    };
    if (pointer.starts_with("/terrain/")) {
      return terrainOption(pointer.substr(std::string_view("/terrain/").size()));
    }
    if (pointer.starts_with("/grass/")) {
      return GrassFlags::option(field("/grass/"));
    }
    if (pointer.starts_with("/forests/")) {
      std::string option = "--trees-" + std::string(field("/forests/"));
      std::replace(option.begin(), option.end(), '_', '-');
      return option;
    }
    return std::string(pointer);
  };
  return d;
}

render::Camera WorldFlags::start(scene::SceneWorld& world, float aspect) const {
  terrain::TerrainScene& ground = world.terrain();
  render::Camera view = camera.camera(ground, aspect);
  const float fov = glm::radians(camera.fovDegrees);
  const bool placed = !camera.cameraPos.empty();
  if (grass.enabled) {
    const grass::GrassField& field = world.grass(0).field();
    log::info("grass: {} blade types, {} tiles of {} m, about {:.3g} blades in the field, patch {:.2f} MB",
              field.types().size(), static_cast<long long>(field.layout().tilesX) * field.layout().tilesZ,
              field.layout().tileSize, field.estimateBlades(),
              static_cast<double>(grass::patchBytes(field.patch().size(), field.types().size())) / 1e6);
    if (!placed) {
      view = scene::grassCamera(ground.field(), ground.bounds(), ground.maxHeight(), field, fov,
                                grass.windDirection);
      const float e = ground.exaggeration();
      log::info("grass: camera at {:.1f},{:.1f},{:.1f} looking at {:.1f},{:.1f},{:.1f} (--camera-pos, "
                "--look-at)",
                view.position.x, view.position.y / e, view.position.z, view.target.x, view.target.y / e,
                view.target.z);
    }
  }
  if (trees.enabled) {
    trees::ForestScene& forest = world.forest(0);
    log::info("trees: {} trees, {} pieces, {} joints, {}", forest.forest().trees.size(),
              forest.renderer().instances().instances.size(), forest.forest().jointCount,
              trees.wind ? "in the wind (--no-trees-wind: rest pose)" : "rest pose");
    if (!placed && !grass.enabled) {
      view = scene::forestCamera(ground.field(), ground.exaggeration(), ground.defaultCamera(),
                                 forest.forest(), fov);
    }
  }
  if (simulation.enabled()) {
    scene::BodyDrop drop;
    drop.centre = scene::ballDropPoint(ground.field(), world.grass(0).field(), view);
    drop.radius = 1.5f;
    drop.count = simulation.balls;
    drop.seed = simulation.seed;
    drop.height = 0.5f;
    world.addDrop(drop);
    if (!placed) {
      view = scene::ballCamera(ground.field(), ground.bounds(), drop.centre, fov);
    }
  }
  return view;
}

} // namespace sylva::app
