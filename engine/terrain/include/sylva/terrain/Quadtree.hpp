#pragma once

#include <sylva/core/Geometry.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/MinMax.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

/**
 * Quadtree LOD for tessellated terrain patches: the CPU side (no OpenGL).
 *
 * Questions answered, once per view: which square patches (quadtree leaves) cover the visible terrain, how
 * large is each, and which tessellation level does each patch edge get so that neighbouring patches of
 * different size share exactly the same edge vertices (no cracks / T-junctions)? See docs/terrain-lod.md.
 *
 * Spaces: world metres, y up; the terrain covers [0, extentX] × [0, extentZ] in x and z. A node at depth d
 * has size rootSize / 2^d metres and grid index (gridX, gridZ) in the depth-d grid of (rootsX·2^d) ×
 * (rootsZ·2^d) nodes; its footprint is [gridX·size, (gridX+1)·size] × [gridZ·size, (gridZ+1)·size].
 */
namespace sylva::terrain {

/** How edge tessellation levels are stitched between leaves of different depth. */
enum class CrackMethod : std::uint8_t {
  /** No stitching: every outer level is the base level. Leaves T-junctions; for tests and comparisons only.
   */
  None,
  /**
   * The paper's method: per leaf edge, find the same-depth neighbour square in the per-view tree (siblings in
   * O(1) through the parent, cousins by a top-down search from the root, O(depth)); a split neighbour means a
   * finer leaf across the edge and doubles that edge's level.
   */
  PaperSearch,
  /**
   * Ours: the same doubling rule, reading "was the same-depth neighbour square split?" from a per-view hash
   * of split nodes keyed by (depth, gridX, gridZ): O(1) per edge, no tree. Exact because the selection is
   * restricted (QuadtreeConfig::restrictSelection).
   */
  RestrictedLevelMap,
};

/** "none", "paper-search" or "restricted-level-map". */
const char* crackMethodName(CrackMethod method);

/**
 * Patch edge indices, equal to the gl_TessLevelOuter index of a quad patch whose domain u runs along +x and v
 * along +z (corner (u, v) = (0, 0) at world (x, z), (1, 1) at (x + size, z + size)).
 */
enum PatchEdge : int {
  kEdgeWest = 0,  ///< u = 0: the x-min edge
  kEdgeNorth = 1, ///< v = 0: the z-min edge
  kEdgeEast = 2,  ///< u = 1: the x-max edge
  kEdgeSouth = 3, ///< v = 1: the z-max edge
};

/** Highest base tessellation level: doubled edges reach 64, the minimum GL_MAX_TESS_GEN_LEVEL. */
inline constexpr int kMaxPatchTessLevel = 32;
/**
 * Smallest lodDistanceFactor accepted with restrictSelection: the restriction proof needs factor ≥ 1; the
 * extra 5 % keeps it robust to float rounding of distances.
 */
inline constexpr float kMinRestrictedLodFactor = 1.05f;
/**
 * Distance floor of the screen-space-error split rule, as a multiple of the node size: a node closer than
 * this splits whatever its error. The restriction proof needs a floor ≥ 1 (docs/terrain-lod.md, "Screen-space
 * error").
 */
inline constexpr float kErrorLodDistanceFloor = kMinRestrictedLodFactor;
/** Pixels per radian of a 720-pixel-high view with a 50° vertical field of view: 360 / tan(25°). */
inline constexpr float kDefaultPixelsPerRadian = 772.0f;
/** Largest node grid at the deepest level (nodes), bounding the min/max memory. */
inline constexpr long long kMaxQuadtreeLeafNodes = 1LL << 24;

/** Layout and LOD policy of a terrain quadtree. */
struct QuadtreeConfig {
  /** Root nodes along x; 0 derives ⌈extentX / rootSize⌉. */
  int rootsX = 0;
  /** Root nodes along z; 0 derives ⌈extentZ / rootSize⌉. */
  int rootsZ = 0;
  /** World size of a root node (metres, square). */
  float rootSize = 256.0f;
  /** Deepest depth a node may reach (0 = roots only); leaves are at most rootSize / 2^maxDepth metres. */
  int maxDepth = 5;
  /**
   * A node splits when the 3D distance (metres) from the camera to its LOD box is below factor × node size.
   * The LOD box is the node footprint × a height range (see restrictSelection). ≥ kMinRestrictedLodFactor
   * when restrictSelection, > 0 otherwise.
   */
  float lodDistanceFactor = 2.0f;
  /**
   * Screen-space-error LOD: > 0 splits a node while its geometric error (Quadtree::nodeError, metres) seen
   * from the camera projects to more than this many pixels, or while the camera is closer than
   * kErrorLodDistanceFloor × its size; lodDistanceFactor is then unused. 0 (the default): distance LOD.
   * At most 1000.
   */
  float lodErrorPixels = 0.0f;
  /**
   * Projection of the view the error is measured in: pixels per radian at the image centre, viewport height
   * / (2·tan(fovY / 2)); see pixelsPerRadianFor(). Only used when lodErrorPixels > 0.
   */
  float pixelsPerRadian = kDefaultPixelsPerRadian;
  /** Base tessellation level of every patch edge and of the inner levels, 1..kMaxPatchTessLevel. */
  int patchTessLevel = 16;
  /** False: draw every present root at depth 0 regardless of distance (the paper's "LOD disabled" rows). */
  bool lodEnabled = true;
  /** How neighbour levels are found and edges stitched. */
  CrackMethod method = CrackMethod::RestrictedLevelMap;
  /** Drop nodes whose AABB is outside the frustum passed to select() (ignored when it passes none). */
  bool frustumCull = true;
  /**
   * True: the LOD box height range is the union of the node's and its 8 same-depth neighbours' ranges, which
   * guarantees that edge-adjacent leaves differ by at most one depth (docs/terrain-lod.md has the proof).
   * False: the node's own range (plain CDLOD box distance); steep terrain can then give unrestricted
   * selections on which no doubling rule is crack-free. Only for tests and comparisons.
   */
  bool restrictSelection = true;

  /**
   * A config with rootCount roots (e.g. the paper's 4, 16, 32, 64) for a terrain of extentX × extentZ metres:
   * picks the factorisation rootsX·rootsZ = rootCount with the least area outside the terrain (32 over a
   * square gives 8×4) and the smallest rootSize that covers the extent. Roots wholly outside the data are
   * dropped by select(). Throws sylva::Error for rootCount < 1 or a non-positive extent.
   */
  static QuadtreeConfig forRootCount(int rootCount, float extentX, float extentZ);
  /** Pixels per radian of a view `viewportHeightPx` pixels high with vertical field of view `fovY` radians.
   */
  static float pixelsPerRadianFor(float viewportHeightPx, float fovY);
  /**
   * Spacing of the vertices of the deepest patches, metres: rootSize / (2^maxDepth · patchTessLevel). The
   * surface drawn at that depth everywhere is the reference of the screen-space error ("full resolution").
   */
  float finestVertexSpacing() const;
  /**
   * This layout with every node split down to maxDepth (distance LOD with an unbounded factor, no error
   * LOD): the full-resolution reference view of the screen-space error measures.
   */
  QuadtreeConfig fullDepth() const;
};

/** One patch to draw: a selected quadtree leaf. */
struct SelectedNode {
  /** World x of the patch's min corner (metres). */
  float x = 0.0f;
  /** World z of the patch's min corner (metres). */
  float z = 0.0f;
  /** Edge length (metres); the patch spans (x, z) … (x + size, z + size). */
  float size = 0.0f;
  /** Lowest valid height inside the patch footprint (metres). */
  float minY = 0.0f;
  /** Highest valid height inside the patch footprint (metres). */
  float maxY = 0.0f;
  /** Depth in the quadtree (0 = root). */
  int level = 0;
  /** Index of the node in the depth-`level` grid along x. */
  int gridX = 0;
  /** Index of the node in the depth-`level` grid along z. */
  int gridZ = 0;
  /**
   * Geometric error of drawing this patch at its depth (Quadtree::nodeError, metres); 0 when the quadtree
   * has not computed errors (distance LOD).
   */
  float error = 0.0f;
  /** Bit e (PatchEdge) set when the leaf across edge e is one depth finer and the edge level was doubled. */
  std::uint32_t edgeFlags = 0;
  /** gl_TessLevelOuter[0..3] in PatchEdge order: base level, or twice it on flagged edges. */
  std::array<float, 4> tessOuter{};
  /** gl_TessLevelInner[0] and [1]: the base level. */
  float tessInner = 0.0f;
};

/**
 * Triangles the GPU tessellator makes for `node`'s quad patch with equal spacing (OpenGL 4.5 §11.2.2.2):
 * 2 when every level is 1; otherwise, with the inner level n (1 counts as 2), 2(n−2)² + 4(n−2) + Σ outer.
 */
std::uint64_t patchTriangles(const SelectedNode& node);

/** Identifies a quadtree node: depth and grid index. */
struct NodeId {
  /** Depth (0 = root). */
  int level = 0;
  /** Grid index along x at that depth. */
  int gridX = 0;
  /** Grid index along z at that depth. */
  int gridZ = 0;
  /** Same depth and grid indices. */
  bool operator==(const NodeId&) const = default;
};

/** Counters of one select() call. */
struct QuadtreeStats {
  /** Nodes with data whose bounds were tested (roots and children of split nodes). */
  int nodesVisited = 0;
  /** Visited nodes dropped by the frustum test (their subtrees are not visited). */
  int nodesCulled = 0;
  /** Candidate nodes dropped because their footprint holds no valid sample (outside the data). */
  int nodesAbsent = 0;
  /** Nodes that split. */
  int nodesSplit = 0;
  /** Selected leaves (= nodes.size()). */
  int leaves = 0;
  /** Leaf edges whose level was doubled. */
  int doubledEdges = 0;
  /** Work spent finding neighbours: tree nodes stepped through (PaperSearch) or hash probes (level map). */
  long long neighbourSteps = 0;
  /** Patch control points submitted: 4 per leaf. */
  std::uint64_t controlPoints = 0;
  /**
   * Processed vertex estimate: Σ over leaves of (tessInner + 1)², the vertices of a quad domain tessellated
   * at the base level (doubled edges add at most base level vertices per edge). This is what the tessellation
   * evaluation stage runs per view; the paper's "processed vertices (CPU)" column is not reproducible.
   */
  std::uint64_t processedVertices = 0;
};

/** Result of one select() call. */
struct QuadtreeSelection {
  /** Patches to draw, in traversal order (deterministic). */
  std::vector<SelectedNode> nodes;
  /** Nodes dropped by the frustum test. */
  std::vector<NodeId> culled;
  /** Counters. */
  QuadtreeStats stats;
  /** Camera position the selection was made for (world metres); geomorphing morphs heights around it. */
  glm::vec3 camera{0.0f};
  /** The quadtree config (rootsX/Z resolved) the selection was made with: LOD distances for geomorphing. */
  QuadtreeConfig config{};
};

/**
 * Terrain quadtree over a grid of root nodes covering [0, extentX] × [0, extentZ] (metres). Owns per-node
 * min/max heights (a MinMaxPyramid whose leaf blocks are the deepest nodes) and per-view scratch buffers.
 * select() is not thread-safe (it reuses the scratch buffers); use one Quadtree per thread.
 */
class Quadtree {
public:
  /**
   * Builds the node min/max pyramid from `field` (sample (i, j) at x = i·spacingX, z = j·spacingZ). A node's
   * range covers the samples [⌊x0/spacingX⌋, ⌈x1/spacingX⌉] × [⌊z0/spacingZ⌋, ⌈z1/spacingZ⌉] that the
   * bilinear surface over its footprint depends on; nodes with no valid sample, or starting at or beyond the
   * extent, are absent. Throws sylva::Error for invalid configs, fields smaller than 2×2 samples, roots that
   * do not cover the extent, or more than kMaxQuadtreeLeafNodes deepest nodes.
   */
  Quadtree(const QuadtreeConfig& config, const HeightField& field);
  /**
   * Uses `nodeRanges`, a pyramid whose level 0 is the (rootsX·2^maxDepth) × (rootsZ·2^maxDepth) grid of
   * deepest nodes (e.g. built with MinMaxPyramid::fromLeaves from a coarse source or an analytic bound, for
   * terrains too large to hold as floats). config.rootsX/Z must be given or derivable from the extent. Throws
   * sylva::Error on a shape mismatch or invalid config.
   */
  Quadtree(const QuadtreeConfig& config, float extentX, float extentZ, MinMaxPyramid nodeRanges);

  /** The config in use, with rootsX/rootsZ resolved. */
  const QuadtreeConfig& config() const { return mConfig; }
  /**
   * Changes the per-view policy (lodDistanceFactor, lodErrorPixels, pixelsPerRadian, patchTessLevel,
   * lodEnabled, method, frustumCull, restrictSelection). Throws sylva::Error if the layout (rootsX, rootsZ,
   * rootSize, maxDepth) differs (0 for rootsX/Z means "keep"), a value is invalid, or it asks for
   * screen-space-error LOD at a patchTessLevel the node errors were not computed for (canSetConfig()).
   */
  void setConfig(const QuadtreeConfig& config);
  /**
   * Height range of the LOD box the split rule measures `node`'s distance to (metres): the union over its
   * 3×3 same-depth neighbourhood when config().restrictSelection, else its own range. Absent outside the
   * grid.
   */
  HeightRange lodBoxRange(const NodeId& node) const;
  /**
   * The error the screen-space-error split rule reads for `node` (metres): the largest nodeError over its 3×3
   * neighbourhood when config().restrictSelection, else its own; 0 without errors or outside the grid.
   */
  float lodRuleError(const NodeId& node) const;
  /**
   * True when setConfig(config) would succeed: same layout and, for screen-space-error LOD, node errors
   * computed for its patchTessLevel. Otherwise build a new Quadtree from the heights.
   */
  bool canSetConfig(const QuadtreeConfig& config) const;

  /** Terrain extent along x, metres. */
  float extentX() const { return mExtentX; }
  /** Terrain extent along z, metres. */
  float extentZ() const { return mExtentZ; }
  /** Node edge length at `level`, metres. */
  float nodeSize(int level) const;
  /** Nodes along x at `level`. */
  int gridWidth(int level) const { return mConfig.rootsX << level; }
  /** Nodes along z at `level`. */
  int gridHeight(int level) const { return mConfig.rootsZ << level; }
  /** Height range of a node (metres); absent outside the grid or the data. O(1). */
  HeightRange nodeRange(const NodeId& node) const;
  /** World AABB of a node: footprint × nodeRange (y is NaN when absent). */
  Aabb nodeBounds(const NodeId& node) const;
  /**
   * Geometric error of drawing `node` at its depth, metres: an upper bound on the vertical distance between
   * the patch as tessellated at the base level (a triangulation of the bilinear heights on a lattice of
   * spacing size / patchTessLevel) and the surface the deepest patches draw there (the same on the finest
   * lattice, QuadtreeConfig::finestVertexSpacing, triangulated either way), over the node's footprint; at
   * least the error of each of its children (saturated); 0 at the deepest level. With the finest lattice at
   * the sample spacing the reference is the full-resolution mesh of the samples. 0 outside the grid or the
   * data, and when hasNodeErrors() is false.
   */
  float nodeError(const NodeId& node) const;
  /**
   * True when the node errors were computed: by the HeightField constructor when its config asks for
   * screen-space-error LOD (lodErrorPixels > 0; O(samples × depths), in parallel). They hold for the
   * patchTessLevel of that config (nodeErrorTessLevel()).
   */
  bool hasNodeErrors() const { return !mError.empty(); }
  /** The base tessellation level the node errors were computed for; 0 without errors. */
  int nodeErrorTessLevel() const { return mErrorTess; }

  /**
   * Selects the leaves to draw for a camera at `cameraPos` (world metres), culling against `frustum` when it
   * is not null and config().frustumCull is set, and computes edge tessellation levels with config().method.
   */
  QuadtreeSelection select(const glm::vec3& cameraPos, const Frustum* frustum);
  /** As above, reusing the vectors in `out` (no allocation once they are large enough). */
  void select(const glm::vec3& cameraPos, const Frustum* frustum, QuadtreeSelection& out);

  /** Bytes of the per-node min/max data (node pyramid + LOD height ranges); excludes per-view scratch. */
  std::size_t memoryBytes() const;

private:
  struct TreeNode {
    std::int32_t gridX;
    std::int32_t gridZ;
    std::int32_t parent;
    std::int32_t level;
    std::array<std::int32_t, 4> child; // index (childZ&1)·2 + (childX&1); -1 absent or culled
    bool split;
  };
  struct StackItem {
    std::int32_t level;
    std::int32_t gridX;
    std::int32_t gridZ;
    std::int32_t parent;
    std::int32_t slot;
  };

  void init(const QuadtreeConfig& config, float extentX, float extentZ, bool needRoots);
  void buildErrors(const HeightField& field);
  void buildLodRanges();
  HeightRange lodRange(int level, int gridX, int gridZ) const;
  bool paperFinerNeighbour(std::int32_t treeIndex, int edge, long long& steps) const;
  void buildSplitHash(std::size_t count);
  bool splitHashContains(std::uint64_t key, long long& steps) const;

  QuadtreeConfig mConfig;
  float mExtentX = 0.0f;
  float mExtentZ = 0.0f;
  std::vector<float> mSizes;                   // node size per depth, metres
  MinMaxPyramid mRanges;                       // level k = depth maxDepth − k
  std::vector<std::vector<HeightRange>> mLodY; // per depth: union over the 3×3 same-depth neighbourhood
  std::vector<std::vector<float>> mError;      // per depth: saturated node error (metres)
  std::vector<std::vector<float>> mLodError;   // per depth: max of mError over the 3×3 neighbourhood
  int mErrorTess = 0;                          // patchTessLevel the errors hold for (0: none)

  // Per-view scratch.
  std::vector<StackItem> mStack;
  std::vector<TreeNode> mTree;
  std::vector<std::int32_t> mRootNode;
  std::vector<std::int32_t> mLeafTree;
  std::vector<std::uint64_t> mSplitKeys;
  std::vector<std::uint64_t> mHash;
  int mHashShift = 64;
};

} // namespace sylva::terrain
