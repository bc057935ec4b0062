#include "TreeFlags.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include "SourceOptions.hpp"

#include <glm/geometric.hpp>

#include <cmath>

namespace sylva::app {

trees::ForestSettings TreeFlags::defaultForest() {
  trees::ForestSettings f;
  f.species = {"almond", "quaking-aspen", "california-black-oak"};
  f.count = 60;
  f.seed = 3;
  f.spacing = 6.0f;
  f.maxSlope = 28.0f;
  return f;
}

void TreeFlags::add(CLI::App& command) {
  command.add_flag("--trees", enabled, "Grow a forest of piece-built trees on the terrain (docs/trees.md)");
  command
      .add_option("--trees-species", forest.species,
                  "Species mix: presets (sylva tree species) or species JSON files, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  command.add_option("--trees-count", forest.count, "Trees to place (fewer where the ground runs out)")
      ->check(CLI::Range(0, 1000000))
      ->capture_default_str();
  command.add_option("--trees-seed", forest.seed, "Seed of placement, topologies and poses")
      ->capture_default_str();
  command.add_option("--trees-spacing", forest.spacing, "Minimum distance between trunks, metres")
      ->check(finiteRange(0.0, 1000.0))
      ->capture_default_str();
  command.add_option("--trees-max-slope", forest.maxSlope, "Steepest ground a tree grows on, degrees")
      ->check(finiteRange(0.0, 90.0))
      ->capture_default_str();
  command.add_option("--trees-pixels", lod.pixelsPerSegment, "Tessellation target: pixels per segment")
      ->check(finiteRange(0.5, 100.0))
      ->capture_default_str();
  command.add_option("--trees-max-level", lod.maxLevel, "Largest tessellation level (1 … 64)")
      ->check(finiteRange(1.0, 64.0))
      ->capture_default_str();
  command
      .add_option("--trees-level", lod.fixedLevel, "Fixed tessellation level for every quad (0: by distance)")
      ->check(finiteRange(0.0, 64.0))
      ->capture_default_str();
  command.add_option("--trees-distance", lod.drawDistance, "Draw distance of tree pieces, metres (0: all)")
      ->check(finiteRange(0.0, 1.0e6))
      ->capture_default_str();
  command
      .add_option("--trees-view", view, "Trees view: shaded, pieces (piece types), bones (root weights), lod")
      ->check(CLI::IsMember({"shaded", "pieces", "bones", "lod"}))
      ->capture_default_str();
}

void TreeFlags::check() const {
  trees::validate(forest, "--trees");
  for (const std::string& s : forest.species) {
    try {
      (void)trees::resolveSpecies(s);
    } catch (const Error& e) {
      fail("--trees-species: {}", e.what());
    }
  }
  (void)parseTreeView(view);
}

trees::TreeView parseTreeView(const std::string& name) {
  if (name == "shaded")
    return trees::TreeView::Shaded;
  if (name == "pieces")
    return trees::TreeView::PieceTypes;
  if (name == "bones")
    return trees::TreeView::Bones;
  if (name == "lod")
    return trees::TreeView::LodLevels;
  fail("--trees-view: '{}' is not one of shaded, pieces, bones, lod", name);
}

trees::TreeView TreeFlags::treeView() const {
  return parseTreeView(view);
}

std::shared_ptr<trees::Forest> TreeFlags::buildForest(const terrain::TerrainScene& scene) const {
  check();
  trees::ForestSettings settings = forest;
  settings.verticalScale = scene.exaggeration();
  if (scene.seaLevel()) {
    settings.minHeight = (*scene.seaLevel() + 0.5f) * scene.exaggeration();
  }
  return std::make_shared<trees::Forest>(trees::placeForest(scene.field(), settings));
}

render::Camera forestCamera(const terrain::TerrainScene& scene, const trees::Forest& forest, float fovY) {
  render::Camera camera = scene.defaultCamera();
  camera.fovY = fovY;
  if (forest.trees.empty()) {
    return camera;
  }
  // The tree nearest the footprint's centre, seen from 14 m away at a little above eye height.
  const glm::vec2 centre(scene.field().extentX() * 0.5f, scene.field().extentZ() * 0.5f);
  const trees::ForestTree* best = &forest.trees.front();
  float bestDistance = 1e30f;
  for (const trees::ForestTree& t : forest.trees) {
    const float d = glm::length(glm::vec2(t.base[3].x, t.base[3].z) - centre);
    if (d < bestDistance) {
      bestDistance = d;
      best = &t;
    }
  }
  const glm::vec3 foot(best->base[3]);
  const glm::vec3 eye = foot + glm::vec3(12.0f, 0.0f, 9.0f);
  const float ground = terrain::heightAt(scene.field(), std::clamp(eye.x, 0.0f, scene.field().extentX()),
                                         std::clamp(eye.z, 0.0f, scene.field().extentZ())) *
                       scene.exaggeration();
  camera.position = glm::vec3(eye.x, (std::isnan(ground) ? foot.y : ground) + 2.5f, eye.z);
  camera.target = foot + glm::vec3(0.0f, 4.0f, 0.0f);
  camera.nearPlane = 0.1f;
  return camera;
}

} // namespace sylva::app
