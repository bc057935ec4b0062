#pragma once
// Command-line options for a forest on the terrain (`sylva render --trees`, `sylva view --trees`).

#include <sylva/terrain/TerrainScene.hpp>
#include <sylva/trees/TreeRenderer.hpp>

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace sylva::app {

/** --trees and its settings. */
struct TreeFlags {
  bool enabled = false;
  trees::ForestSettings forest = defaultForest();
  trees::TreeLod lod;
  std::string view = "shaded";

  static trees::ForestSettings defaultForest();
  /** Adds --trees, --trees-species, --trees-count, --trees-seed, --trees-spacing, --trees-max-slope,
   * --trees-pixels, --trees-max-level, --trees-level, --trees-distance, --trees-view. */
  void add(CLI::App& command);
  /** Throws naming the option when a value is malformed (before any work is done). */
  void check() const;
  trees::TreeView treeView() const;
  /** The forest on `scene`'s terrain (drawn heights), only above the sea level. */
  std::shared_ptr<trees::Forest> buildForest(const terrain::TerrainScene& scene) const;
};

/** "shaded" | "pieces" | "bones" | "lod" → TreeView; throws naming the option otherwise. */
trees::TreeView parseTreeView(const std::string& name);

/** A camera at eye height a little outside the forest's densest part, looking at a tree near the centre. */
render::Camera forestCamera(const terrain::TerrainScene& scene, const trees::Forest& forest, float fovY);

} // namespace sylva::app
