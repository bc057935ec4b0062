#pragma once
// Command-line options for a forest on the terrain (`sylva render --trees`, `sylva view --trees`).

#include <sylva/core/Geometry.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>
#include <sylva/trees/gpu/FoliageRenderer.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>
#include <sylva/trees/gpu/ImpostorRenderer.hpp>
#include <sylva/trees/gpu/JointWindGpu.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>
#include <sylva/wind/Wind.hpp>

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sylva::app {

/** --trees and its settings. */
struct TreeFlags {
  bool enabled = false;
  trees::ForestSettings forest = defaultForest();
  trees::TreeLod lod;
  std::string view = "shaded";
  /** --trees-wind: the joints sway in the wind (--wind-speed, --wind-direction, --wind-gusts, --wind-seed).
   */
  bool wind = true;
  /** --trees-bark: auto | procedural | none | a tile-set directory (docs/trees.md "Bark"). */
  std::string bark = "auto";
  /** --trees-bark-photos, --trees-bark-tile, --trees-bark-variants. */
  std::string barkPhotos; ///< empty: the data folder's (trees::BarkSources::photoDir)
  int barkTile = trees::BarkSources::defaultBarkTiles().tileSize;
  int barkVariants = trees::BarkSources{}.variants;
  /** --trees-foliage: 2.5D leaf-cloud impostors at the branch tips (docs/trees.md "Foliage"). */
  bool foliage = true;
  /** --trees-leaves: a leaf PNG with alpha, "auto" (ez-tree's oak leaf when fetched, else procedural) or
   * "procedural"; --trees-leaf-model: a leaf-cloud model through Assimp ("" : procedural cards). */
  std::string leaves = "auto";
  std::string leafModel;
  /** --trees-far: trees farther than this become octahedral impostors (metres; 0: never);
   * --trees-far-band: over how many metres they dissolve; --trees-far-count: impostor-only trees added
   * around the forest out to the terrain's edge (a forest to the horizon). */
  float farDistance = 0.0f;
  float farBand = 25.0f;
  int farCount = 0;

  static trees::ForestSettings defaultForest();
  /** Bark, foliage and far field as the flags say (the engine's description, trees::ForestLook). */
  trees::ForestLook look() const;
  /** Adds --trees, --trees-species, --trees-count, --trees-seed, --trees-spacing, --trees-max-slope,
   * --trees-autumn, --trees-leaf-fall,
   * --trees-pixels, --trees-max-level, --trees-level, --trees-distance, --trees-min-pixels,
   * --trees-min-width, --trees-view, --trees-wind. */
  void add(CLI::App& command);
  /** Throws naming the option when a value is malformed (before any work is done). */
  void check() const;
  trees::TreeView treeView() const;
  /** The forest these options describe (what a scene file's forest holds, with every look setting): the
   * species weighted equally, around the terrain's centre within --trees-radius. */
  scene::ForestDesc forestDesc() const;
};

/** "shaded" | "pieces" | "bones" | "lod" | "tiles" → TreeView; throws naming the option otherwise. */
trees::TreeView parseTreeView(const std::string& name);

} // namespace sylva::app
