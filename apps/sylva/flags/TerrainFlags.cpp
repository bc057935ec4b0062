#include "flags/TerrainFlags.hpp"

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace sylva::app {

terrain::CrackMethod parseCrackMethod(const std::string& name) {
  if (name == "paper") {
    return terrain::CrackMethod::PaperSearch;
  }
  if (name == "ours") {
    return terrain::CrackMethod::RestrictedLevelMap;
  }
  if (name == "none") {
    return terrain::CrackMethod::None;
  }
  fail("--method: unknown crack method '{}' (expected paper, ours or none)", name);
}

terrain::TerrainView parseTerrainView(const std::string& name) {
  if (name == "shaded") {
    return terrain::TerrainView::Shaded;
  }
  if (name == "lod") {
    return terrain::TerrainView::LodColours;
  }
  if (name == "normals") {
    return terrain::TerrainView::Normals;
  }
  if (name == "splat") {
    return terrain::TerrainView::Splat;
  }
  fail("--view: unknown view '{}' (expected shaded, lod, normals or splat)", name);
}

void SeaLevelFlag::add(CLI::App& command) {
  command
      .add_option(
          "--sea-level", text,
          "Sea level in metres, 'auto' (0 m when heights go below 0 m, else none) or 'none': water is "
          "drawn there and the default splat rules put sand on the coast and no grass under water")
      ->capture_default_str();
}

terrain::SeaLevelRule SeaLevelFlag::rule() const {
  terrain::SeaLevelRule rule;
  if (text == "auto") {
    return rule;
  }
  if (text == "none") {
    rule.kind = terrain::SeaLevelRule::Kind::None;
    return rule;
  }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value) || std::abs(value) > 1.0e5) {
    fail("--sea-level: expected metres in [-100000, 100000], 'auto' or 'none', got '{}'", text);
  }
  rule.kind = terrain::SeaLevelRule::Kind::Metres;
  rule.metres = static_cast<float>(value);
  return rule;
}

namespace {

/** "X,Y,Z" → a point in metres; throws naming the option. */
glm::vec3 parseVec3(const std::string& option, const std::string& text) {
  const std::vector<float> v = parseNumbers(option, text, 3, "X,Y,Z in metres");
  return {v[0], v[1], v[2]};
}

} // namespace

void CameraFlags::add(CLI::App& command) {
  command
      .add_option("--view-from", viewFrom,
                  "Frame the whole terrain from this side: south-west, south, south-east, east, north-east, "
                  "north, north-west, west or top (north is row 0 of the DEM)")
      ->check(CLI::IsMember(render::viewFromNames()))
      ->capture_default_str();
  fovOption = command.add_option("--fov", fovDegrees, "Vertical field of view, degrees")
                  ->check(finiteRange(1.0, 150.0))
                  ->capture_default_str();
  command.add_option("--camera-pos", cameraPos,
                     "Camera position X,Y,Z in metres (x east, y height in the data's metres, z south; "
                     "default: framed by --view-from)");
  command.add_option("--look-at", lookAt,
                     "Point to look at X,Y,Z in metres (default: the centre of the terrain)");
  command
      .add_option("--fog", fog,
                  "Fog at the far side of the terrain, 0 (none) to 0.95; scales with the terrain's size")
      ->check(finiteRange(0.0, 0.95))
      ->capture_default_str();
}

void CameraFlags::check() const {
  if (!cameraPos.empty()) {
    (void)parseVec3("--camera-pos", cameraPos);
  }
  if (!lookAt.empty()) {
    (void)parseVec3("--look-at", lookAt);
  }
  if (!cameraPos.empty() && !lookAt.empty() &&
      parseVec3("--camera-pos", cameraPos) == parseVec3("--look-at", lookAt)) {
    fail("--camera-pos and --look-at: the same point ({}); the camera needs a direction", cameraPos);
  }
}

scene::CameraPlacement CameraFlags::placement() const {
  check();
  scene::CameraPlacement p;
  p.viewFrom = viewFrom;
  p.fovDegrees = fovDegrees;
  if (!cameraPos.empty()) {
    p.position = parseVec3("--camera-pos", cameraPos);
  }
  if (!lookAt.empty()) {
    p.lookAt = parseVec3("--look-at", lookAt);
  }
  return p;
}

render::Camera CameraFlags::camera(const terrain::TerrainScene& scene, float aspect) const {
  return scene::placedCamera(scene, placement(), aspect);
}

void TerrainFlags::add(CLI::App& command) {
  source.add(command);
  command
      .add_option("--exaggeration", exaggeration,
                  "Vertical exaggeration: heights are drawn x this (splat rules, sea level and camera "
                  "heights stay in true metres)")
      ->check(finiteRange(0.01, 1000.0))
      ->capture_default_str();
  seaLevel.add(command);
  command
      .add_option("--layers", layers,
                  "Splat layer rules (JSON); default: sand/grass/snow/rock by height and slope")
      ->check(CLI::ExistingFile);
  command
      .add_option("--method", method,
                  "Crack removal: paper (quadtree search), ours (restricted level map), none")
      ->check(CLI::IsMember({"paper", "ours", "none"}))
      ->capture_default_str();
  command.add_option("--tess", quadtree.patchTessLevel, "Base tessellation level per patch edge (1..32)")
      ->check(CLI::Range(1, terrain::kMaxPatchTessLevel))
      ->capture_default_str();
  command
      .add_option("--roots", rootCount,
                  "Number of quadtree roots (e.g. 4, 16, 32, 64; default: 4 across the longer side)")
      ->check(CLI::Range(1, 4096));
  maxDepthOption =
      command
          .add_option("--max-depth", quadtree.maxDepth,
                      "Deepest quadtree level (default: leaves whose vertices are half a sample apart)")
          ->check(CLI::Range(0, 16));
  command.add_option("--lod-factor", quadtree.lodDistanceFactor, "Split when distance < factor x node size")
      ->check(finiteRange(terrain::kMinRestrictedLodFactor, 64.0))
      ->capture_default_str();
  command
      .add_option(
          "--lod-error", quadtree.lodErrorPixels,
          "Screen-space-error LOD: split a patch while its geometric error projects to more than this "
          "many pixels (e.g. 1; --lod-factor is then unused); 0 = distance LOD")
      ->check(finiteRange(0.0, 1000.0))
      ->capture_default_str();
  command.add_flag("--terrain-geomorph,!--no-terrain-geomorph", geomorph,
                   "Geomorphing: terrain heights blend between LOD levels by distance, so patches do not pop "
                   "when they split or merge (default: off; not with --lod-error, whose splits change at most "
                   "that many pixels)");
}

std::string terrainOption(std::string_view field) {
  if (field == "tess_level") {
    return "--tess";
  }
  if (field == "relief") {
    return "--height-scale";
  }
  std::string option = "--" + std::string(field);
  std::replace(option.begin(), option.end(), '_', '-');
  return option;
}

terrain::TerrainSetup TerrainFlags::layout() const {
  terrain::TerrainSetup s;
  s.quadtree = quadtree;
  s.quadtree.method = parseCrackMethod(method);
  s.roots = rootCount;
  if (maxDepthOption != nullptr && maxDepthOption->count() > 0) {
    s.maxDepth = quadtree.maxDepth;
  }
  return s;
}

terrain::TerrainSetup TerrainFlags::setup() const {
  terrain::TerrainSetup s = layout();
  s.layersFile = layers;
  s.seaLevel = seaLevel.rule(); // a malformed --sea-level fails before the heights are loaded
  s.source = source.terrainSource();
  s.exaggeration = exaggeration;
  s.geomorph = geomorph;
  return s;
}

terrain::QuadtreeConfig TerrainFlags::configFor(const terrain::HeightField& field) const {
  return terrain::quadtreeFor(layout(), field, terrainOption);
}

std::unique_ptr<terrain::TerrainScene> TerrainFlags::build(const shader::Library& library) const {
  return terrain::TerrainScene::fromSetup(library, setup(), terrainOption);
}

} // namespace sylva::app
