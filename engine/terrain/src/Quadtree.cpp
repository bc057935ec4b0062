#include <sylva/terrain/Quadtree.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

namespace sylva::terrain {

namespace {

constexpr std::uint64_t kEmptyKey = ~std::uint64_t{0};
constexpr int kMaxDepthLimit = 24;
constexpr int kMaxRoots = 1 << 16;
// Neighbour offsets in PatchEdge order: west (x−1), north (z−1), east (x+1), south (z+1).
constexpr std::array<int, 4> kEdgeDx{-1, 0, 1, 0};
constexpr std::array<int, 4> kEdgeDz{0, -1, 0, 1};

std::uint64_t nodeKey(int level, int gridX, int gridZ) {
  return (static_cast<std::uint64_t>(level) << 58) | (static_cast<std::uint64_t>(gridX) << 29) |
         static_cast<std::uint64_t>(gridZ);
}

std::size_t hashSlot(std::uint64_t key, int shift) {
  return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ULL) >> shift);
}

void validatePolicy(const QuadtreeConfig& c) {
  if (c.patchTessLevel < 1 || c.patchTessLevel > kMaxPatchTessLevel) {
    fail("QuadtreeConfig.patchTessLevel: {} is outside 1..{} (doubled edges must stay ≤ 64)",
         c.patchTessLevel, kMaxPatchTessLevel);
  }
  if (!std::isfinite(c.lodDistanceFactor) || c.lodDistanceFactor <= 0.0f) {
    fail("QuadtreeConfig.lodDistanceFactor: {} must be a positive number", c.lodDistanceFactor);
  }
  if (c.restrictSelection && c.lodDistanceFactor < kMinRestrictedLodFactor) {
    fail("QuadtreeConfig.lodDistanceFactor: {} is below {} (needed for a restricted selection)",
         c.lodDistanceFactor, kMinRestrictedLodFactor);
  }
  if (!std::isfinite(c.lodErrorPixels) || c.lodErrorPixels < 0.0f || c.lodErrorPixels > 1000.0f) {
    fail("QuadtreeConfig.lodErrorPixels: {} is outside 0..1000 pixels (0 = distance LOD)", c.lodErrorPixels);
  }
  if (c.lodErrorPixels > 0.0f && !(std::isfinite(c.pixelsPerRadian) && c.pixelsPerRadian > 0.0f)) {
    fail("QuadtreeConfig.pixelsPerRadian: {} must be a positive number", c.pixelsPerRadian);
  }
  if (c.method != CrackMethod::None && c.method != CrackMethod::PaperSearch &&
      c.method != CrackMethod::RestrictedLevelMap) {
    fail("QuadtreeConfig.method: unknown crack method {}", static_cast<int>(c.method));
  }
}

} // namespace

const char* crackMethodName(CrackMethod method) {
  switch (method) {
  case CrackMethod::None:
    return "none";
  case CrackMethod::PaperSearch:
    return "paper-search";
  case CrackMethod::RestrictedLevelMap:
    return "restricted-level-map";
  }
  return "unknown";
}

QuadtreeConfig QuadtreeConfig::forRootCount(int rootCount, float extentX, float extentZ) {
  if (rootCount < 1 || rootCount > kMaxRoots) {
    fail("QuadtreeConfig::forRootCount: root count {} is outside 1..{}", rootCount, kMaxRoots);
  }
  if (!(extentX > 0.0f) || !(extentZ > 0.0f) || !std::isfinite(extentX) || !std::isfinite(extentZ)) {
    fail("QuadtreeConfig::forRootCount: extent {}×{} m must be positive", extentX, extentZ);
  }
  QuadtreeConfig best;
  double bestWaste = std::numeric_limits<double>::infinity();
  for (int rx = rootCount; rx >= 1; --rx) {
    if (rootCount % rx != 0) {
      continue;
    }
    const int rz = rootCount / rx;
    const double size = std::max(static_cast<double>(extentX) / rx, static_cast<double>(extentZ) / rz);
    const double waste = size * size * rootCount - static_cast<double>(extentX) * extentZ;
    // Strictly better only, so ties keep the wider grid (rootsX ≥ rootsZ), e.g. 8×4 for 32 over a square.
    if (waste < bestWaste * (1.0 - 1e-9)) {
      bestWaste = waste;
      best.rootsX = rx;
      best.rootsZ = rz;
      // Round up by a hair so float rounding never leaves the far edge uncovered.
      best.rootSize = static_cast<float>(size * (1.0 + 1e-6));
    }
  }
  return best;
}

float QuadtreeConfig::pixelsPerRadianFor(float viewportHeightPx, float fovY) {
  if (!(viewportHeightPx > 0.0f) || !(fovY > 0.0f && fovY < 3.14f)) {
    fail(
        "QuadtreeConfig::pixelsPerRadianFor: viewport height {} px and field of view {} rad must be positive",
        viewportHeightPx, fovY);
  }
  return 0.5f * viewportHeightPx / std::tan(0.5f * fovY);
}

std::uint64_t patchTriangles(const SelectedNode& node) {
  const auto outer = [&](int e) { return static_cast<std::uint64_t>(std::lround(node.tessOuter[e])); };
  const auto inner = static_cast<std::uint64_t>(std::lround(node.tessInner));
  const std::uint64_t sum = outer(0) + outer(1) + outer(2) + outer(3);
  if (inner <= 1 && sum == 4) {
    return 2;
  }
  const std::uint64_t n = std::max<std::uint64_t>(inner, 2) - 2; // segments of the innermost ring
  return 2 * n * n + 4 * n + sum;
}

QuadtreeConfig QuadtreeConfig::fullDepth() const {
  QuadtreeConfig c = *this;
  c.lodEnabled = true;
  c.lodErrorPixels = 0.0f;
  c.lodDistanceFactor = 1.0e30f; // every box is nearer than this many node sizes
  return c;
}

float QuadtreeConfig::finestVertexSpacing() const {
  return std::ldexp(rootSize, -maxDepth) / static_cast<float>(patchTessLevel);
}

// ---------------------------------------------------------------------------------------------------------------
// Construction

void Quadtree::init(const QuadtreeConfig& config, float extentX, float extentZ, bool needRoots) {
  if (!(extentX > 0.0f) || !(extentZ > 0.0f) || !std::isfinite(extentX) || !std::isfinite(extentZ)) {
    fail("Quadtree: terrain extent {}×{} m must be positive", extentX, extentZ);
  }
  if (!(config.rootSize > 0.0f) || !std::isfinite(config.rootSize)) {
    fail("QuadtreeConfig.rootSize: {} m must be positive", config.rootSize);
  }
  if (config.maxDepth < 0 || config.maxDepth > kMaxDepthLimit) {
    fail("QuadtreeConfig.maxDepth: {} is outside 0..{}", config.maxDepth, kMaxDepthLimit);
  }
  if (config.rootsX < 0 || config.rootsZ < 0 || config.rootsX > kMaxRoots || config.rootsZ > kMaxRoots) {
    fail("QuadtreeConfig.rootsX/rootsZ: {}×{} is outside 0..{}", config.rootsX, config.rootsZ, kMaxRoots);
  }
  if (needRoots && (config.rootsX == 0 || config.rootsZ == 0)) {
    fail("QuadtreeConfig.rootsX/rootsZ: must be given with a prebuilt node pyramid");
  }
  validatePolicy(config);
  mConfig = config;
  const auto derive = [&](int given, float extent) {
    const double n = std::ceil(static_cast<double>(extent) / config.rootSize);
    return given > 0 ? given : static_cast<int>(std::clamp(n, 1.0, static_cast<double>(kMaxRoots)));
  };
  mConfig.rootsX = derive(config.rootsX, extentX);
  mConfig.rootsZ = derive(config.rootsZ, extentZ);
  const double tol = 1.0 - 1e-6;
  if (static_cast<double>(mConfig.rootsX) * config.rootSize < extentX * tol ||
      static_cast<double>(mConfig.rootsZ) * config.rootSize < extentZ * tol) {
    fail("QuadtreeConfig.rootsX/rootsZ: {}×{} roots of {} m do not cover the {}×{} m terrain", mConfig.rootsX,
         mConfig.rootsZ, config.rootSize, extentX, extentZ);
  }
  const long long leaves = (static_cast<long long>(mConfig.rootsX) << config.maxDepth) *
                           (static_cast<long long>(mConfig.rootsZ) << config.maxDepth);
  if (leaves > kMaxQuadtreeLeafNodes) {
    fail("QuadtreeConfig.maxDepth: {} with {}×{} roots gives {} deepest nodes, above the limit of {}",
         config.maxDepth, mConfig.rootsX, mConfig.rootsZ, leaves, kMaxQuadtreeLeafNodes);
  }
  mExtentX = extentX;
  mExtentZ = extentZ;
  mSizes.resize(static_cast<std::size_t>(config.maxDepth) + 1);
  for (int d = 0; d <= config.maxDepth; ++d) {
    mSizes[static_cast<std::size_t>(d)] = std::ldexp(config.rootSize, -d); // exact: power-of-two scaling
  }
}

Quadtree::Quadtree(const QuadtreeConfig& config, const HeightField& field) {
  if (field.width() < 2 || field.height() < 2) {
    fail("Quadtree: height field of {}×{} samples is too small (need ≥ 2×2)", field.width(), field.height());
  }
  if (!(field.spacingX() > 0.0f) || !(field.spacingZ() > 0.0f)) {
    fail("Quadtree: sample spacing {}×{} m must be positive", field.spacingX(), field.spacingZ());
  }
  init(config, field.extentX(), field.extentZ(), false);
  const int nx = gridWidth(mConfig.maxDepth);
  const int nz = gridHeight(mConfig.maxDepth);
  const double leafSize =
      static_cast<double>(mConfig.rootSize) / static_cast<double>(1LL << mConfig.maxDepth);
  const double sx = field.spacingX();
  const double sz = field.spacingZ();
  const double extentX = (field.width() - 1) * sx;
  const double extentZ = (field.height() - 1) * sz;
  mRanges = MinMaxPyramid::fromLeaves(nx, nz, [&](int bx, int bz) {
    const double x0 = bx * leafSize;
    const double z0 = bz * leafSize;
    if (x0 >= extentX || z0 >= extentZ) {
      return HeightRange::absent(); // starts at or beyond the far edge: no area with data
    }
    const int i0 = static_cast<int>(std::floor(x0 / sx));
    const int j0 = static_cast<int>(std::floor(z0 / sz));
    const double i1 = std::min(std::ceil((x0 + leafSize) / sx), static_cast<double>(field.width() - 1));
    const double j1 = std::min(std::ceil((z0 + leafSize) / sz), static_cast<double>(field.height() - 1));
    return scanRange(field, i0, static_cast<int>(i1), j0, static_cast<int>(j1));
  });
  buildLodRanges();
  if (mConfig.lodErrorPixels > 0.0f) {
    buildErrors(field);
  }
}

Quadtree::Quadtree(const QuadtreeConfig& config, float extentX, float extentZ, MinMaxPyramid nodeRanges) {
  init(config, extentX, extentZ, true);
  const int nx = gridWidth(mConfig.maxDepth);
  const int nz = gridHeight(mConfig.maxDepth);
  if (nodeRanges.levelCount() < mConfig.maxDepth + 1 || nodeRanges.blocksX(0) != nx ||
      nodeRanges.blocksZ(0) != nz) {
    fail("Quadtree: node pyramid has {}×{} leaf blocks, expected {}×{} (roots × 2^maxDepth)",
         nodeRanges.levelCount() > 0 ? nodeRanges.blocksX(0) : 0,
         nodeRanges.levelCount() > 0 ? nodeRanges.blocksZ(0) : 0, nx, nz);
  }
  mRanges = std::move(nodeRanges);
  buildLodRanges();
  if (mConfig.lodErrorPixels > 0.0f) {
    fail(
        "Quadtree: screen-space-error LOD (lodErrorPixels {}) needs the heights to measure node errors; this "
        "quadtree is built from a node range pyramid alone",
        mConfig.lodErrorPixels);
  }
}

void Quadtree::buildErrors(const HeightField& field) {
  // The reference is the surface drawn at the deepest level: the bilinear heights (heightAt) on the finest
  // vertex lattice L_D (spacing σ_D = rootSize / (2^maxDepth · T)), triangulated either way. A depth-d patch
  // draws a triangulation of the same heights on L_d ⊂ L_D. Its error bound is the largest |B_d − h| over
  // the L_D points of the node (B_d: the bilinear interpolation over L_d; B_d − B_D is bilinear on every L_D
  // cell, so its extremes are at those points) plus a quarter of the largest L_d cell twist
  // |h00 − h10 − h01 + h11| (how far a triangulation of a cell lies from its bilinear patch); B_D lies
  // between the two triangulations of L_D, so the bound holds against either. Deepest nodes: 0.
  // docs/terrain-lod.md, "Screen-space error".
  const int depths = mConfig.maxDepth + 1;
  const int tess = mConfig.patchTessLevel;
  const double finest = mSizes[static_cast<std::size_t>(mConfig.maxDepth)] / tess;
  mError.assign(static_cast<std::size_t>(depths), {});
  for (int d = 0; d < depths; ++d) {
    const int w = gridWidth(d);
    const int h = gridHeight(d);
    std::vector<float>& out = mError[static_cast<std::size_t>(d)];
    out.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0.0f);
    if (d == mConfig.maxDepth) {
      continue;
    }
    const int ratio = 1 << (mConfig.maxDepth - d); // L_D points per L_d interval
    const int m = ratio * tess;                    // L_D intervals per node side
    parallelFor(
        static_cast<std::size_t>(h),
        [&](std::size_t begin, std::size_t end) {
          std::vector<float> fine(static_cast<std::size_t>(m + 1) * static_cast<std::size_t>(m + 1));
          const auto at = [&](int a, int b) -> float& {
            return fine[static_cast<std::size_t>(b) * static_cast<std::size_t>(m + 1) +
                        static_cast<std::size_t>(a)];
          };
          for (std::size_t z = begin; z < end; ++z) {
            for (int x = 0; x < w; ++x) {
              const int gz = static_cast<int>(z);
              if (!mRanges.node(mConfig.maxDepth - d, x, gz).present()) {
                continue;
              }
              // Lattice coordinates as integers times σ_D, the way the patches place their vertices.
              const long long i0 = static_cast<long long>(x) * m;
              const long long j0 = static_cast<long long>(gz) * m;
              for (int b = 0; b <= m; ++b) {
                for (int a = 0; a <= m; ++a) {
                  at(a, b) = heightAt(field, static_cast<float>(static_cast<double>(i0 + a) * finest),
                                      static_cast<float>(static_cast<double>(j0 + b) * finest));
                }
              }
              float twist = 0.0f;
              for (int b = 0; b < m; b += ratio) {
                for (int a = 0; a < m; a += ratio) {
                  const float t =
                      std::abs(at(a, b) - at(a + ratio, b) - at(a, b + ratio) + at(a + ratio, b + ratio));
                  if (t == t) { // NaN next to absent samples: the renderer fills those, no data to compare
                    twist = std::max(twist, t);
                  }
                }
              }
              float deviation = 0.0f;
              const float inv = 1.0f / static_cast<float>(ratio);
              for (int b = 0; b <= m; ++b) {
                const int cb = std::min(b / ratio, tess - 1) * ratio;
                const float fz = static_cast<float>(b - cb) * inv;
                for (int a = 0; a <= m; ++a) {
                  const int ca = std::min(a / ratio, tess - 1) * ratio;
                  const float fx = static_cast<float>(a - ca) * inv;
                  const float top = at(ca, cb) + (at(ca + ratio, cb) - at(ca, cb)) * fx;
                  const float bottom =
                      at(ca, cb + ratio) + (at(ca + ratio, cb + ratio) - at(ca, cb + ratio)) * fx;
                  const float e = std::abs(top + (bottom - top) * fz - at(a, b));
                  if (e == e) {
                    deviation = std::max(deviation, e);
                  }
                }
              }
              out[z * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = deviation + 0.25f * twist;
            }
          }
        },
        1);
  }
  // Saturate (a node's error is at least its children's), then dilate over the 3×3 same-depth neighbourhood
  // for the restricted split rule, as the LOD height ranges are.
  for (int d = depths - 2; d >= 0; --d) {
    const int w = gridWidth(d);
    const int h = gridHeight(d);
    const int cw = gridWidth(d + 1);
    std::vector<float>& out = mError[static_cast<std::size_t>(d)];
    const std::vector<float>& child = mError[static_cast<std::size_t>(d + 1)];
    for (int z = 0; z < h; ++z) {
      for (int x = 0; x < w; ++x) {
        float& e =
            out[static_cast<std::size_t>(z) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
        for (int k = 0; k < 4; ++k) {
          const std::size_t c = static_cast<std::size_t>(2 * z + (k >> 1)) * static_cast<std::size_t>(cw) +
                                static_cast<std::size_t>(2 * x + (k & 1));
          e = std::max(e, child[c]);
        }
      }
    }
  }
  mLodError.assign(static_cast<std::size_t>(depths), {});
  for (int d = 0; d < depths; ++d) {
    const int w = gridWidth(d);
    const int h = gridHeight(d);
    const std::vector<float>& in = mError[static_cast<std::size_t>(d)];
    std::vector<float>& out = mLodError[static_cast<std::size_t>(d)];
    out.assign(in.size(), 0.0f);
    for (int z = 0; z < h; ++z) {
      for (int x = 0; x < w; ++x) {
        float e = 0.0f;
        for (int dz = std::max(z - 1, 0); dz <= std::min(z + 1, h - 1); ++dz) {
          for (int dx = std::max(x - 1, 0); dx <= std::min(x + 1, w - 1); ++dx) {
            e = std::max(e, in[static_cast<std::size_t>(dz) * static_cast<std::size_t>(w) +
                               static_cast<std::size_t>(dx)]);
          }
        }
        out[static_cast<std::size_t>(z) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = e;
      }
    }
  }
  mErrorTess = tess;
}

void Quadtree::buildLodRanges() {
  // Per depth, the union of each node's range with its 8 same-depth neighbours (separable 3×3 dilation). With
  // it a node's LOD box contains the LOD boxes of all children of its edge neighbours, which is what makes
  // the distance rule restricted (docs/terrain-lod.md, "restriction").
  const int depths = mConfig.maxDepth + 1;
  mLodY.assign(static_cast<std::size_t>(depths), {});
  for (int d = 0; d < depths; ++d) {
    const int w = gridWidth(d);
    const int h = gridHeight(d);
    const int level = mConfig.maxDepth - d;
    const auto at = [w](int x, int z) {
      return static_cast<std::size_t>(z) * static_cast<std::size_t>(w) + x;
    };
    std::vector<HeightRange> rows(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (int z = 0; z < h; ++z) {
      for (int x = 0; x < w; ++x) {
        HeightRange r = mRanges.node(level, x, z);
        r.include(mRanges.node(level, x - 1, z));
        r.include(mRanges.node(level, x + 1, z));
        rows[at(x, z)] = r;
      }
    }
    std::vector<HeightRange>& out = mLodY[static_cast<std::size_t>(d)];
    out.resize(rows.size());
    for (int z = 0; z < h; ++z) {
      for (int x = 0; x < w; ++x) {
        HeightRange r = rows[at(x, z)];
        if (z > 0) {
          r.include(rows[at(x, z - 1)]);
        }
        if (z + 1 < h) {
          r.include(rows[at(x, z + 1)]);
        }
        out[at(x, z)] = r;
      }
    }
  }
}

bool Quadtree::canSetConfig(const QuadtreeConfig& config) const {
  const bool sameLayout = (config.rootsX == 0 || config.rootsX == mConfig.rootsX) &&
                          (config.rootsZ == 0 || config.rootsZ == mConfig.rootsZ) &&
                          config.rootSize == mConfig.rootSize && config.maxDepth == mConfig.maxDepth;
  return sameLayout && (config.lodErrorPixels <= 0.0f || mErrorTess == config.patchTessLevel);
}

void Quadtree::setConfig(const QuadtreeConfig& config) {
  if ((config.rootsX != 0 && config.rootsX != mConfig.rootsX) ||
      (config.rootsZ != 0 && config.rootsZ != mConfig.rootsZ) || config.rootSize != mConfig.rootSize ||
      config.maxDepth != mConfig.maxDepth) {
    fail("Quadtree::setConfig: the layout (rootsX, rootsZ, rootSize, maxDepth) is fixed at construction");
  }
  validatePolicy(config);
  if (config.lodErrorPixels > 0.0f && mErrorTess != config.patchTessLevel) {
    fail(
        "Quadtree::setConfig: screen-space-error LOD at base level {} needs node errors for that level ({}); "
        "build the quadtree from the heights with this config",
        config.patchTessLevel,
        mErrorTess == 0 ? "none computed" : fmt::format("computed for {}", mErrorTess));
  }
  const int rx = mConfig.rootsX;
  const int rz = mConfig.rootsZ;
  mConfig = config;
  mConfig.rootsX = rx;
  mConfig.rootsZ = rz;
}

// ---------------------------------------------------------------------------------------------------------------
// Queries

float Quadtree::nodeSize(int level) const {
  return level >= 0 && level < static_cast<int>(mSizes.size()) ? mSizes[static_cast<std::size_t>(level)]
                                                               : std::ldexp(mConfig.rootSize, -level);
}

HeightRange Quadtree::nodeRange(const NodeId& node) const {
  if (node.level < 0 || node.level > mConfig.maxDepth) {
    return HeightRange::absent();
  }
  return mRanges.node(mConfig.maxDepth - node.level, node.gridX, node.gridZ);
}

Aabb Quadtree::nodeBounds(const NodeId& node) const {
  const float size = nodeSize(node.level);
  const HeightRange r = nodeRange(node);
  const float x0 = static_cast<float>(node.gridX) * size;
  const float z0 = static_cast<float>(node.gridZ) * size;
  return Aabb{glm::vec3(x0, r.min, z0), glm::vec3(x0 + size, r.max, z0 + size)};
}

HeightRange Quadtree::lodRange(int level, int gridX, int gridZ) const {
  if (mConfig.restrictSelection) {
    return mLodY[static_cast<std::size_t>(level)]
                [static_cast<std::size_t>(gridZ) * static_cast<std::size_t>(gridWidth(level)) +
                 static_cast<std::size_t>(gridX)];
  }
  return mRanges.node(mConfig.maxDepth - level, gridX, gridZ);
}

HeightRange Quadtree::lodBoxRange(const NodeId& node) const {
  if (node.level < 0 || node.level > mConfig.maxDepth || node.gridX < 0 || node.gridZ < 0 ||
      node.gridX >= gridWidth(node.level) || node.gridZ >= gridHeight(node.level)) {
    return HeightRange::absent();
  }
  return lodRange(node.level, node.gridX, node.gridZ);
}

float Quadtree::lodRuleError(const NodeId& node) const {
  if (mError.empty() || node.level < 0 || node.level > mConfig.maxDepth || node.gridX < 0 || node.gridZ < 0 ||
      node.gridX >= gridWidth(node.level) || node.gridZ >= gridHeight(node.level)) {
    return 0.0f;
  }
  return (mConfig.restrictSelection ? mLodError : mError)[static_cast<std::size_t>(
      node.level)][static_cast<std::size_t>(node.gridZ) * static_cast<std::size_t>(gridWidth(node.level)) +
                   static_cast<std::size_t>(node.gridX)];
}

float Quadtree::nodeError(const NodeId& node) const {
  if (mError.empty() || node.level < 0 || node.level > mConfig.maxDepth || node.gridX < 0 || node.gridZ < 0 ||
      node.gridX >= gridWidth(node.level) || node.gridZ >= gridHeight(node.level)) {
    return 0.0f;
  }
  return mError[static_cast<std::size_t>(node.level)]
               [static_cast<std::size_t>(node.gridZ) * static_cast<std::size_t>(gridWidth(node.level)) +
                static_cast<std::size_t>(node.gridX)];
}

std::size_t Quadtree::memoryBytes() const {
  std::size_t bytes = mRanges.memoryBytes();
  for (const auto& level : mLodY) {
    bytes += level.size() * sizeof(HeightRange);
  }
  for (std::size_t d = 0; d < mError.size(); ++d) {
    bytes += (mError[d].size() + mLodError[d].size()) * sizeof(float);
  }
  return bytes;
}

// ---------------------------------------------------------------------------------------------------------------
// Selection

QuadtreeSelection Quadtree::select(const glm::vec3& cameraPos, const Frustum* frustum) {
  QuadtreeSelection out;
  select(cameraPos, frustum, out);
  return out;
}

void Quadtree::select(const glm::vec3& cameraPos, const Frustum* frustum, QuadtreeSelection& out) {
  const QuadtreeConfig& c = mConfig;
  const bool cull = frustum != nullptr && c.frustumCull;
  const bool paper = c.method == CrackMethod::PaperSearch;
  const bool levelMap = c.method == CrackMethod::RestrictedLevelMap;
  const int maxSplitDepth = c.lodEnabled ? c.maxDepth : 0;
  const float factor = c.lodDistanceFactor;
  // Screen-space error: split while K·e / dist > τ or dist < floor·size, i.e. dist < K·e/τ + floor·size.
  const bool errorLod = c.lodErrorPixels > 0.0f;
  const float errorScale = errorLod ? c.pixelsPerRadian / c.lodErrorPixels : 0.0f;

  out.nodes.clear();
  out.culled.clear();
  out.stats = QuadtreeStats{};
  out.camera = cameraPos;
  out.config = c;
  QuadtreeStats& stats = out.stats;
  mStack.clear();
  mTree.clear();
  mLeafTree.clear();
  mSplitKeys.clear();
  if (paper) {
    mRootNode.assign(static_cast<std::size_t>(c.rootsX) * static_cast<std::size_t>(c.rootsZ), -1);
  }

  // Roots pushed in reverse so they pop in row-major order; traversal order is deterministic and identical
  // for every crack method.
  for (int z = c.rootsZ - 1; z >= 0; --z) {
    for (int x = c.rootsX - 1; x >= 0; --x) {
      mStack.push_back(StackItem{0, x, z, -1, 0});
    }
  }

  while (!mStack.empty()) {
    const StackItem item = mStack.back();
    mStack.pop_back();
    const HeightRange range = mRanges.node(c.maxDepth - item.level, item.gridX, item.gridZ);
    if (!range.present()) {
      ++stats.nodesAbsent; // outside the data: never drawn, never treated as height 0
      continue;
    }
    ++stats.nodesVisited;
    const float size = mSizes[static_cast<std::size_t>(item.level)];
    const float x0 = static_cast<float>(item.gridX) * size;
    const float z0 = static_cast<float>(item.gridZ) * size;
    if (cull) {
      const Aabb box{glm::vec3(x0, range.min, z0), glm::vec3(x0 + size, range.max, z0 + size)};
      if (!frustum->intersects(box)) {
        ++stats.nodesCulled;
        out.culled.push_back(NodeId{item.level, item.gridX, item.gridZ});
        continue;
      }
    }

    bool split = false;
    if (item.level < maxSplitDepth) {
      // CDLOD-style 3D distance from the camera to the LOD box (footprint × LOD height range).
      const HeightRange lod = lodRange(item.level, item.gridX, item.gridZ);
      const float dx = std::max(std::max(x0 - cameraPos.x, cameraPos.x - (x0 + size)), 0.0f);
      const float dy = std::max(std::max(lod.min - cameraPos.y, cameraPos.y - lod.max), 0.0f);
      const float dz = std::max(std::max(z0 - cameraPos.z, cameraPos.z - (z0 + size)), 0.0f);
      float limit = factor * size;
      if (errorLod) {
        const std::size_t index =
            static_cast<std::size_t>(item.gridZ) * static_cast<std::size_t>(gridWidth(item.level)) +
            static_cast<std::size_t>(item.gridX);
        const float e =
            (c.restrictSelection ? mLodError : mError)[static_cast<std::size_t>(item.level)][index];
        limit = errorScale * e + kErrorLodDistanceFloor * size;
      }
      split = dx * dx + dy * dy + dz * dz < limit * limit;
    }

    std::int32_t treeIndex = -1;
    if (paper) {
      treeIndex = static_cast<std::int32_t>(mTree.size());
      mTree.push_back(TreeNode{item.gridX, item.gridZ, item.parent, item.level, {-1, -1, -1, -1}, split});
      if (item.parent >= 0) {
        mTree[static_cast<std::size_t>(item.parent)].child[static_cast<std::size_t>(item.slot)] = treeIndex;
      } else {
        mRootNode[static_cast<std::size_t>(item.gridZ) * static_cast<std::size_t>(c.rootsX) +
                  static_cast<std::size_t>(item.gridX)] = treeIndex;
      }
    }

    if (split) {
      ++stats.nodesSplit;
      if (levelMap) {
        mSplitKeys.push_back(nodeKey(item.level, item.gridX, item.gridZ));
      }
      for (int slot = 3; slot >= 0; --slot) {
        mStack.push_back(StackItem{item.level + 1, item.gridX * 2 + (slot & 1), item.gridZ * 2 + (slot >> 1),
                                   treeIndex, slot});
      }
      continue;
    }

    SelectedNode node;
    node.x = x0;
    node.z = z0;
    node.size = size;
    node.minY = range.min;
    node.maxY = range.max;
    node.level = item.level;
    node.gridX = item.gridX;
    node.gridZ = item.gridZ;
    node.error = nodeError(NodeId{item.level, item.gridX, item.gridZ});
    out.nodes.push_back(node);
    if (paper) {
      mLeafTree.push_back(treeIndex);
    }
  }

  // Edge levels. Rule (all methods but None): the outer level of edge e is 2·T when the same-depth square
  // across e was split (so the leaf there is one depth finer, by restriction), else T. Each side derives its
  // levels from the shared edge alone, so both sides place vertices at the same positions.
  const float base = static_cast<float>(c.patchTessLevel);
  if (levelMap) {
    buildSplitHash(mSplitKeys.size());
  }
  long long steps = 0;
  int doubled = 0;
  for (std::size_t i = 0; i < out.nodes.size(); ++i) {
    SelectedNode& node = out.nodes[i];
    node.tessInner = base;
    node.edgeFlags = 0;
    for (int e = 0; e < 4; ++e) {
      bool finer = false;
      if (c.method != CrackMethod::None) {
        const int nx = node.gridX + kEdgeDx[static_cast<std::size_t>(e)];
        const int nz = node.gridZ + kEdgeDz[static_cast<std::size_t>(e)];
        if (nx >= 0 && nz >= 0 && nx < gridWidth(node.level) && nz < gridHeight(node.level)) {
          finer = paper ? paperFinerNeighbour(mLeafTree[i], e, steps)
                        : splitHashContains(nodeKey(node.level, nx, nz), steps);
        }
      }
      node.tessOuter[static_cast<std::size_t>(e)] = finer ? 2.0f * base : base;
      if (finer) {
        node.edgeFlags |= 1u << e;
        ++doubled;
      }
    }
  }

  const auto leaves = static_cast<std::uint64_t>(out.nodes.size());
  const auto perPatch = static_cast<std::uint64_t>(c.patchTessLevel + 1) * (c.patchTessLevel + 1);
  stats.leaves = static_cast<int>(out.nodes.size());
  stats.doubledEdges = doubled;
  stats.neighbourSteps = steps;
  stats.controlPoints = 4 * leaves;
  stats.processedVertices = perPatch * leaves;
}

bool Quadtree::paperFinerNeighbour(std::int32_t treeIndex, int edge, long long& steps) const {
  const TreeNode& node = mTree[static_cast<std::size_t>(treeIndex)];
  const int level = node.level;
  const int nx = node.gridX + kEdgeDx[static_cast<std::size_t>(edge)];
  const int nz = node.gridZ + kEdgeDz[static_cast<std::size_t>(edge)];
  // Sibling: same parent, found in O(1).
  if (level > 0 && (nx >> 1) == (node.gridX >> 1) && (nz >> 1) == (node.gridZ >> 1)) {
    ++steps;
    const std::int32_t sibling =
        mTree[static_cast<std::size_t>(node.parent)].child[static_cast<std::size_t>((nz & 1) * 2 + (nx & 1))];
    return sibling >= 0 && mTree[static_cast<std::size_t>(sibling)].split;
  }
  // Cousin: top-down search for the same-depth square from its root, pruning to the one child that contains
  // it; stops early at a leaf (the square is covered by a coarser or equal leaf) or a dropped node.
  std::int32_t current =
      mRootNode[static_cast<std::size_t>(nz >> level) * static_cast<std::size_t>(mConfig.rootsX) +
                static_cast<std::size_t>(nx >> level)];
  for (int depth = 0; current >= 0; ++depth) {
    ++steps;
    const TreeNode& n = mTree[static_cast<std::size_t>(current)];
    if (depth == level || !n.split) {
      return depth == level && n.split;
    }
    const int shift = level - depth - 1;
    current = n.child[static_cast<std::size_t>(((nz >> shift) & 1) * 2 + ((nx >> shift) & 1))];
  }
  return false;
}

void Quadtree::buildSplitHash(std::size_t count) {
  const std::size_t capacity = std::max<std::size_t>(64, std::bit_ceil(count * 2));
  mHashShift = 64 - static_cast<int>(std::countr_zero(capacity));
  mHash.assign(capacity, kEmptyKey);
  const std::size_t mask = capacity - 1;
  for (const std::uint64_t key : mSplitKeys) {
    std::size_t slot = hashSlot(key, mHashShift);
    while (mHash[slot] != kEmptyKey) {
      slot = (slot + 1) & mask;
    }
    mHash[slot] = key;
  }
}

bool Quadtree::splitHashContains(std::uint64_t key, long long& steps) const {
  const std::size_t mask = mHash.size() - 1;
  for (std::size_t slot = hashSlot(key, mHashShift);; slot = (slot + 1) & mask) {
    ++steps;
    const std::uint64_t k = mHash[slot];
    if (k == key) {
      return true;
    }
    if (k == kEmptyKey) {
      return false;
    }
  }
}

} // namespace sylva::terrain
