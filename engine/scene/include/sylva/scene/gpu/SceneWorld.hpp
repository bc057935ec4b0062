#pragma once
// A scene made drawable (`sylva render scene.json`, `sylva view scene.json`, `sylva bench scene`): the engine
// composes the world a scene description names (terrain, grass layers, forests, simulated grass and bodies,
// lakes, cameras) with the same builders as the per-subsystem options, and draws it frame by frame in the
// scene's pass order (ScenePasses). docs/scenes.md. GL side.

#include <sylva/grass/gpu/GrassRenderer.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/scene/CameraPath.hpp>
#include <sylva/scene/Quality.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/scene/gpu/ScenePasses.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>
#include <sylva/trees/Forest.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>
#include <sylva/wind/Wind.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace sylva::trees {
class ForestScene;
}

namespace sylva::scene {

class GrassSimulation;
class ShoreWater;

/** How a world is shown: the debugging views of each subsystem and the trees' level of detail. */
struct SceneDrawOptions {
  /** The terrain's view (shaded or a debug view). */
  terrain::TerrainView terrainView = terrain::TerrainView::Shaded;
  /** Draw every subsystem's triangles as lines. */
  bool wireframe = false;
  /** The grass's view. */
  grass::GrassView grassView = grass::GrassView::Shaded;
  /** The trees' view. */
  trees::TreeView treeView = trees::TreeView::Shaded;
  /** The trees' tessellation rule in the view (shadow draws keep it, with pieces under
   * render::kCasterMinTexels skipped). */
  trees::TreeLod treeLod;
  /** The terrain's crack check: skirts drawn in a signal colour under every patch edge (counted). */
  bool terrainSkirts = false;
  /** Count the terrain's vertex shader invocations (a pipeline query:
   * TerrainRenderer::lastVertexInvocations).
   */
  bool countVertices = false;
  /** Count the grass draws' primitives (a pipeline query: GrassRenderer::lastPrimitivesSubmitted). */
  bool countPrimitives = false;
  /** The terrain's LOD chosen for this frustum instead of the camera's (inspecting the selection). */
  std::optional<Frustum> frozenFrustum;
  /**
   * The full path: every shadow cascade every frame, so a frame is a pure function of its time and the
   * simulations' state (offline renders; `sylva bench scene --quality full`). Off (the default, real time):
   * far cascades are redrawn one per frame and kept otherwise (ScenePasses::setShadowReuse).
   */
  bool fullQuality = false;
};

/** A scene's wind as the wind module takes it (direction clockwise from north becomes a unit xz vector). */
wind::WindSettings windSettings(const WindDesc& desc);

/**
 * Every subsystem of one scene file, on the GPU, with its simulations. Frame f of a sequence is a pure
 * function of (scene, f): simulations (physics, simulated grass, the trees' joint springs) are stepped
 * through the times of every frame from 0 to f at the scene's fps, whatever frames were drawn before
 * (advanceToFrame). Needs a current GL context; not thread-safe.
 */
class SceneWorld {
public:
  /** Builds every subsystem of `desc`; errors name the scene file and field (before the expensive work where
   * the description allows it). */
  SceneWorld(const shader::Library& library, SceneDesc desc);
  ~SceneWorld();
  SceneWorld(const SceneWorld&) = delete;
  SceneWorld& operator=(const SceneWorld&) = delete;

  /** The description the world was built from (with the viewer's edits). */
  const SceneDesc& desc() const { return mDesc; }
  /** Seconds of frame `frame` on the scene's fixed clock (frame / fps). */
  double frameTime(int frame) const { return static_cast<double>(frame) / mDesc.output.fps; }

  /** The camera `name` (a key of the file's cameras) at scene time `time`, for `aspect` = width / height. */
  render::Camera camera(const std::string& name, double time, float aspect) const;

  /**
   * Brings every simulation to frame `frame`'s time by stepping through each earlier frame's time in order
   * (restarting from frame 0 when `frame` is before the current one). Deterministic: the same calls give the
   * same state in every process, so shards and resumed runs draw identical frames.
   */
  void advanceToFrame(int frame);
  /**
   * Interactive use (viewer): advances the simulations to `time` seconds directly (not frame-exact). After a
   * real-time draw (SceneDrawOptions::fullQuality off) the simulated grass tiles beyond that camera's drawn
   * grass distance are held, not stepped (grass::TileSimulation::setFocus); advanceToFrame steps them all.
   */
  void advanceTo(double time);
  /** Adds a drop of balls (it becomes part of the description; the simulation restarts from time 0). Throws
   * without a simulated grass layer. */
  void addDrop(const BodyDrop& drop);

  /** Views and tree LOD of the next frames (default: shaded, the default TreeLod). */
  void setDrawOptions(const SceneDrawOptions& options);
  /** The views of the next frames. */
  const SceneDrawOptions& drawOptions() const { return mDrawOptions; }

  /**
   * Draws one frame for `camera` into the bound framebuffer (`width` × `height`), all passes in order;
   * `depth` is that framebuffer's depth attachment (the sun flare's occlusion test; null: no flare).
   */
  void draw(const render::Camera& camera, int width, int height, double time, const gl::Texture* depth,
            render::GpuTimers* timers);

  /**
   * The interactive quality step of the next frames (Quality.hpp; default: full, the scene as described):
   * every grass layer draws out to its distance × step.grassDistance, shadows are drawn only with
   * step.shadows. The render scale is the caller's: it draws at renderSize(output, step.renderScale) and
   * scales the frame up (the viewer; `sylva bench scene --quality auto`).
   */
  void setQuality(const QualityStep& step);
  /** The interactive quality step of the next frames. */
  const QualityStep& quality() const { return mQuality; }

  /** The frame environment (sun, sky, fog) the passes share; shadows are filled per frame. */
  const render::Environment& environment() const { return mPasses->environment(); }
  /** The frame's passes. */
  ScenePasses& passes() { return *mPasses; }
  /** The wind the grass and trees share. */
  const wind::WindSettings& wind() const { return mWind; }
  /** The terrain. */
  terrain::TerrainScene& terrain() { return *mTerrain; }
  /** Drawn terrain height at world (x, z) (exaggerated metres); NaN outside or over nodata. */
  float groundHeight(float x, float z) const;
  /** The box free cameras' clip planes must hold: the terrain and every forest's crowns, world metres. */
  Aabb bounds();

  /** Adds a ball at `position` with `velocity` (needs a simulated grass layer: the physics world lives
   * there). */
  bool spawnBall(const glm::vec3& position, const glm::vec3& velocity);
  /** Bodies in the physics world. */
  std::size_t bodies() const;
  /** Trees in every forest. */
  std::size_t treeCount() const;
  /** Grass layer `i`'s renderer (its field: fieldPointer()), in the description's order. */
  grass::GrassRenderer& grass(std::size_t i) { return *mGrass.at(i); }
  /** Forest `i`, in the description's order. */
  trees::ForestScene& forest(std::size_t i) { return *mForests.at(i); }
  /** The grass simulation, or null without a simulated layer. */
  GrassSimulation* simulation() { return mSimulation.get(); }
  /** Grass layers, forests (in the description's order). */
  std::size_t grassCount() const { return mGrass.size(); }
  /** Forests in the world. */
  std::size_t forestCount() const { return mForests.size(); }
  /**
   * Replaces grass layer `i` with `layer`, or adds it at i == grassCount() (the viewer's panel). Builds the
   * new field first: on an error (naming the field) the world is unchanged. A simulated layer restarts its
   * simulation with the description's bodies.
   */
  void setGrassLayer(std::size_t i, GrassLayer layer);
  /** Layer `i`'s culling rules as described (before the quality step scales its distances). */
  grass::CullSettings grassCull(std::size_t i) const;
  /** New culling rules for layer `i` (validated, kept in the description; drawn at the quality step's scale).
   */
  void setGrassCull(std::size_t i, const grass::CullSettings& cull);
  /** Makes grass layer `i` the simulated one (no layer may be yet): the physics world starts, with the
   * description's bodies (none for a description that had no simulated layer). */
  void simulateGrass(std::size_t i);
  /** Removes every body and drop from the description; the simulation restarts empty at time 0. */
  void clearBodies();
  /** Replaces forest `i` with `forest`, or adds it at i == forestCount(); on an error, unchanged. */
  void setForest(std::size_t i, ForestDesc forest);
  /** Where forest `i` was placed from (its description turned into placement rules on this terrain). */
  const trees::ForestSettings& forestPlacement(std::size_t i) const { return mPlacements.at(i); }
  /** The wind of the next steps and frames (grass, trees, simulation). */
  void setWind(const WindDesc& wind) {
    mDesc.wind = wind;
    mWind = windSettings(wind);
  }
  /** The simulated grass layer's index, or -1 when none is simulated. */
  int simulatedLayer() const { return mSimulatedGrass; }
  /** Bytes of GPU memory the scene's subsystems hold (those that report it). */
  std::size_t gpuBytes() const;
  /** Recompiles every subsystem's shaders from `library` (the viewer's F5). */
  void reloadShaders(const shader::Library& library);

private:
  std::unique_ptr<grass::GrassRenderer> makeGrass(std::size_t i, const GrassLayer& layer) const;
  /** `layer`'s (layer `i`'s) culling rules at the quality step's distance. */
  grass::CullSettings scaledGrassCull(std::size_t i, const GrassLayer& layer) const;
  std::unique_ptr<trees::ForestScene> makeForest(std::size_t i, const ForestDesc& forest,
                                                 trees::ForestSettings& placement) const;
  /** (Re)registers every subsystem's draws with the passes. */
  void registerPasses();
  void buildSimulation();
  void stepTo(double time);

  const shader::Library& mLibrary;
  SceneDesc mDesc;
  wind::WindSettings mWind;
  std::unique_ptr<terrain::TerrainScene> mTerrain;
  std::vector<std::unique_ptr<grass::GrassRenderer>> mGrass;
  int mSimulatedGrass = -1;
  std::unique_ptr<GrassSimulation> mSimulation;
  std::vector<std::unique_ptr<trees::ForestScene>> mForests;
  std::vector<trees::ForestSettings> mPlacements;
  std::vector<std::unique_ptr<ShoreWater>> mWater;
  std::unique_ptr<ScenePasses> mPasses;
  std::map<std::string, std::vector<WorldCameraKey>> mCameras;
  SceneDrawOptions mDrawOptions;
  QualityStep mQuality;
  int mFrame = -1;
  double mTime = 0.0;
};

} // namespace sylva::scene
