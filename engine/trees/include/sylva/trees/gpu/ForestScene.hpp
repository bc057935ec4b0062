#pragma once
// A forest ready to draw: the forest, its piece renderer, bark tiles, foliage, far-field impostors and the
// joint springs in the wind, stepped at a fixed rate and drawn as one pass (docs/trees.md). GL side.

#include <sylva/core/Geometry.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/gpu/FoliageRenderer.hpp>
#include <sylva/trees/ForestLook.hpp>
#include <sylva/trees/gpu/ImpostorRenderer.hpp>
#include <sylva/trees/gpu/JointWindGpu.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>
#include <sylva/wind/Wind.hpp>

#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace sylva::trees {

/** Fixed time step of the trees' joint springs, seconds (60 Hz, whatever the frame rate). */
inline constexpr double kForestWindStep = 1.0 / 60.0;
/**
 * Seconds of wind the springs feel, from rest, before the first frame: it shows trees already swaying (not
 * starting from straight), and the same first frame for the same time.
 */
inline constexpr double kForestWindWarmup = 4.0;

/**
 * A forest ready to draw (scene files, `sylva render --trees`, `sylva view --trees`): the forest, its
 * renderer, its bark, foliage and far field and, while the wind is on, its joint springs on the GPU
 * (JointWindGpu) stepped at kForestWindStep, whose frames the renderer draws; with the wind off the renderer
 * draws the rest pose. Needs a current GL context; not thread-safe.
 */
class ForestScene {
public:
  /** Uploads `forest`; with `wind`, builds the springs' rest data and GPU state too (else on setWind(true)).
   */
  ForestScene(const shader::Library& library, std::shared_ptr<const Forest> forest, bool wind);

  /** Bark tiles from `sources` (synthesised or loaded, see barkSetsFor); nullopt: flat colours. */
  void setBark(const std::optional<BarkSources>& sources);
  /** The bark sets in use (empty: flat colours). */
  const std::vector<BarkSet>& barkSets() const { return mBarkSets; }

  /**
   * Foliage impostors with `leafImage` (RGBA, alpha-tested; null: procedural) and `cloud` (null: procedural
   * leaf cards); nullopt-like `enabled` false removes them.
   */
  void setFoliage(bool enabled, const Image* leafImage = nullptr, const LeafCloud* cloud = nullptr);
  /** Foliage renderer, or null when foliage is off. */
  FoliageRenderer* foliage() { return mFoliage.get(); }

  /**
   * Far field (docs/trees.md "Far field"): bakes every species' impostor atlas (with this scene's bark and
   * foliage) and draws `extra` impostor-only trees besides the forest's own; trees dissolve into impostors
   * between `range.x` and `range.y` metres. range.y <= range.x turns it off.
   */
  void setFarField(glm::vec2 range, std::span<const FarTree> extra = {});
  /** The impostor renderer, or null without a far field. */
  ImpostorRenderer* impostors() { return mImpostors.get(); }

  /**
   * Bark, foliage and far field as `look` says (check() it first): the far field's extra trees stand on
   * `ground` around the forest `placement` placed (farFieldTrees).
   */
  void applyLook(const ForestLook& look, const ForestSettings& placement, const FarGround& ground);
  /** Foliage as `look` says: off, or with its leaf image ("auto": kAutoLeafImage when fetched) and model. */
  void applyFoliage(const ForestLook& look);
  /** Far field as `look` says (off for farDistance 0; bakes the atlases: seconds on llvmpipe). */
  void applyFarField(const ForestLook& look, const ForestSettings& placement, const FarGround& ground);

  /** Turns the wind on (building the springs on first use; they go on from their last state) or off. */
  void setWind(bool on);
  /** Puts the springs back at rest; the next advance() starts kForestWindWarmup seconds before its time. */
  void resetWind();
  /** Whether the trees are drawn in the wind (else in their rest pose). */
  bool windOn() const { return mWindOn; }

  /**
   * Steps the springs in `wind` at kForestWindStep up to scene time `time` (seconds) and rebuilds the joint
   * frames. The first call starts from rest kForestWindWarmup seconds before `time`; later calls take at most
   * `maxSteps` steps (after a stall the clock skips ahead, see fixedSteps). Nothing while the wind is
   * off. With `timers`, the two compute passes are timed as "trees wind".
   */
  void advance(double time, const wind::WindSettings& wind, int maxSteps = 8,
               render::GpuTimers* timers = nullptr);
  /** Culls and draws the forest for `camera` into the bound framebuffer (`width` × `height` pixels). */
  void draw(const render::Camera& camera, int width, int height, double time, const TreeLod& lod,
            const TreeDrawOptions& options, render::GpuTimers* timers = nullptr);
  /** Recompiles every program (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);

  /** The forest drawn. */
  const Forest& forest() const { return *mForest; }
  /** The renderer (visible counts, GPU memory). */
  TreeRenderer& renderer() { return *mRenderer; }
  /** World box around every tree at rest with a margin for the wind's bends, metres. */
  const Aabb& bounds() const { return mBounds; }
  /** Spring steps of the last advance(). */
  int lastSteps() const { return mSteps; }
  /** Bytes of GPU memory held by the renderer and the springs. */
  std::size_t gpuBytes() const;

private:
  shader::Library mShaders;
  std::shared_ptr<const Forest> mForest;
  std::unique_ptr<TreeRenderer> mRenderer;
  std::unique_ptr<JointWindGpu> mWind;
  std::unique_ptr<FoliageRenderer> mFoliage;
  std::unique_ptr<ImpostorRenderer> mImpostors;
  glm::vec2 mFarRange{0.0f};
  std::vector<BarkSet> mBarkSets;
  std::vector<int> mSpeciesSet;
  std::optional<Image> mLeafImageCopy;
  std::optional<LeafCloud> mLeafCloud;
  Aabb mBounds;
  bool mWindOn = false;
  /** The springs' simulated time, seconds; empty until the first advance(). */
  std::optional<double> mClock;
  int mSteps = 0;
};

} // namespace sylva::trees
