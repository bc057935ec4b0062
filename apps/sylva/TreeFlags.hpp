#pragma once
// Command-line options for a forest on the terrain (`sylva render --trees`, `sylva view --trees`).

#include <sylva/core/Geometry.hpp>
#include <sylva/render/GpuTimers.hpp>
#include <sylva/terrain/TerrainScene.hpp>
#include <sylva/trees/FoliageRenderer.hpp>
#include <sylva/trees/ImpostorRenderer.hpp>
#include <sylva/trees/JointWindGpu.hpp>
#include <sylva/trees/TreeRenderer.hpp>
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
  std::string barkPhotos = "data/external/ez-tree/bark";
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
  /** Where bark tiles come from; nullopt for --trees-bark none (flat bark colours). */
  std::optional<trees::BarkSources> barkSources() const;
  /** Puts foliage on `scene` as the flags say (none with --no-trees-foliage). */
  void applyFoliage(class TreeScene& scene) const;
  /** Sets up the far field of `scene` on `terrain` as the flags say (none without --trees-far). */
  void applyFarField(class TreeScene& scene, const terrain::TerrainScene& terrain) const;
  /** Adds --trees, --trees-species, --trees-count, --trees-seed, --trees-spacing, --trees-max-slope,
   * --trees-pixels, --trees-max-level, --trees-level, --trees-distance, --trees-view, --trees-wind. */
  void add(CLI::App& command);
  /** Throws naming the option when a value is malformed (before any work is done). */
  void check() const;
  trees::TreeView treeView() const;
  /** The forest on `scene`'s terrain (drawn heights), only above the sea level. */
  std::shared_ptr<trees::Forest> buildForest(const terrain::TerrainScene& scene) const;
};

/** Fixed time step of the trees' joint springs, seconds (60 Hz, whatever the frame rate). */
inline constexpr double kTreeWindStep = 1.0 / 60.0;
/**
 * Seconds of wind the springs feel, from rest, before the first frame: it shows trees already swaying (not
 * starting from straight), and the same first frame for the same time.
 */
inline constexpr double kTreeWindWarmup = 4.0;

/**
 * A forest ready to draw (`sylva render --trees`, `sylva view --trees`): the forest, its renderer and, while
 * the wind is on, its joint springs on the GPU (JointWindGpu) stepped at kTreeWindStep, whose frames the
 * renderer draws; with the wind off the renderer draws the rest pose. Needs a current GL context; not
 * thread-safe.
 */
class TreeScene {
public:
  /** Uploads `forest`; with `wind`, builds the springs' rest data and GPU state too (else on setWind(true)).
   */
  TreeScene(const shader::Library& library, std::shared_ptr<const trees::Forest> forest, bool wind);

  /** Bark tiles from `sources` (synthesised or loaded, see trees::barkSetsFor); nullopt: flat colours. */
  void setBark(const std::optional<trees::BarkSources>& sources);
  /** The bark sets in use (empty: flat colours). */
  const std::vector<trees::BarkSet>& barkSets() const { return mBarkSets; }

  /**
   * Foliage impostors with `leafImage` (RGBA, alpha-tested; null: procedural) and `cloud` (null: procedural
   * leaf cards); nullopt-like `enabled` false removes them.
   */
  void setFoliage(bool enabled, const Image* leafImage = nullptr, const trees::LeafCloud* cloud = nullptr);
  /** Foliage renderer, or null when foliage is off. */
  trees::FoliageRenderer* foliage() { return mFoliage.get(); }

  /**
   * Far field (docs/trees.md "Far field"): bakes every species' impostor atlas (with this scene's bark and
   * foliage) and draws `extra` impostor-only trees besides the forest's own; trees dissolve into impostors
   * between `range.x` and `range.y` metres. range.y <= range.x turns it off.
   */
  void setFarField(glm::vec2 range, std::span<const trees::FarTree> extra = {});
  /** The impostor renderer, or null without a far field. */
  trees::ImpostorRenderer* impostors() { return mImpostors.get(); }

  /** Turns the wind on (building the springs on first use; they go on from their last state) or off. */
  void setWind(bool on);
  /** Puts the springs back at rest; the next advance() starts kTreeWindWarmup seconds before its time. */
  void resetWind();
  /** Whether the trees are drawn in the wind (else in their rest pose). */
  bool windOn() const { return mWindOn; }

  /**
   * Steps the springs in `wind` at kTreeWindStep up to scene time `time` (seconds) and rebuilds the joint
   * frames. The first call starts from rest kTreeWindWarmup seconds before `time`; later calls take at most
   * `maxSteps` steps (after a stall the clock skips ahead, see trees::fixedSteps). Nothing while the wind is
   * off. With `timers`, the two compute passes are timed as "trees wind".
   */
  void advance(double time, const wind::WindSettings& wind, int maxSteps = 8,
               render::GpuTimers* timers = nullptr);
  /** Culls and draws the forest for `camera` into the bound framebuffer (`width` × `height` pixels). */
  void draw(const render::Camera& camera, int width, int height, double time, const trees::TreeLod& lod,
            const trees::TreeDrawOptions& options, render::GpuTimers* timers = nullptr);
  /** Recompiles every program (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);

  /** The forest drawn. */
  const trees::Forest& forest() const { return *mForest; }
  /** The renderer (visible counts, GPU memory). */
  trees::TreeRenderer& renderer() { return *mRenderer; }
  /** World box around every tree at rest with a margin for the wind's bends, metres. */
  const Aabb& bounds() const { return mBounds; }
  /** Spring steps of the last advance(). */
  int lastSteps() const { return mSteps; }
  /** Bytes of GPU memory held by the renderer and the springs. */
  std::size_t gpuBytes() const;

private:
  shader::Library mShaders;
  std::shared_ptr<const trees::Forest> mForest;
  std::unique_ptr<trees::TreeRenderer> mRenderer;
  std::unique_ptr<trees::JointWindGpu> mWind;
  std::unique_ptr<trees::FoliageRenderer> mFoliage;
  std::unique_ptr<trees::ImpostorRenderer> mImpostors;
  glm::vec2 mFarRange{0.0f};
  std::vector<trees::BarkSet> mBarkSets;
  std::vector<int> mSpeciesSet;
  std::optional<Image> mLeafImageCopy;
  std::optional<trees::LeafCloud> mLeafCloud;
  Aabb mBounds;
  bool mWindOn = false;
  /** The springs' simulated time, seconds; empty until the first advance(). */
  std::optional<double> mClock;
  int mSteps = 0;
};

/** The joint springs' rest data of `forest` (one JointWindTree per tree; its phase is the wind offset). */
trees::JointWindRest forestWindRest(const trees::Forest& forest);

/** "shaded" | "pieces" | "bones" | "lod" | "tiles" → TreeView; throws naming the option otherwise. */
trees::TreeView parseTreeView(const std::string& name);

/**
 * A camera 2.5 m above the ground, 2.5 tree heights (8 … 60 m) from the tree nearest the terrain's centre,
 * looking at that tree's middle: the default view of `sylva render --trees` and `sylva view --trees`.
 */
render::Camera forestCamera(const terrain::TerrainScene& scene, const trees::Forest& forest, float fovY);

} // namespace sylva::app
