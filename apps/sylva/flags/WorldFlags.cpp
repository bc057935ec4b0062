#include "flags/WorldFlags.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/scene/Viewpoints.hpp>
#include <sylva/scene/gpu/StartView.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

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

namespace {

/** The true height whose product with `exaggeration` (as --camera-pos computes it, in float) is `drawn`. */
float trueHeight(float drawn, float exaggeration) {
  const float guess = drawn / exaggeration;
  float lo = guess;
  float hi = guess;
  for (int i = 0; i < 8; ++i) {
    if (lo * exaggeration == drawn) {
      return lo;
    }
    if (hi * exaggeration == drawn) {
      return hi;
    }
    lo = std::nextafter(lo, -std::numeric_limits<float>::infinity());
    hi = std::nextafter(hi, std::numeric_limits<float>::infinity());
  }
  return guess;
}

/**
 * Logs the camera a render uses as the options that render it again, byte for byte: floats with 9
 * significant digits (they read back as the same floats), Y in true metres, the drop point of the balls.
 */
void logCamera(const render::Camera& view, float exaggeration, float fovDegrees,
               std::optional<glm::vec2> drop) {
  log::info("camera: --camera-pos {:.9g},{:.9g},{:.9g} --look-at {:.9g},{:.9g},{:.9g} --fov {:.9g}{} (these "
            "options render this view again)",
            view.position.x, trueHeight(view.position.y, exaggeration), view.position.z, view.target.x,
            trueHeight(view.target.y, exaggeration), view.target.z, fovDegrees,
            drop ? fmt::format(" --balls-at {:.9g},{:.9g}", drop->x, drop->y) : std::string());
}

} // namespace

render::Camera WorldFlags::start(scene::SceneWorld& world, float aspect) const {
  scene::StartSettings settings;
  settings.camera = camera.placement();
  settings.windDirectionDegrees = grass.windDirection;
  if (simulation.enabled()) {
    settings.balls = simulation.balls;
    settings.ballSeed = simulation.seed;
    if (!simulation.ballsAt.empty()) {
      const std::vector<float> at = parseNumbers("--balls-at", simulation.ballsAt, 2, "X,Z in metres");
      settings.ballsAt = glm::vec2(at[0], at[1]);
    }
  }
  if (grass.enabled) {
    const grass::GrassField& field = world.grass(0).field();
    log::info("grass: {} blade types, {} tiles of {} m, about {:.3g} blades in the field, patch {:.2f} MB",
              field.types().size(), static_cast<long long>(field.layout().tilesX) * field.layout().tilesZ,
              field.layout().tileSize, field.estimateBlades(),
              static_cast<double>(grass::patchBytes(field.patch().size(), field.types().size())) / 1e6);
  }
  if (trees.enabled) {
    trees::ForestScene& forest = world.forest(0);
    log::info("trees: {} trees, {} pieces, {} joints, {}", forest.forest().trees.size(),
              forest.renderer().instances().instances.size(), forest.forest().jointCount,
              trees.wind ? "in the wind (--no-trees-wind: rest pose)" : "rest pose");
  }
  const scene::StartView view = scene::startView(world, settings, aspect);
  logCamera(view.camera, world.terrain().exaggeration(), camera.fovDegrees, view.dropCentre);
  return view.camera;
}

} // namespace sylva::app
