#include "TerrainFlags.hpp"

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>

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

void TerrainFlags::add(CLI::App& command) {
  source.add(command);
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
  terrain::HeightField field = source.load();
  std::vector<terrain::SplatLayer> rules;
  if (!layers.empty()) {
    rules = terrain::loadSplatLayers(layers);
  }
  const terrain::QuadtreeConfig config = configFor(field);
  return std::make_unique<terrain::TerrainScene>(library, std::move(field), config, std::move(rules));
}

} // namespace sylva::app
