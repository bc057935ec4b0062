#pragma once

#include <sylva/render/Camera.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>
#include <sylva/terrain/TerrainSetup.hpp>

#include <filesystem>
#include <memory>
#include <optional>

namespace sylva::terrain {

/** How a TerrainScene presents its heights. */
struct TerrainSceneOptions {
  /** Splat rules in true metres and degrees; empty = defaultSplatLayers over the height range and sea level.
   */
  std::vector<SplatLayer> layers;
  /** Vertical exaggeration: heights are drawn multiplied by this (> 0; 1 = true scale). */
  float exaggeration = 1.0f;
  /** Sea level in true metres: sets the default splat rules' coast line and draws water; nullopt = none. */
  std::optional<float> seaLevel;
  /** Geomorphing in drawOptions() (TerrainDrawOptions::geomorph); off by default. */
  bool geomorph = false;
};

/**
 * A terrain ready to draw: heights, quadtree LOD (CPU) and renderer (GPU). update() selects the patches for a
 * camera (optionally against a frozen frustum, to inspect culling from outside), draw() renders them.
 * Needs a current GL context.
 */
class TerrainScene {
public:
  /** `config` rootsX/Z = 0 derive from rootSize; `layers` empty = defaultSplatLayers over the height range.
   */
  TerrainScene(const shader::Library& library, HeightField field, const QuadtreeConfig& config,
               std::vector<SplatLayer> layers = {});
  /** `field` in true metres; it is exaggerated here (options.exaggeration) before the quadtree and GPU see
   * it. */
  TerrainScene(const shader::Library& library, HeightField field, const QuadtreeConfig& config,
               TerrainSceneOptions options);

  /**
   * Builds the terrain `setup` describes: the splat rules file, then limits known before any work (the GPU's
   * largest texture side, the memory a procedural field needs), then the heights, the sea level and the
   * quadtree (quadtreeFor). Errors name the file or the field through `name` (null: the scene-file names).
   * Logs a hint when the relief will look flat; shows progress for large fields.
   */
  static std::unique_ptr<TerrainScene> fromSetup(const shader::Library& library, const TerrainSetup& setup,
                                                 const TerrainFieldName& name = {});

  /**
   * Runs LOD selection and neighbour levels for `camera` at `aspect`; returns the selection. With
   * screen-space-error LOD and `viewportHeightPx` > 0, the error is projected into a view that many pixels
   * high with the camera's field of view (QuadtreeConfig::pixelsPerRadian); 0 keeps the last projection.
   */
  const QuadtreeSelection& update(const render::Camera& camera, float aspect, int viewportHeightPx = 0);
  /** Draws the last selection. */
  void draw(const render::Camera& camera, int width, int height, double time,
            render::GpuTimers* timers = nullptr, const TerrainDrawOptions& options = {});

  /**
   * Applies a new LOD policy; rebuilds the quadtree when the layout (roots, root size, depth) changes or
   * screen-space-error LOD needs node errors it does not have (Quadtree::canSetConfig).
   */
  void setQuadtreeConfig(const QuadtreeConfig& config);
  /** Culls against this frustum instead of the camera's (viewer "freeze frustum"); nullopt = follow camera.
   */
  void setFrozenFrustum(std::optional<Frustum> frustum) { mFrozen = frustum; }
  /** Whether culling uses a frozen frustum. */
  bool frustumFrozen() const { return mFrozen.has_value(); }

  /**
   * World bounds of what is drawn, metres: the footprint [0, extentX] × [0, extentZ] and the (exaggerated)
   * height range, including the water surface.
   */
  Aabb bounds() const;
  /**
   * The framing camera of renders and the viewer's start: looks at the centre of bounds() from `from`, just
   * far enough to see all of it at `aspect` (render::frameBox).
   */
  render::Camera frameCamera(render::ViewFrom from = render::ViewFrom::SouthWest,
                             float fovY = glm::radians(50.0f), float aspect = 16.0f / 9.0f) const;
  /** frameCamera() from the south-west at 16:9 (kept for callers that need one fixed view). */
  render::Camera defaultCamera() const { return frameCamera(); }
  /**
   * Sun and fog for `camera`: exponential fog scaled so that the farthest corner of bounds() is `fog` fogged
   * (0 = no fog), whatever the terrain's size.
   */
  render::Environment environment(const render::Camera& camera, float fog = 0.5f) const;
  /** Vertical exaggeration the scene was built with. */
  float exaggeration() const { return mOptions.exaggeration; }
  /** Sea level, true metres; nullopt when there is no water. */
  std::optional<float> seaLevel() const { return mOptions.seaLevel; }
  /** Whether drawOptions() turns geomorphing on. */
  bool geomorph() const { return mOptions.geomorph; }
  /** Turns geomorphing in drawOptions() on or off. */
  void setGeomorph(bool on) { mOptions.geomorph = on; }
  /**
   * Draw options for a shaded frame from `camera`: environment, water at the (exaggerated) sea level,
   * geomorphing as in the scene options.
   */
  TerrainDrawOptions drawOptions(const render::Camera& camera, float fog = 0.5f) const;
  /** CPU time of the last update() (selection + neighbour levels), milliseconds. */
  double lastUpdateMs() const { return mLastUpdateMs; }

  /** The heights, metres as loaded (not exaggerated). */
  const HeightField& field() const { return mField; }
  /** The LOD quadtree. */
  Quadtree& quadtree() { return mQuadtree; }
  /** The GL renderer. */
  TerrainRenderer& renderer() { return *mRenderer; }
  /** The GL renderer. */
  const TerrainRenderer& renderer() const { return *mRenderer; }
  /** The nodes the last update() selected. */
  const QuadtreeSelection& selection() const { return mSelection; }
  /** Height range of the valid samples, metres as drawn (× exaggeration). */
  float minHeight() const { return mInfo.minHeight; }
  /** Highest valid sample, metres as drawn (× exaggeration). */
  float maxHeight() const { return mInfo.maxHeight; }

private:
  TerrainSceneOptions mOptions;
  HeightField mField;
  HeightFieldInfo mInfo;
  Quadtree mQuadtree;
  std::unique_ptr<TerrainRenderer> mRenderer;
  QuadtreeSelection mSelection;
  std::optional<Frustum> mFrozen;
  double mLastUpdateMs = 0.0;
};

} // namespace sylva::terrain
