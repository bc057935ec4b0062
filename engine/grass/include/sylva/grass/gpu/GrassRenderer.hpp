#pragma once
// The grass field on the GPU (docs/grass.md): the patch, blade types, tile ranges and the baked density in
// buffers and textures; per frame three compute passes cull tiles and blades into per-level instance lists
// with their indirect draw commands, and one glMultiDrawArraysIndirect draws the whole field. Blades are
// expanded to triangle strips and bent by the wind in the vertex shader (CPU reference: expandBlade), and
// shaded with Phong, translucency and root occlusion. Needs a current GL context.

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Query.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/grass/Cull.hpp>
#include <sylva/grass/Expand.hpp>
#include <sylva/grass/GrassField.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>
#include <sylva/wind/Wind.hpp>

#include <shared/Grass.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace sylva::grass {

class GrassSimulator;

/** What the blade fragment shader shows. */
enum class GrassView : int {
  Shaded = 0,
  /** Level of detail: red 16 knots, green 8, blue 4; cross-fading instances mixed. */
  LodColours = 1,
  /** A colour per tile, to see the tiles and their ranges; simulated tiles white (fading back as they are
   * released). */
  Tiles = 2,
};

/** Per-draw options. */
struct GrassDrawOptions {
  /** Shaded, or a debug view. */
  GrassView view = GrassView::Shaded;
  /** Sun, sky, fog and shadows of the frame. */
  render::Environment environment{};
  /** The wind the blades bend in. */
  wind::WindSettings wind{};
  /** Count submitted vertices and primitives (GL_ARB_pipeline_statistics_query) when available. */
  bool countPrimitives = false;
};

/** The grass field's GPU state. */
class GrassRenderer {
public:
  /** Uploads `field` (patch, blade types, density and terrain maps) and sizes the instance lists for
   * `settings`. */
  GrassRenderer(const shader::Library& library, std::shared_ptr<const GrassField> field,
                const CullSettings& settings = {});

  /** Recompiles the programs (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);
  /** New culling settings (validated); the instance lists grow when the draw distance needs more room. */
  void setCullSettings(const CullSettings& settings);
  /** The culling settings in use. */
  const CullSettings& cullSettings() const { return mSettings; }

  /**
   * Draws the tiles `simulation` simulates from its pool (one more list in the same draw); null: none. Not
   * owned; it must outlive its use here.
   */
  void setSimulation(const GrassSimulator* simulation);
  /** Binds what the field's shaders read (uniform block, patch, blade types, terrain and density textures).
   */
  void bindFieldResources() const;

  /** Runs the culling passes for `camera` at `aspect` (width / height); wind time for the draw comes later.
   */
  void cull(const render::Camera& camera, float aspect, render::GpuTimers* timers = nullptr);
  /** Draws the last cull's lists into the bound framebuffer (one draw call). */
  void draw(const render::Camera& camera, int width, int height, double time,
            render::GpuTimers* timers = nullptr, const GrassDrawOptions& options = {});

  /** The command buffer of the last cull: per-level draw commands, visible tiles, statistics (synchronous).
   */
  gpu::GrassCounters readCounters() const;
  /** Vertices and primitives submitted by the last draw with countPrimitives; -1 when not counted. */
  std::int64_t lastVerticesSubmitted() const { return mLastVertices; }
  /** Primitives submitted by the last draw with countPrimitives; -1 when not counted. */
  std::int64_t lastPrimitivesSubmitted() const { return mLastPrimitives; }
  /** The instance lists of the levels (not the simulated list) of the last cull, for tests. */
  std::vector<VisibleBlade> readInstances() const;

  /**
   * Runs `instances` through the real blade vertex shader (compiled with SYLVA_GRASS_CAPTURE, drawn as points
   * with rasterisation off) and returns each instance's vertices as the shader computed them, in
   * expandBlade's order, with the wind of `wind` at `time` seconds: the expansion parity test's GPU side.
   * A complete framebuffer must be bound (nothing is drawn into it).
   */
  std::vector<std::vector<BladeVertex>> captureExpansion(const std::vector<VisibleBlade>& instances,
                                                         const wind::WindSettings& wind, double time);

  /** The baked density (r32f over the terrain's footprint), for the terrain's ground tint. */
  const gl::Texture& densityTexture() const { return mDensity; }
  /** The ground tint matching this field (its density map and average colour): its far representation. */
  terrain::GroundTint groundTint(float strength = 0.85f) const;
  /** The average linear colour of the field's blades (weighted by the patch's type frequencies). */
  glm::vec3 averageColour() const { return mAverageColour; }
  /** Instances each level's list holds. */
  std::size_t capacity() const { return mCapacity; }
  /** Bytes of GPU memory held (patch, types, maps, lists). */
  std::size_t gpuBytes() const;
  /** The field drawn. */
  const GrassField& field() const { return *mField; }
  /** The field drawn, shared. */
  const std::shared_ptr<const GrassField>& fieldPointer() const { return mField; }

private:
  void uploadUniforms(const render::Camera& camera, float aspect, const wind::WindSettings& wind, double time,
                      GrassView view);
  void bindCommon() const;
  void uploadConstants();

  std::shared_ptr<const GrassField> mField;
  const GrassSimulator* mSimulation = nullptr;
  gl::Buffer mNoSimulation{gl::NoCreate};
  CullSettings mSettings;
  std::size_t mCapacity = 0;
  glm::vec3 mAverageColour{0.0f};
  gl::Program mTiles{gl::NoCreate};
  gl::Program mBlades{gl::NoCreate};
  gl::Program mFinish{gl::NoCreate};
  gl::Program mDraw{gl::NoCreate};
  gl::Program mCapture{gl::NoCreate};
  gl::Buffer mUniforms;
  gl::Buffer mPatch;
  gl::Buffer mTypes;
  gl::Buffer mVisibleTiles{gl::NoCreate};
  gl::Buffer mInstances{gl::NoCreate};
  gl::Buffer mCommands;
  gl::Texture mHeights;
  gl::Texture mValid;
  gl::Texture mDensity;
  gl::VertexArray mVao;
  render::FrameBinding mFrame; ///< the frame path's block, or its own when drawn alone
  gl::Query mVerticesQuery{gl::NoCreate};
  gl::Query mPrimitivesQuery{gl::NoCreate};
  std::int64_t mLastVertices = -1;
  std::int64_t mLastPrimitives = -1;
  gpu::GrassUniforms mLast{};
};

/** The blade-type table as the GPU holds it (knots of the three levels, colour, stiffness, length). */
std::vector<gpu::GrassTypeGpu> packBladeTypes(const std::vector<BladeType>& types);

} // namespace sylva::grass
