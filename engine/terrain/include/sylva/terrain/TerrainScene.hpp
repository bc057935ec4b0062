#pragma once

#include <sylva/render/Camera.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/TerrainRenderer.hpp>

#include <filesystem>
#include <memory>
#include <optional>

namespace sylva::terrain {

/** Where a scene's heights come from: a DEM/heightmap file, or the seeded procedural generator. */
struct TerrainSource {
  /** Height file (PNG, GeoTIFF and other GDAL rasters, .npy/.npz); empty = procedural. */
  std::filesystem::path dem;
  LoadOptions load;
  ProceduralSpec procedural = defaultProcedural();
  /** Procedural field size in samples per side, and spacing in metres. */
  int proceduralSize = 1025;
  float proceduralSpacing = 2.0f;

  /** The demo landscape: warped fBm, 400 m relief. */
  static ProceduralSpec defaultProcedural();
};

/** Loads or generates the heights of `source`; errors name the file or the field. */
HeightField loadTerrainSource(const TerrainSource& source);

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

  /** Runs LOD selection and neighbour levels for `camera` at `aspect`; returns the selection. */
  const QuadtreeSelection& update(const render::Camera& camera, float aspect);
  /** Draws the last selection. */
  void draw(const render::Camera& camera, int width, int height, double time,
            render::GpuTimers* timers = nullptr, const TerrainDrawOptions& options = {});

  /** Applies a new LOD policy; rebuilds the quadtree when the layout (roots, root size, depth) changes. */
  void setQuadtreeConfig(const QuadtreeConfig& config);
  /** Culls against this frustum instead of the camera's (viewer "freeze frustum"); nullopt = follow camera.
   */
  void setFrozenFrustum(std::optional<Frustum> frustum) { mFrozen = frustum; }
  bool frustumFrozen() const { return mFrozen.has_value(); }

  /** A camera looking across the terrain from its south-west, for renders and the viewer's start. */
  render::Camera defaultCamera() const;
  /** Sun and fog suited to the terrain's size (fog reaches ~70 % at the far side of the terrain). */
  render::Environment environment() const;
  /** CPU time of the last update() (selection + neighbour levels), milliseconds. */
  double lastUpdateMs() const { return mLastUpdateMs; }

  const HeightField& field() const { return mField; }
  Quadtree& quadtree() { return mQuadtree; }
  TerrainRenderer& renderer() { return *mRenderer; }
  const QuadtreeSelection& selection() const { return mSelection; }
  /** Height range of the valid samples, metres. */
  float minHeight() const { return mInfo.minHeight; }
  float maxHeight() const { return mInfo.maxHeight; }

private:
  HeightField mField;
  HeightFieldInfo mInfo;
  Quadtree mQuadtree;
  std::unique_ptr<TerrainRenderer> mRenderer;
  QuadtreeSelection mSelection;
  std::optional<Frustum> mFrozen;
  double mLastUpdateMs = 0.0;
};

} // namespace sylva::terrain
