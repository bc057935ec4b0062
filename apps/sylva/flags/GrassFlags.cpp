#include "flags/GrassFlags.hpp"

#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/scene/gpu/Ground.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <glm/geometric.hpp>

#include <cmath>

namespace sylva::app {

grass::FieldSettings GrassFlags::defaultField() {
  // The patch of a scene's grass layer (one set of defaults for files and options).
  const scene::GrassLayer layer;
  grass::FieldSettings f;
  f.patch.blades = layer.patchBlades;
  f.patch.tileSize = layer.tileSize;
  f.bladesPerTile = layer.bladesPerTile;
  return f;
}

grass::GrassView parseGrassView(const std::string& name) {
  if (name == "shaded") {
    return grass::GrassView::Shaded;
  }
  if (name == "lod") {
    return grass::GrassView::LodColours;
  }
  if (name == "tiles") {
    return grass::GrassView::Tiles;
  }
  fail("--grass-view: unknown view '{}' (expected shaded, lod or tiles)", name);
}

void GrassFlags::add(CLI::App& command) {
  command.add_flag("--grass", enabled, "Grow a grass field on the terrain (docs/grass.md)");
  command
      .add_option("--grass-types", types,
                  "Blade types: 'procedural' (meadow, fescue, broadleaf) or comma-separated blade-model "
                  "files from `sylva capture` (e.g. data/blades/slim.json)")
      ->capture_default_str();
  command.add_flag("--grass-extreme-blades", extremeBlades,
                   "Accept blade models outside the plausible 5 mm to 5 m long, 0.1 mm to 30 cm wide");
  command.add_option("--grass-blades", field.patch.blades, "Blades in the patch every tile draws from")
      ->check(CLI::Range(1, 1 << 22))
      ->capture_default_str();
  command.add_option("--grass-per-tile", field.bladesPerTile, "Blades a tile draws at full density")
      ->check(CLI::Range(1, 1 << 22))
      ->capture_default_str();
  command.add_option("--grass-tile", field.patch.tileSize, "Tile (and patch) side, metres")
      ->check(finiteRange(0.1, 1000.0))
      ->capture_default_str();
  command.add_option("--grass-density", field.density.base, "Overall density, 0..1")
      ->check(finiteRange(0.0, 1.0))
      ->capture_default_str();
  command
      .add_option("--grass-coverage", field.density.coverage,
                  "Fraction of the ground the Perlin density map covers, 0..1")
      ->check(finiteRange(0.0, 1.0))
      ->capture_default_str();
  command.add_option("--grass-seed", field.patch.seed, "Seed of the patch and (+1) of the density map")
      ->check(unsignedInteger())
      ->capture_default_str();
  command.add_option("--grass-paint", paint,
                     "Paint mask image (first channel 0..1) stretched over the terrain's footprint; "
                     "multiplies the density");
  command
      .add_option("--grass-layer", layer,
                  "Grow only where the terrain's splat layer of this name applies ('none': everywhere)")
      ->capture_default_str();
  command
      .add_option("--grass-max-slope", maxSlope,
                  "Steepest ground with grass, true degrees (before --exaggeration), faded over the last 8")
      ->check(finiteRange(0.0, 90.0))
      ->capture_default_str();
  command.add_option("--grass-distance", cull.maxDistance, "Draw distance of blades, metres")
      ->check(finiteRange(1.0, 100000.0))
      ->capture_default_str();
  command.add_option("--grass-lod", lod, "Distances (m) where blades drop to 8 and to 4 knots: A,B")
      ->capture_default_str();
  command
      .add_option(
          "--grass-near-layers", cull.nearLayers,
          "Tufts near the camera: up to this many blades per field blade, thinning out to the field's "
          "own density at --grass-near-distance (1: off)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  command
      .add_option("--grass-near-distance", cull.nearDistance,
                  "How far the near tufts reach, metres (never into the first LOD band)")
      ->check(finiteRange(0.0, 1000.0))
      ->capture_default_str();
  command.add_option("--grass-view", view, "Blade view: shaded, lod (level colours) or tiles")
      ->check(CLI::IsMember({"shaded", "lod", "tiles"}))
      ->capture_default_str();
  command
      .add_option("--wind-speed", windSpeed, "Mean wind speed, m/s (the wind of the grass and of the trees)")
      ->check(finiteRange(0.0, 60.0))
      ->capture_default_str();
  command
      .add_option("--wind-direction", windDirection,
                  "Direction the wind blows towards, degrees from east (+x) towards south (+z)")
      ->check(finiteRange(-360.0, 360.0))
      ->capture_default_str();
  command
      .add_option("--wind-gusts", gusts, "Gust strength: fraction of the mean speed added at a gust's peak")
      ->check(finiteRange(0.0, 10.0))
      ->capture_default_str();
  command.add_option("--wind-seed", windSeed, "Seed of the gust and turbulence patterns")
      ->check(unsignedInteger())
      ->capture_default_str();
}

grass::CullSettings GrassFlags::cullSettings() const {
  grass::CullSettings c = cull;
  const std::vector<float> d = parseNumbers("--grass-lod", lod, 2, "A,B in metres");
  c.lodDistances = {d[0], d[1]};
  c.farFade = std::min(c.farFade, 0.25f * c.maxDistance);
  c.orientationDistance = std::min(c.orientationDistance, c.maxDistance);
  try {
    grass::validate(c);
  } catch (const Error& e) {
    fail("--grass-lod/--grass-distance: {}", e.what());
  }
  return c;
}

void GrassFlags::check() const {
  (void)cullSettings();
  (void)parseGrassView(view);
  if (field.bladesPerTile > field.patch.blades) {
    fail("--grass-per-tile: {} is more than the patch's {} blades (--grass-blades)", field.bladesPerTile,
         field.patch.blades);
  }
}

wind::WindSettings GrassFlags::wind() const {
  wind::WindSettings w;
  const float a = glm::radians(windDirection);
  w.direction = {std::cos(a), std::sin(a)};
  w.speed = windSpeed;
  w.gustStrength = gusts;
  w.seed = windSeed;
  return w;
}

grass::GrassView GrassFlags::grassView() const {
  return parseGrassView(view);
}

scene::GrassLayer GrassFlags::layerDesc() const {
  scene::GrassLayer l;
  if (types != "procedural") {
    for (std::string& item : commaItems(types)) {
      if (!item.empty()) {
        l.blades.push_back(std::move(item));
      }
    }
    if (l.blades.empty()) {
      fail("--grass-types: no blade-model file in '{}'", types);
    }
  }
  l.density = field.density.base;
  l.coverage = field.density.coverage;
  l.seed = field.patch.seed;
  l.paint = paint;
  l.layer = layer;
  l.maxSlope = maxSlope;
  l.extremeBlades = extremeBlades;
  l.distance = cull.maxDistance;
  l.nearLayers = cull.nearLayers;
  l.nearDistance = cull.nearDistance;
  l.patchBlades = field.patch.blades;
  l.tileSize = field.patch.tileSize;
  l.bladesPerTile = field.bladesPerTile;
  l.cull = cullSettings();
  return l;
}

std::string GrassFlags::option(std::string_view field) {
  if (field == "blades") {
    return "--grass-types";
  }
  if (field == "blades_per_tile") {
    return "--grass-per-tile";
  }
  if (field == "max_slope") {
    return "--grass-max-slope";
  }
  return fmt::format("--grass-{}", field);
}

} // namespace sylva::app
