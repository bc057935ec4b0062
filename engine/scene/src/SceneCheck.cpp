#include <sylva/scene/SceneCheck.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/scene/SceneForest.hpp>
#include <sylva/scene/SceneGrass.hpp>
#include <sylva/scene/SceneTerrain.hpp>
#include <sylva/scene/Shore.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/TerrainSetup.hpp>

#include <fmt/format.h>

#include <optional>

namespace sylva::scene {

namespace {

/** Runs `check`, appending its error to `errors`; true when it passed. */
template <class F> bool attempt(std::vector<std::string>& errors, const F& check) {
  try {
    check();
    return true;
  } catch (const Error& e) {
    errors.push_back(e.what());
    return false;
  }
}

} // namespace

SceneCheck checkScene(const std::filesystem::path& file) {
  SceneCheck result;
  SceneFileErrors read;
  SceneDesc scene;
  try {
    scene = parseSceneAll(readTextFile(file), file, read);
  } catch (const Error& e) {
    result.errors.push_back(e.what());
    return result;
  }
  result.errors = read.messages;
  result.cameras = scene.cameras.size();
  result.grass = scene.grass.size();
  result.forests = scene.forests.size();
  result.water = scene.water.size();
  const auto failed = [&read](const std::string& item) { return read.items.contains(item); };

  // What building the world checks, in its order, with its messages.
  std::optional<terrain::LoadedTerrain> terrain;
  attempt(result.errors, [&] {
    terrain = terrain::loadTerrainSetup(terrainSetup(scene.terrain), sceneFieldName(scene, "/terrain"));
  });
  attempt(result.errors, [&] { (void)simulatedGrassLayer(scene); });
  if (terrain) {
    result.terrainWidth = terrain->heights.width();
    result.terrainHeight = terrain->heights.height();
  }
  const float exaggeration = std::max(scene.terrain.exaggeration, 1e-6f);
  std::vector<terrain::SplatLayer> layers;
  if (terrain) {
    const terrain::HeightFieldInfo info = terrain::heightFieldInfo(terrain->heights);
    layers = terrain->layers.empty()
                 ? terrain::defaultSplatLayers(info.minHeight, info.maxHeight, terrain->seaLevel)
                 : terrain->layers;
  }
  for (std::size_t i = 0; i < scene.grass.size(); ++i) {
    if (failed(fmt::format("/grass/{}", i))) {
      continue;
    }
    const GrassLayer& layer = scene.grass[i];
    const GrassFieldName name = sceneFieldName(scene, fmt::format("/grass/{}", i));
    attempt(result.errors, [&] { (void)grassCullSettings(layer, name); });
    attempt(result.errors, [&] { (void)grassBladeTypes(layer, name); });
    if (terrain) {
      attempt(result.errors, [&] {
        (void)grassFieldSettings(
            layer, GrassGround{&terrain->heights, exaggeration, terrain->seaLevel, layers}, name);
      });
    }
  }
  for (std::size_t i = 0; i < scene.forests.size(); ++i) {
    if (failed(fmt::format("/forests/{}", i))) {
      continue;
    }
    const ForestDesc& forest = scene.forests[i];
    const FieldName name = sceneFieldName(scene, fmt::format("/forests/{}", i));
    const glm::vec2 footprint =
        terrain ? glm::vec2(terrain->heights.extentX(), terrain->heights.extentZ()) : glm::vec2(0.0f);
    attempt(result.errors, [&] {
      (void)forestSettings(forest, exaggeration, terrain ? terrain->seaLevel : std::nullopt, name, footprint,
                           terrain::snowLine(layers));
    });
    attempt(result.errors, [&] { (void)forestLook(forest, name); });
  }
  for (std::size_t i = 0; i < scene.water.size(); ++i) {
    if (failed(fmt::format("/water/{}", i))) {
      continue;
    }
    ShoreSettings settings;
    settings.band = scene.water[i].band;
    settings.tile = scene.water[i].tile;
    if (!scene.water[i].folding.empty()) {
      settings.folding = scene.water[i].folding;
    }
    attempt(result.errors, [&] {
      try {
        validate(settings);
        const folding::Project project = folding::loadProject(settings.folding);
        (void)folding::loadProjectImages(project, settings.folding);
      } catch (const Error& e) {
        fail("{}: /water/{}/folding: {}", scene.path, i, e.what());
      }
    });
  }
  return result;
}

} // namespace sylva::scene
