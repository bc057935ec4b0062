#pragma once

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Query.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/ExactCoverage.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/TerrainMaps.hpp>

#include <shared/Terrain.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace sylva::terrain {

class GpuQuadtreeSelection;

/** What the terrain fragment shader shows. */
enum class TerrainView : int {
  Shaded = 0,
  LodColours = 1,
  Normals = 2,
  Splat = 3,
  /** World position (metres) in RGB, for float targets: what is drawn, to compare with CPU queries. */
  WorldPosition = 4,
  /**
   * Depth only (shadow casters; colour writes must be masked): on a field without holes whose patches stay
   * inside its extent, a fragment shader without discard or work, so the rasteriser can test depth before
   * shading; otherwise the WorldPosition program, which discards outside the data.
   */
  Depth = 5,
};

/**
 * A tint over the terrain's albedo (Shaded view): the far representation of a grass field, so the ground
 * keeps the field's colour where blades thin out with distance.
 */
struct GroundTint {
  /** Texture (first channel 0..1, linear filtering) whose sample (i, j) sits at world (i·spacing.x,
   * j·spacing.y); not owned, must outlive the draw; null: no tint. */
  const gl::Texture* texture = nullptr;
  glm::vec2 spacing{1.0f}; ///< metres between the texture's samples along x and z
  glm::ivec2 size{1};      ///< the texture's samples along x and z
  /** Linear colour the ground moves towards, and how far (0..1) where the map is 1. */
  glm::vec3 colour{0.2f, 0.4f, 0.1f};
  /** How far (0..1) the ground moves towards `colour` where the map is 1. */
  float strength = 0.85f;
};

/** Per-draw options of TerrainRenderer::draw. */
struct TerrainDrawOptions {
  TerrainView view = TerrainView::Shaded; ///< shaded, or one of the debug views (LOD levels, normals, …)
  bool wireframe = false;                 ///< draw the triangles' edges only
  /**
   * Crack check: after the surface, draw skirts (vertical curtains under every patch edge shared with other
   * terrain, magenta, pushed back by polygon offset) inside a GL_SAMPLES_PASSED query. Surface ∪ skirts is
   * the terrain's footprint; a skirt sample passes the depth test only where the surface in front of it has a
   * hole, i.e. where the background would show through. lastCrackSamples() is that count (0 = watertight).
   * Valid for cameras above the terrain whose view rays enter it from above (see docs/terrain-lod.md).
   */
  bool skirts = false;
  /** Skirt depth below the node's lowest height, metres. */
  float skirtDepth = 1000.0f;
  /** World metres per repeat of the layer textures. */
  float textureTiling = 24.0f;
  /**
   * Geomorphing: vertex heights blend continuously between the surfaces of two quadtree depths by distance
   * to the selection's camera (morphedHeight, docs/terrain-lod.md "Geomorphing"), so patches that split or
   * merge do not pop. Crack-free like the plain surface (the height is a function of world xz and the
   * camera). Off by default: the plain bilinear surface, byte-identical to earlier images.
   */
  bool geomorph = false;
  /**
   * Draw every tessellated vertex as a 1-pixel point instead of triangles (no skirts, no water): with
   * TerrainView::WorldPosition each covered pixel holds one vertex's exact world position, for tests. The
   * point program is compiled on first use from the shader library last given to the constructor or
   * reloadShaders(), which must still be alive then.
   */
  bool vertexPoints = false;
  /** Count tessellation-evaluation invocations (GL_ARB_pipeline_statistics_query) when available. */
  bool countVertices = false;
  /** Sun, sky, fog and shadows of the frame. */
  render::Environment environment{};
  /**
   * World height (metres, already exaggerated) of a still water surface drawn over the samples below it, in
   * the Shaded view; nullopt = no water.
   */
  std::optional<float> waterLevel;
  /** Ground tint (grass far representation); nullopt = none. */
  std::optional<GroundTint> groundTint;
};

/**
 * Packs a selection into the GPU node array: one surface patch per leaf, then (with `skirts`) one skirt patch
 * per leaf edge that borders terrain inside [0, extentX] × [0, extentZ] (never the outer border). Pure CPU.
 */
std::vector<gpu::TerrainNode> packTerrainNodes(const QuadtreeSelection& selection, float extentX,
                                               float extentZ, bool skirts);

/** A tileable procedural albedo texture (RGBA8, size² texels) for a splat layer, chosen by its name. */
Image proceduralLayerTexture(const SplatLayer& layer, int index, int size = 256);

/**
 * The terrain on the GPU. Construction uploads the heights (absent samples filled from valid neighbours for
 * geometry, plus a validity mask), then runs the Sobel normal-map and splat-map compute passes (CPU
 * references: sobelNormalMap, splatMap). draw() renders a Quadtree selection in one instanced draw of 4-point
 * patches with hardware tessellation; vertex heights are evaluated exactly as heightAt (bilinear) does, and
 * edge vertices lie on an integer lattice so that neighbours match bit for bit. Needs a current GL context.
 */
class TerrainRenderer {
public:
  /**
   * `verticalScale`: the factor by which `field`'s heights were exaggerated for display (1 = true heights);
   * the splat rules and the water's depth colours use true metres and slopes (see splatMap).
   */
  TerrainRenderer(const shader::Library& library, const HeightField& field, std::vector<SplatLayer> layers,
                  const SobelOptions& sobel = {}, float verticalScale = 1.0f);

  /** Recompiles all programs (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);
  /** Re-runs the normal and splat compute passes (e.g. after changing the layer rules). */
  void computeMaps(std::vector<SplatLayer> layers);
  /** Draws `selection` into the bound framebuffer (passes "terrain" and, with skirts, the skirts within it).
   */
  void draw(const QuadtreeSelection& selection, const render::Camera& camera, int width, int height,
            double time, render::GpuTimers* timers = nullptr, const TerrainDrawOptions& options = {});
  /**
   * Draws the leaves a GpuQuadtreeSelection left on the GPU with one indirect draw (no CPU readback), as the
   * overload above draws a CPU selection; skirts and vertexPoints are not drawn on this path, and depth-only
   * views use the program that discards outside the data.
   */
  void draw(const GpuQuadtreeSelection& selection, const render::Camera& camera, int width, int height,
            double time, render::GpuTimers* timers = nullptr, const TerrainDrawOptions& options = {});

  /**
   * The triangles draw() rasterises for `selection` with `options` (tag 0: surface, tag 1: skirt, drawn with
   * options.skirts), as clip-space positions captured by transform feedback with the rasteriser off. The
   * capture program is the surface program's text and gl_Position is invariant, so the positions equal the
   * drawn ones bit for bit. For exact-coverage checks (render::exactCoverage) in tests; slow (a readback).
   */
  std::vector<render::ClipTriangle> captureTriangles(const QuadtreeSelection& selection,
                                                     const render::Camera& camera, int width, int height,
                                                     const TerrainDrawOptions& options = {});

  /** Skirt samples that passed the depth test in the last draw with skirts (crack pixels), else -1. */
  std::int64_t lastCrackSamples() const { return mLastCrackSamples; }
  /** Tessellation-evaluation invocations of the last draw with countVertices (-1 when not supported). */
  std::int64_t lastVertexInvocations() const { return mLastInvocations; }
  /**
   * The GPU normal map as an RGB F32 image (pixel (i, j) = sample (i, j)), for tests and exports. Stored as
   * RG16_SNORM (x, z; y = sqrt(1 − x² − z²) ≥ 0, as every height-field normal points up): 4 bytes a sample.
   */
  Image downloadNormals() const;
  /** The GPU splat pages as RGBA F32 images (page k = layers 4k..4k+3), stored as RGBA8 (steps of 1/255). */
  std::vector<Image> downloadSplat() const;
  /** The splat layers the renderer was built with. */
  const std::vector<SplatLayer>& layers() const { return mLayers; }

private:
  /** Uniforms, textures, program and the surface draw (instanced, or indirect from `indirect`); the program.
   */
  /** Which surface program drawSurface uses (vertexPoints overrides all but Capture). */
  enum class SurfaceProgram { Shaded, DepthOnly, Capture };
  gl::Program& drawSurface(const QuadtreeConfig& lod, const glm::vec3& selectionCamera,
                           SurfaceProgram program, GLsizei patches, const gl::Buffer* indirect,
                           const render::Camera& camera, int width, int height, double time,
                           const TerrainDrawOptions& options);
  /** Packs and uploads the nodes of `selection` (with skirts as asked); the node count. */
  std::size_t uploadNodes(const QuadtreeSelection& selection, bool skirts);
  void uploadLayerTextures();

  /** The field's shape only: its heights live in the textures (no CPU copy is kept). */
  struct Shape {
    int width = 0;
    int height = 0;
    float spacingX = 1.0f;
    float spacingZ = 1.0f;
    float extentX = 0.0f;
    float extentZ = 0.0f;
  };
  Shape mField;
  std::vector<SplatLayer> mLayers;
  SobelOptions mSobel;
  float mMinHeight = 0.0f;
  float mMaxHeight = 0.0f;
  gl::Program mSurface{gl::NoCreate};
  gl::Program mSurfacePoints{gl::NoCreate};  // point_mode variant, compiled on first use
  gl::Program mSurfaceDepth{gl::NoCreate};   // TerrainView::Depth variant, compiled on first use
  gl::Program mSurfaceCapture{gl::NoCreate}; // transform-feedback variant for captureTriangles
  bool mHoles = false;                       // some sample is nodata
  const shader::Library* mLibrary = nullptr;
  gl::Program mNormals{gl::NoCreate};
  gl::Program mSplat{gl::NoCreate};
  gl::Program mWater{gl::NoCreate};
  float mVerticalScale = 1.0f;
  gl::Texture mHeights;
  gl::Texture mValid;
  gl::Texture mNormalMap;
  gl::Texture mSplatMap{gl::NoCreate};
  gl::Texture mLayerAlbedo{gl::NoCreate};
  gl::Buffer mUniforms;
  gl::Buffer mRules;
  gl::Buffer mNodes{gl::NoCreate};
  gl::VertexArray mVao;
  gl::Query mInvocations{gl::NoCreate};
  gl::Query mCrackSamples{gl::NoCreate};
  std::int64_t mLastCrackSamples = -1;
  render::FrameBinding mFrame; ///< the frame path's block, or its own when drawn alone
  std::int64_t mLastInvocations = -1;
};

} // namespace sylva::terrain
