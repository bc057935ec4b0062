#pragma once
// Trees on the GPU (docs/trees.md, seed 000 §4): the piece meshes of a forest in one vertex and index buffer,
// every piece instance of every tree in one instance buffer, every joint of every tree in one frame buffer.
// Per frame a culling compute pass writes the indirect commands of every piece type (all instances of a type
// in each; a type's quads in chunks of quadsPerCommand() for the cull's largest level, Tessellation.hpp) and
// one glMultiDrawElementsIndirect draws them all as quad patches: skinned in the vertex
// shader, Phong-tessellated by distance in the tessellation shaders, lit in the fragment shader. Needs a
// current GL context.

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/Forest.hpp>

#include <shared/Trees.h>

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace sylva::trees {

/** What the fragment shader shows. */
enum class TreeView : int {
  Shaded = 0,
  /** A colour per piece type (I red, Y green, Psi blue, Branch yellow, Cap magenta, Foot cyan). */
  PieceTypes = 1,
  /** The root joint's skinning weight: white on the root rim, black on leaf rims (paper Fig. 5). */
  Bones = 2,
  /** Tessellation level: blue (1) to red (64). */
  LodLevels = 3,
  /**
   * Bark tiles as ids, unlit, for tests and debugging: red = the tile (layer within the bark set), green =
   * the quad id (patch), blue = the piece instance index's low 5 bits | the sub-tile along the quad's grain
   * (mod 8) << 5, alpha = 1 + the instance index >> 5 (so alpha 0 is background), each / 255.
   */
  Tiles = 4,
  /**
   * Depth only (shadow casters; colour writes must be masked): a fragment shader that does only the far
   * field's dissolve, none of the bark's texturing and lighting.
   */
  Depth = 5,
};

/** Which faces to draw (trees are closed surfaces, so back faces are hidden and culled by default). */
enum class TreeFaces { Front, Back, Both };

/** Level of detail: the distance rule of the tessellation (docs/trees.md). */
struct TreeLod {
  /** Target length of a tessellated segment on screen, pixels. */
  float pixelsPerSegment = 6.0f;
  /** Largest tessellation level (1 … 64). */
  float maxLevel = 16.0f;
  /** > 0: every edge and the inside get this level (tests, benchmarks); 0: the distance rule. */
  float fixedLevel = 0.0f;
  /** Pieces whose bounding sphere lies farther than this are not drawn, metres (0: no limit). */
  float drawDistance = 0.0f;
  /**
   * Far field, metres from the camera to a tree's crown centre: from x on a tree dissolves into its impostor
   * (shaders/trees/fade.glsl), from y on only the impostor is drawn; y <= x: no far field.
   */
  glm::vec2 farRange{0.0f};
  /**
   * Size culling: a piece whose bounding sphere (bends included) spans fewer pixels than this across is not
   * drawn. It could cover at most about one pixel, which its sample hits or misses; a distant tree's twigs
   * are thousands of such pieces, each paying its tessellation (docs/trees.md "Size culling"). 0 draws every
   * piece. Used by cull() with a target size: pixels of a perspective view, texels of an orthographic one (a
   * shadow cascade).
   */
  float minPixels = 1.0f;
  /**
   * Width culling: a piece whose root rim (the branch's thickness there, 2 · frame scale) spans fewer pixels
   * than this is not drawn, however long it is. A twig a fifth of a pixel wide is a dotted line whose
   * samples hit one pixel in five along it, and the foliage around it covers most of it; it still pays for
   * all its patches (docs/trees.md "Size culling"). 0 draws every piece; cull() with a target size only.
   */
  float minWidthPixels = 0.2f;
};

/** Per-draw options. */
struct TreeDrawOptions {
  /** Shaded, or a debug view. */
  TreeView view = TreeView::Shaded;
  /** Which faces are drawn: front, back or both (the watertightness check). */
  TreeFaces faces = TreeFaces::Front;
  /** Sun, sky, fog and shadows of the frame. */
  render::Environment environment{};
  /** Debug: shrink every root rim by 3 % so seams open (the watertightness test's control). */
  bool breakRims = false;
};

/** A forest's GPU state. */
class TreeRenderer {
public:
  /** Uploads `forest`'s pieces, instances and joints; needs a current context. */
  TreeRenderer(const shader::Library& library, std::shared_ptr<const Forest> forest);

  /** Recompiles the programs (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);

  /** Uploads all joint frames (Forest joint numbering, world space); see forestFrames(). */
  void setFrames(std::span<const gpu::JointFrame> frames);
  /** Reads frames from `external` instead (e.g. the wind pass's output; not owned); null: the own buffer. */
  void useFrames(const gl::Buffer* external);
  /** The joint frames the draws read (the external buffer when one is in use). */
  const gl::Buffer& framesBuffer() const { return mExternalFrames != nullptr ? *mExternalFrames : mFrames; }

  /**
   * Bark tiles (docs/trees.md "Bark"): every set's tiles go into one texture array; species s draws with set
   * speciesSet[s] (missing entries: set 0). All sets must have the same tile size and class layout. An empty
   * span goes back to flat bark colours. Throws sylva::Error for invalid sets.
   */
  void setBark(std::span<const BarkSet> sets, std::span<const int> speciesSet = {});
  /** Whether bark tiles are in use. */
  bool textured() const { return mBarkLayers > 0; }

  /** Per tree: base position (world xyz, metres) and crown height (w, metres), as at
   * SYLVA_TREE_CENTRE_BINDING. */
  const std::vector<glm::vec4>& treeCentres() const { return mCentres; }
  /** The buffer holding treeCentres(). */
  const gl::Buffer& centresBuffer() const { return mCentreBuffer; }

  /**
   * Culls every piece instance for `camera` at `aspect`, writing the indirect commands. No size culling:
   * for views without a pixel size (impostor bakes, tests of the frustum).
   */
  void cull(const render::Camera& camera, float aspect, const TreeLod& lod,
            render::GpuTimers* timers = nullptr);
  /**
   * As above for a `width` × `height` pixel target, also dropping pieces under lod.minPixels across.
   * `environment.frame`, when a frame path set it for `camera`, is the frame block the cull reads.
   */
  void cull(const render::Camera& camera, int width, int height, const TreeLod& lod,
            render::GpuTimers* timers = nullptr, const render::Environment& environment = {});
  /** Draws the last cull into the bound framebuffer: one glMultiDrawElementsIndirect for all piece types. */
  void draw(const render::Camera& camera, int width, int height, double time, const TreeLod& lod,
            render::GpuTimers* timers = nullptr, const TreeDrawOptions& options = {});
  /**
   * The baseline the paper's instancing is measured against: one draw call per piece instance (no culling),
   * same shaders and levels.
   */
  void drawPerPiece(const render::Camera& camera, int width, int height, double time, const TreeLod& lod,
                    const TreeDrawOptions& options = {});

  /** Visible instances per piece type after the last cull (synchronous readback). */
  std::vector<std::uint32_t> readVisibleCounts() const;
  /** The visible instance indices of piece type `type` (unordered), for tests. */
  std::vector<std::uint32_t> readVisible(std::size_t type) const;

  /** The forest drawn. */
  const Forest& forest() const { return *mForest; }
  /** The forest, shared (for passes that draw with this renderer, e.g. FoliageRenderer). */
  const std::shared_ptr<const Forest>& sharedForest() const { return mForest; }
  /** The instances, grouped by piece type. */
  const PackedInstances& instances() const { return mPacked; }
  /** Model-space bounding sphere (xyz centre, w radius; rim units) of piece type `type`. */
  glm::vec4 pieceSphere(std::size_t type) const { return mPieceTable[type].sphere; }
  /** Bytes of GPU memory held. */
  std::size_t gpuBytes() const;

private:
  void uploadUniforms(const render::Camera& camera, float aspect, const TreeLod& lod, TreeView view,
                      bool breakRims, glm::vec4 sizeCull = glm::vec4(0.0f));
  void runCull(const render::Camera& camera, float aspect, const TreeLod& lod, glm::vec4 sizeCull,
               render::GpuTimers* timers, const render::Environment& environment);
  void bindAll() const;
  /** Uniforms, frame block and bindings of a draw (both draw paths). */
  void prepareDraw(const render::Camera& camera, int width, int height, double time, const TreeLod& lod,
                   const TreeDrawOptions& options);
  void submit(const TreeDrawOptions& options, bool perPiece);
  /** Rebuilds the indirect commands and the piece table's command ranges for chunks of `quads` quads. */
  void useQuadsPerCommand(std::uint32_t quads);

  /** Where a piece type's quads lie in the index and vertex buffers. */
  struct PieceGeometry {
    std::uint32_t firstIndex;
    std::uint32_t baseVertex;
    std::uint32_t quads;
  };

  std::shared_ptr<const Forest> mForest;
  PackedInstances mPacked;
  std::vector<gpu::TreePieceGpu> mPieceTable;
  std::vector<PieceGeometry> mPieceGeometry;
  std::vector<std::uint32_t> mCommandsReset;
  std::uint32_t mQuadsPerCommand = 0;
  std::size_t mVertexBytes = 0;
  std::size_t mIndexBytes = 0;
  gl::Program mCull{gl::NoCreate};
  gl::Program mDraw{gl::NoCreate};
  gl::Program mDrawDepth{gl::NoCreate}; // TreeView::Depth
  gl::Buffer mVertices{gl::NoCreate};
  gl::Buffer mIndices{gl::NoCreate};
  gl::Buffer mInstances{gl::NoCreate};
  gl::Buffer mPieces{gl::NoCreate};
  gl::Buffer mVisible{gl::NoCreate};
  gl::Buffer mAll{gl::NoCreate};
  gl::Buffer mCommands{gl::NoCreate};
  gl::Buffer mFrames{gl::NoCreate};
  gl::Buffer mUniforms;
  gl::Buffer mQuadTable{gl::NoCreate};
  gl::Buffer mCentreBuffer{gl::NoCreate};
  std::vector<glm::vec4> mCentres;
  std::array<std::uint32_t, SYLVA_TREE_MAX_PIECES> mQuadFirst{};
  gl::Texture mBarkColour{gl::NoCreate};
  gl::Texture mBarkNormal{gl::NoCreate};
  std::uint32_t mBarkLayers = 0;
  int mBarkTileSize = 0;
  int mEdgeColours = 1;
  bool mBarkNormals = false;
  std::array<std::uint32_t, SYLVA_TREE_MAX_TILE_CLASSES> mTileFirst{};
  std::array<std::uint32_t, SYLVA_TREE_MAX_TILE_CLASSES> mTileCount{};
  std::array<std::uint32_t, SYLVA_TREE_MAX_SPECIES> mSpeciesSet{};
  const gl::Buffer* mExternalFrames = nullptr;
  gl::VertexArray mVao;
  gl::VertexArray mAllVao;
  render::FrameBinding mFrame; ///< the frame path's block, or its own when drawn alone
  gpu::TreeUniforms mLast{};
};

/** The GPU vertex of a piece (56 bytes): position, normal, weights, uv, joints, rim << 8 | corner (or -1). */
struct PieceVertexGpu {
  /** Position, model space (rim units). */
  float position[3];
  /** Unit normal, model space. */
  float normal[3];
  /** The four joints' weights. */
  float weights[4];
  /** u, v texture coordinates. */
  float uv[2];
  /** Up to four joint indices. */
  std::uint8_t joints[4];
  /** rim << 8 | corner, or -1 for interior vertices. */
  std::int32_t rim;
};
static_assert(sizeof(PieceVertexGpu) == 56);

} // namespace sylva::trees
