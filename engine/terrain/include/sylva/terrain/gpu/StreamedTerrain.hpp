#pragma once

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Query.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/Environment.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/TileSelection.hpp>
#include <sylva/terrain/TileStreamer.hpp>

#include <shared/Terrain.h>

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

namespace sylva::terrain {

/** Default GPU budget of streamed tiles, bytes (`--gpu-budget` in MB). */
inline constexpr std::size_t kDefaultGpuBudget = std::size_t{256} << 20;

/** Budgets and policy of a StreamedTerrain. */
struct StreamedTerrainOptions {
  /** Bytes of the tile texture array (fixed at construction: its layers are the GPU cache). */
  std::size_t gpuBudget = kDefaultGpuBudget;
  /** Bytes of tiles in RAM (TileStreamer); must hold the GPU's tiles and 64 more. */
  std::size_t ramBudget = kDefaultRamBudget;
  int loaders = 2;          ///< background loader threads
  TileLodConfig lod;        ///< which tiles a view wants
  int uploadsPerFrame = 32; ///< most tiles copied to the GPU per update() (bounds a frame's upload time)
  /**
   * Seconds of the camera's motion to look ahead: update() also requests the tiles the view will want at
   * eye + velocity · prefetchSeconds (at a lower priority than the current view's).
   */
  float prefetchSeconds = 1.5f;
  int patchLevel = 32; ///< tessellation level P of a patch (T / P patches per tile edge); even, divides T
};

/** What one update() did. */
struct StreamedFrame {
  int tiles = 0;              ///< tiles drawn
  int missing = 0;            ///< tiles the view wanted that were not on the GPU (stand-ins drawn)
  bool waited = false;        ///< missing > 0: some of the view waits for tiles
  int uploads = 0;            ///< tiles copied to the GPU
  int layersUsed = 0;         ///< texture-array layers holding a tile
  std::uint64_t vertices = 0; ///< vertices the tessellator makes for the drawn tiles (CPU count)
};

/** Views of StreamedTerrain::draw. */
enum class StreamedView : int {
  Shaded = 0,        ///< meadow, rock and snow by height and slope, sun and haze
  LevelColours = 1,  ///< tinted by tile level
  WorldPosition = 4, ///< position relative to origin() in RGB (float targets): tests
  Normal = 5,        ///< unit normal in RGB, tile level + 1 in alpha (float targets): tests
};

/**
 * Terrain streamed from a TileSource within fixed GPU and RAM budgets (docs/terrain-data.md, "Streaming").
 * Each update() selects the tiles the view wants (selectTiles: only tiles on the GPU, restricted), asks the
 * streamer for the missing ones and for those the camera's motion will want (prefetch), copies up to
 * uploadsPerFrame loaded tiles into free or least recently used texture-array layers, and selects again, so a
 * frame never waits: coarser tiles stand in until finer ones arrive. draw() draws the selection in one
 * instanced draw of tessellated patches whose vertices are the tiles' samples; a tile edge next to a coarser
 * tile keeps every second vertex, which meets the coarser tile exactly (no cracks). Positions are relative
 * to origin(), a level-0 sample near the camera, so worlds of 1,000 km keep float precision. Needs a current
 * GL context.
 */
class StreamedTerrain {
public:
  /** Throws sylva::Error when the budgets do not fit (GPU layers, RAM for them) or T is not a multiple of P.
   */
  StreamedTerrain(const shader::Library& library, std::shared_ptr<const TileSource> source,
                  const StreamedTerrainOptions& options = {});
  ~StreamedTerrain();
  StreamedTerrain(const StreamedTerrain&) = delete;
  StreamedTerrain& operator=(const StreamedTerrain&) = delete;

  /**
   * Chooses and uploads tiles for `camera` (world metres, double) moving at `velocity` (m/s), as seen with
   * `fovY` radians, `aspect` and `farPlane` metres; sets origin().
   */
  StreamedFrame update(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& velocity,
                       float fovY, float aspect, float farPlane);
  /** update() until nothing is missing (blocking on the loaders): a complete view, for stills and tests. */
  StreamedFrame updateComplete(const glm::dvec3& eye, const glm::dvec3& target, float fovY, float aspect,
                               float farPlane);
  /**
   * Draws the last update()'s tiles into the bound framebuffer with `camera` (relative to origin(): use
   * relativeCamera()). `points`: every vertex as a 1-pixel point (tests).
   */
  void draw(const render::Camera& camera, int width, int height, double time,
            StreamedView view = StreamedView::Shaded, const render::Environment& environment = {},
            bool points = false);
  /**
   * Sun and haze for a view `viewDepth` metres deep (the distance that matters: 30 km over the procedural
   * world, a pyramid's extent): Environment's defaults with a fog density of 1.6 / viewDepth per metre (20 %
   * of the colour left at viewDepth).
   */
  static render::Environment wideEnvironment(double viewDepth);
  /** The colour to clear to behind the terrain: the haze colour as the shader writes it (sRGB-encoded). */
  static glm::vec4 clearColour(const render::Environment& environment);
  /** The camera update() was given, relative to origin(). */
  render::Camera relativeCamera(float fovY, float nearPlane, float farPlane) const;
  /** World position (metres) of the render origin: positions drawn are relative to it in x and z. */
  glm::dvec3 origin() const { return mOrigin; }
  /**
   * Height (metres) of the drawn surface at world (x, z): bilinear over the samples of the drawn tile that
   * covers (x, z), equal to the drawn vertices at sample positions; where no drawn tile covers it (culled,
   * e.g. under the camera), the finest tile on the GPU there; NaN outside the world.
   */
  float drawnHeightAt(double x, double z) const;
  /** The last selection. */
  const TileSelection& selection() const { return mSelection; }
  /** The streamer (RAM cache and loader counters). */
  const TileStreamer& streamer() const { return *mStreamer; }
  /** Texture-array layers: the GPU budget in tiles. */
  int layers() const { return mLayerCount; }
  /** Bytes of one layer: (T + 1)² floats. */
  std::size_t layerBytes() const;
  /** The source's layout. */
  const PyramidInfo& layout() const { return mSource->layout(); }
  /** Whether tile `key` is in the GPU cache (drawable, and readable by its neighbours' normals). */
  bool onGpu(const TileKey& key) const { return mLayerOf.count(key) != 0; }

private:
  struct Layer {
    TileKey key;
    bool used = false;
    std::uint64_t lastFrame = 0;
  };
  int freeLayer();
  void upload(const TileKey& key, const TileData& tile, int layer);
  void requestView(const glm::dvec3& eye, const Frustum* frustum, float priorityOffset);

  std::shared_ptr<const TileSource> mSource;
  StreamedTerrainOptions mOptions;
  std::unique_ptr<TileStreamer> mStreamer;
  const shader::Library* mLibrary;
  gl::Program mProgram{gl::NoCreate};
  gl::Program mPoints{gl::NoCreate};
  gl::Texture mHeights{gl::NoCreate};
  gl::Buffer mTiles{gl::NoCreate};
  gl::Buffer mUniforms{sizeof(gpu::StreamUniforms)};
  gl::VertexArray mVao;
  render::FrameBinding mFrame;
  int mLayerCount = 0;
  std::vector<Layer> mLayers;
  std::map<TileKey, int> mLayerOf;
  std::uint64_t mFrameIndex = 0;
  TileSelection mSelection;
  glm::dvec3 mEye{0.0};
  glm::dvec3 mTarget{0.0};
  glm::dvec3 mOrigin{0.0};
  glm::ivec2 mOriginIndex{0};
};

} // namespace sylva::terrain
