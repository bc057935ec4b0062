#pragma once

#include <sylva/folding/Synthesis.hpp>
#include <sylva/folding/gpu/FoldRenderer.hpp>
#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/scene/Shore.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <memory>

namespace sylva::scene {

/** What the shore water's fragment shader writes. */
enum class ShoreWaterView : int {
  Shaded = 0, ///< water, Fresnel, glint and the swash band, alpha-blended
  Band = 1,   ///< shoreBand(depth) in every channel, opaque (debug and tests; dry ground still discarded)
};

/**
 * The scene's water (docs/scenes.md "Water with a folding-textured shore"): a surface at ShoreSettings::level
 * over the terrain's footprint with depth colour, Fresnel towards the sky colour and a sun glint, and in the
 * shore band (shoreBand) a folding texture animating the swash, laid with its advance direction up the slope
 * (swashCoords). The folding project is loaded and synthesised on the CPU at construction (like `sylva fold
 * render`); update() renders its frame for the scene time into a small RGBA8 texture with
 * folding::gpu::FoldRenderer. Deterministic: the same time gives the same pixels. Needs a current GL 4.5
 * context for every call, including construction and destruction.
 */
class ShoreWater {
public:
  /** Largest side, texels, of the swash texture (the project image is scaled down to fit, never up). */
  static constexpr int kMaxSwashSide = 512;
  /** Largest number of mesh cells per axis (the mesh takes every n-th height sample beyond it). */
  static constexpr int kMaxCells = 512;
  /** Cells of the mesh drawn (the wet ones: scene::wetCells) and in all. */
  int drawnCells() const { return mWetCells; }
  /** Vertices drawn for them (scene::waterTriangles: flat rectangles as fans), three per triangle. */
  int drawnVertices() const { return mVertexCount; }
  /** Cells of the water grid. */
  int gridCells() const { return mCellsX * mCellsZ; }
  /** Draw every cell of the grid instead of the wet ones (comparisons: the pixels must not change). */
  void setDrawEveryCell(bool on) { mDrawEveryCell = on; }

  /**
   * `field`: the drawn heights (world metres, already multiplied by `verticalScale`, the same field the
   * TerrainRenderer draws); `settings.folding`: a sylva-fold project path (as given, relative to the working
   * directory). Throws sylva::Error for invalid settings (validate), a field under 2×2 samples, a scale that
   * is not finite and > 0, or a project that does not load or synthesise (the message names the file).
   */
  ShoreWater(const shader::Library& library, const terrain::HeightField& field, float verticalScale,
             ShoreSettings settings);
  ~ShoreWater();
  ShoreWater(const ShoreWater&) = delete;
  ShoreWater& operator=(const ShoreWater&) = delete;

  /** Recompiles the water program (viewer hot reload); keeps the old one and throws on error. */
  void reloadShaders(const shader::Library& library);

  /**
   * Renders the folding frame for scene time `time` seconds (swashTime: one project cycle per
   * settings.period) into swashTexture() and regenerates its mips. Restores the draw framebuffer binding and
   * viewport.
   */
  void update(double time);

  /**
   * Draws the water into the bound framebuffer (viewport `width`×`height` pixels), after the terrain:
   * blended, depth-tested against it, no depth writes; binds the frame block for `camera`, `time` and
   * `environment` (the frame path's, else its own: render::FrameBinding). Only the cells that can show water
   * are drawn. Call update() first for the swash to move.
   */
  void draw(const render::Camera& camera, int width, int height, double time,
            const render::Environment& environment);

  /** Selects what the water shows: shaded, or the shore band (debug). */
  void setView(ShoreWaterView view) { mView = view; }
  /** What the water shows. */
  ShoreWaterView view() const { return mView; }
  /** The shore settings the water was made with. */
  const ShoreSettings& settings() const { return mSettings; }
  /** The project's longest profile period, seconds (what settings.period 0 plays). */
  double projectPeriod() const { return mProjectPeriod; }
  /**
   * The finest mip level of the swash texture that update() renders and the water samples (clamped to the
   * texture's levels; 0 by default). A frame drawn at a fraction s of the resolution samples levels at least
   * log2(1/s) coarser everywhere, so level floor(log2(1/s)) draws the same picture for a quarter of the swash
   * work per level (SceneWorld::setQuality).
   */
  void setSwashLevel(int level);
  /** The finest mip level of the swash texture in use. */
  int swashLevel() const { return mSwashLevel; }
  /** The swash texture (RGBA8, row 0 of the folding image at the top, i.e. at t = 1). */
  const gl::Texture& swashTexture() const { return mSwash; }
  /** Height / width of the swash frame (the project image's crop). */
  float swashAspect() const { return mAspect; }

private:
  ShoreSettings mSettings;
  float mVerticalScale = 1.0f;
  int mFieldWidth = 0;
  int mFieldHeight = 0;
  float mSpacingX = 1.0f;
  float mSpacingZ = 1.0f;
  int mStride = 1;
  int mCellsX = 1;
  int mCellsZ = 1;
  int mWetCells = 0;                  ///< cells drawn (wetCells): those that can show water
  int mVertexCount = 0;               ///< the vertices they are drawn with (waterTriangles)
  gl::Buffer mCellList{gl::NoCreate}; ///< their triangles' grid points, ivec2
  gl::Buffer mEveryCell{
      gl::NoCreate}; ///< every cell's two triangles, made when setDrawEveryCell(true) is first drawn
  bool mDrawEveryCell = false;
  double mProjectPeriod = 1.0;
  float mAspect = 1.0f;
  float mWaterlineV = 0.5f; ///< settings.waterline in the frame's v (the crop)
  folding::Rect mRegion;    ///< the project image's atlas rectangle
  ShoreWaterView mView = ShoreWaterView::Shaded;
  std::unique_ptr<folding::gpu::FoldRenderer> mFold;
  gl::Program mProgram{gl::NoCreate};
  gl::Texture mHeights{gl::NoCreate};
  gl::Texture mSwash{gl::NoCreate};
  gl::Framebuffer mSwashTarget;
  int mSwashLevel = 0;
  int mSwashLevels = 1; ///< mip levels of mSwash
  /** How far above the ground the surface is draped on the wet strip (world metres; uLift, waterRects). */
  float lift() const { return 0.02f * mVerticalScale; }
  gl::VertexArray mVao;
  render::FrameBinding mFrame; ///< the frame path's block, or its own when drawn alone
};

} // namespace sylva::scene
