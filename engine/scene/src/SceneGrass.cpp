#include <sylva/scene/SceneGrass.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::scene {
namespace {

/** The drawn slope (degrees) of ground whose true slope is `degrees`, heights scaled by `exaggeration`. */
float drawnSlope(float degrees, float exaggeration) {
  if (degrees >= 90.0f) {
    return 90.0f;
  }
  constexpr double kRadians = std::numbers::pi / 180.0;
  return static_cast<float>(std::atan(std::tan(degrees * kRadians) * exaggeration) / kRadians);
}

} // namespace

GrassFieldName sceneGrassFieldName(const std::filesystem::path& file, std::size_t index) {
  return [file = file.string(), index](std::string_view field) {
    return fmt::format("{}: /grass/{}/{}", file, index, field);
  };
}

grass::CullSettings grassCullSettings(const GrassLayer& layer, const GrassFieldName& name) {
  grass::CullSettings c;
  if (layer.cull) {
    c = *layer.cull;
  } else {
    c.maxDistance = layer.distance;
    c.lodDistances = {0.2f * layer.distance, 0.55f * layer.distance};
    c.nearLayers = layer.nearLayers;
    c.nearDistance = layer.nearDistance;
  }
  c.farFade = std::min(c.farFade, 0.25f * c.maxDistance);
  c.orientationDistance = std::min(c.orientationDistance, c.maxDistance);
  try {
    grass::validate(c);
  } catch (const Error& e) {
    fail("{}: {}", fieldName(name, "distance"), e.what());
  }
  return c;
}

grass::FieldSettings grassFieldSettings(const GrassLayer& layer, const GrassGround& ground,
                                        const GrassFieldName& name) {
  if (ground.field == nullptr) {
    fail("grass: no terrain to grow on");
  }
  const terrain::HeightField& terrain = *ground.field;
  if (!(ground.exaggeration > 0.0f) || !std::isfinite(ground.exaggeration)) {
    fail("grass: the terrain's exaggeration must be > 0, got {}", ground.exaggeration);
  }
  if (!(layer.maxSlope >= 0.0f && layer.maxSlope <= 90.0f)) {
    fail("{}: {} is not in [0, 90] degrees", name("max_slope"), layer.maxSlope);
  }
  if (layer.bladesPerTile > layer.patchBlades) {
    fail("{}: {} is more than the patch's {} blades", name("blades_per_tile"), layer.bladesPerTile,
         layer.patchBlades);
  }
  grass::FieldSettings s;
  s.patch.blades = layer.patchBlades;
  s.patch.tileSize = layer.tileSize;
  s.patch.seed = layer.seed;
  s.bladesPerTile = layer.bladesPerTile;
  s.density.base = layer.density;
  s.density.coverage = layer.coverage;
  if (layer.noiseFrequency) {
    s.density.noiseFrequency = *layer.noiseFrequency;
  }
  s.density.seed = layer.seed + 1;
  s.density.verticalScale = ground.exaggeration;
  s.density.maxSlopeDegrees = drawnSlope(layer.maxSlope, ground.exaggeration);
  if (ground.seaLevel) {
    s.density.minHeight = (*ground.seaLevel + 0.3f) * ground.exaggeration;
    s.density.heightFade = 1.0f * ground.exaggeration;
  }
  if (!layer.paint.empty()) {
    auto image = std::make_shared<Image>(loadImage(layer.paint));
    if (image->width() < 2 || image->height() < 2) {
      fail("{}: {}: {}x{} pixels is too small (at least 2x2)", name("paint"), layer.paint, image->width(),
           image->height());
    }
    const double imageAspect = static_cast<double>(image->width()) / image->height();
    const double groundAspect = static_cast<double>(terrain.extentX()) / terrain.extentZ();
    if (std::abs(imageAspect / groundAspect - 1.0) > 0.02) {
      fail(
          "{}: {}: {}x{} pixels does not match the terrain's {:.0f} x {:.0f} m footprint (aspect {:.3f}, the "
          "image's {:.3f})",
          name("paint"), layer.paint, image->width(), image->height(), terrain.extentX(), terrain.extentZ(),
          groundAspect, imageAspect);
    }
    s.density.paint = std::move(image);
    s.density.paintMin = {0.0f, 0.0f};
    s.density.paintMax = {terrain.extentX(), terrain.extentZ()};
  }
  if (layer.layer != "none") {
    const auto it = std::find_if(ground.layers.begin(), ground.layers.end(),
                                 [&](const terrain::SplatLayer& l) { return l.name == layer.layer; });
    if (it == ground.layers.end()) {
      std::string names;
      for (const terrain::SplatLayer& l : ground.layers) {
        names += (names.empty() ? "" : ", ") + l.name;
      }
      fail("{}: the terrain has no splat layer '{}' (it has: {}; or 'none')", name("layer"), layer.layer,
           names.empty() ? "none" : names);
    }
    s.density.layer = *it;
  }
  return s;
}

int simulatedGrassLayer(const SceneDesc& scene) {
  int simulated = -1;
  for (std::size_t i = 0; i < scene.grass.size(); ++i) {
    if (scene.grass[i].simulate) {
      if (simulated >= 0) {
        fail("{}: /grass/{}/simulate: only one grass layer can be simulated (layer {} already is)",
             scene.path, i, simulated);
      }
      simulated = static_cast<int>(i);
    }
  }
  if ((!scene.bodies.empty() || !scene.drops.empty()) && simulated < 0) {
    fail("{}: /bodies: bodies need a grass layer with \"simulate\": true (the physics world moves the grass)",
         scene.path);
  }
  return simulated;
}

std::vector<grass::BladeType> grassBladeTypes(const GrassLayer& layer, const GrassFieldName& name) {
  if (layer.blades.empty()) {
    return grass::proceduralBladeTypes();
  }
  std::vector<grass::BladeType> types;
  for (const std::string& file : layer.blades) {
    try {
      std::vector<grass::BladeType> loaded = grass::loadBladeTypes(
          file, grass::BladeType{}.colour, grass::BladeType{}.stiffness, layer.extremeBlades);
      types.insert(types.end(), loaded.begin(), loaded.end());
    } catch (const Error& e) {
      fail("{}: {}", name("blades"), e.what());
    }
  }
  return types;
}

std::shared_ptr<const grass::GrassField> buildGrassField(const GrassLayer& layer, const GrassGround& ground,
                                                         const GrassFieldName& name) {
  const grass::FieldSettings settings = grassFieldSettings(layer, ground, name);
  return std::make_shared<grass::GrassField>(*ground.field, grassBladeTypes(layer, name), settings);
}

} // namespace sylva::scene
