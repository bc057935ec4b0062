#include "TerrainFlags.hpp"

#include <epoxy/gl.h>

#include <sylva/core/Error.hpp>
#include <sylva/core/Limits.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

namespace sylva::app {

terrain::QuadtreeConfig TerrainFlags::defaultQuadtree() {
  terrain::QuadtreeConfig config;
  config.rootSize = 512.0f;
  config.maxDepth = 5;
  config.lodDistanceFactor = 2.0f;
  config.patchTessLevel = 16;
  return config;
}

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

std::size_t affordableSamples() {
  // Unknown available memory (not Linux) = no limit beyond the loader's own.
  const std::optional<std::size_t> bytes = availableMemoryBytes();
  return bytes ? std::max<std::size_t>(4, *bytes / kRenderBytesPerSample) : terrain::kMaxHeightFieldSamples;
}

void checkMemoryFor(std::size_t samples, const std::string& option) {
  const std::size_t affordable = affordableSamples();
  if (samples > affordable) {
    fail("{}: {} samples need about {:.1f} GiB to render ({} bytes each: heights, GPU textures), {:.1f} GiB "
         "is available",
         option, samples, static_cast<double>(samples) * kRenderBytesPerSample / (1u << 30),
         kRenderBytesPerSample, static_cast<double>(affordable) * kRenderBytesPerSample / (1u << 30));
  }
}

void SeaLevelFlag::add(CLI::App& command) {
  command
      .add_option(
          "--sea-level", text,
          "Sea level in metres, 'auto' (0 m when heights go below 0 m, else none) or 'none': water is "
          "drawn there and the default splat rules put sand on the coast and no grass under water")
      ->capture_default_str();
}

std::optional<float> SeaLevelFlag::resolve(float minHeight) const {
  if (text == "auto") {
    return minHeight < 0.0f ? std::optional<float>(0.0f) : std::nullopt;
  }
  if (text == "none") {
    return std::nullopt;
  }
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value) || std::abs(value) > 1.0e5) {
    fail("--sea-level: expected metres in [-100000, 100000], 'auto' or 'none', got '{}'", text);
  }
  return static_cast<float>(value);
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

render::Camera CameraFlags::camera(const terrain::TerrainScene& scene, float aspect) const {
  check();
  const Aabb box = scene.bounds();
  const float fov = glm::radians(fovDegrees);
  const float e = scene.exaggeration();
  // Y is given in the data's metres; the scene is drawn with heights × exaggeration.
  const auto toWorld = [e](glm::vec3 p) { return glm::vec3(p.x, p.y * e, p.z); };
  const glm::vec3 target = lookAt.empty() ? box.center() : toWorld(parseVec3("--look-at", lookAt));
  render::Camera camera = render::frameBox(box, render::parseViewFrom(viewFrom), fov, aspect, target);
  if (!cameraPos.empty()) {
    camera.position = toWorld(parseVec3("--camera-pos", cameraPos));
    camera.up = glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 dir = glm::normalize(camera.target - camera.position);
    if (std::abs(dir.y) > 0.999f) {
      camera.up = glm::vec3(0.0f, 0.0f, -1.0f); // straight down or up: keep north at the top of the image
    }
  }
  // A camera inside or beyond the terrain still sees all of it between the clip planes.
  render::fitClipPlanes(camera, box);
  return camera;
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
  command.add_flag("--terrain-geomorph,!--no-terrain-geomorph", geomorph,
                   "Geomorphing: terrain heights blend between LOD levels by distance, so patches do not pop "
                   "when they split or merge (default: off)");
}

terrain::QuadtreeConfig TerrainFlags::configFor(const terrain::HeightField& field) const {
  terrain::QuadtreeConfig config = quadtree;
  if (rootCount > 0) {
    const terrain::QuadtreeConfig layout =
        terrain::QuadtreeConfig::forRootCount(rootCount, field.extentX(), field.extentZ());
    config.rootsX = layout.rootsX;
    config.rootsZ = layout.rootsZ;
    config.rootSize = layout.rootSize;
  } else {
    // Four roots across the longer side, whatever the terrain's size (the demo's 2048 m gives 512 m roots).
    config.rootSize = 0.25f * std::max(field.extentX(), field.extentZ());
  }
  if (maxDepthOption == nullptr || maxDepthOption->count() == 0) {
    // Deep enough that the finest leaves put two tessellated vertices per height sample, and no deeper: finer
    // leaves would only interpolate (the demo: 512 m roots, 2 m samples, level 16 → depth 5, 16 m leaves).
    const float spacing = std::min(field.spacingX(), field.spacingZ());
    const float leaf = 0.5f * spacing * static_cast<float>(config.patchTessLevel);
    config.maxDepth = std::clamp(static_cast<int>(std::round(std::log2(config.rootSize / leaf))), 0, 12);
  }
  config.method = parseCrackMethod(method);
  return config;
}

std::unique_ptr<terrain::TerrainScene> TerrainFlags::build(const shader::Library& library) const {
  terrain::TerrainSceneOptions options;
  options.geomorph = geomorph;
  if (!layers.empty()) {
    options.layers = terrain::loadSplatLayers(layers); // before loading: a bad rules file costs nothing
  }
  (void)seaLevel.resolve(0.0f); // a malformed --sea-level fails before the heights are loaded
  // Limits known before any work: the GPU's largest texture, and memory for a procedural field.
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  const std::string textureReason = fmt::format("the GPU's largest texture side is {}", maxTexture);
  if (source.procedural()) {
    if (source.size > maxTexture) {
      fail("--size {}: larger than the GPU's largest texture side ({}); use --size {} or less", source.size,
           maxTexture, maxTexture);
    }
    checkMemoryFor(static_cast<std::size_t>(source.size) * static_cast<std::size_t>(source.size), "--size");
  }
  terrain::LoadOptions limits = source.loadOptions();
  limits.maxSide = maxTexture;
  limits.maxSideReason = textureReason;
  limits.maxSamples = std::min(limits.maxSamples, affordableSamples());
  terrain::HeightField field = source.load(nullptr, &limits);
  const terrain::HeightFieldInfo info = terrain::heightFieldInfo(field);
  options.exaggeration = exaggeration;
  options.seaLevel = seaLevel.resolve(info.minHeight);
  const float relief = info.maxHeight - info.minHeight;
  const float extent = std::max(field.extentX(), field.extentZ());
  if (exaggeration == 1.0f && relief > 0.0f && relief < 0.002f * extent) {
    log::info(
        "relief {:.0f} m is {:.2g} % of the {:.0f} km extent and will look flat; try --exaggeration {:.0f}",
        relief, 100.0 * relief / extent, extent / 1000.0, std::ceil(0.02f * extent / relief));
  }
  const terrain::QuadtreeConfig config = configFor(field);
  std::optional<Progress> progress;
  if (field.samples().size() > kProgressSamples) {
    progress.emplace("building terrain (min/max tree, GPU normal and splat maps)", 1);
  }
  auto scene = std::make_unique<terrain::TerrainScene>(library, std::move(field), config, std::move(options));
  if (progress) {
    progress->advance();
  }
  return scene;
}

} // namespace sylva::app
