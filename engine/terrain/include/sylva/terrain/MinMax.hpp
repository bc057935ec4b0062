#pragma once

#include <sylva/terrain/HeightField.hpp>

#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

/**
 * Min/max height structures for terrain LOD and culling.
 *
 * Questions answered: what are the lowest and highest valid heights (metres) over a rectangle of samples, or
 * over the footprint of a quadtree node? Two structures answer them:
 *  - MinMaxRmq: the baseline of Deaconu et al. (2021), a 2D range-minimum/maximum query through a 2D sparse
 *    table. Any rectangle in O(1), but O(n log² n) memory.
 *  - MinMaxPyramid: a min-max mip pyramid over quadtree-aligned blocks (CDLOD style). O(1) per quadtree node,
 *    memory about 1/(6·leafSize²) of the float heightmap.
 * Absent samples (NaN) are ignored; a region with no valid sample reports HeightRange::absent().
 */
namespace sylva::terrain {

/**
 * Lowest and highest valid height of a region, metres (world y). A region without any valid sample is
 * "absent": both values are NaN and present() is false. Never treat an absent region as height 0.
 */
struct HeightRange {
  /** Lowest valid height, metres; NaN when absent. */
  float min = std::numeric_limits<float>::quiet_NaN();
  /** Highest valid height, metres; NaN when absent. */
  float max = std::numeric_limits<float>::quiet_NaN();

  /** True when the region holds at least one valid sample (min ≤ max). */
  bool present() const { return min <= max; }
  /** The absent range (NaN, NaN). */
  static HeightRange absent() { return {}; }
  /** Widens the range to include height `h` metres; NaN is ignored. */
  void include(float h);
  /** Widens the range to include `other`; an absent `other` changes nothing. */
  void include(const HeightRange& other);
  /** Exact equality of both bounds; two absent ranges compare equal. */
  bool operator==(const HeightRange& other) const;
};

/** Brute-force min/max over samples [i0, i1] × [j0, j1] (inclusive, clamped to the field), for tests and
 * tools. */
HeightRange scanRange(const HeightField& field, int i0, int i1, int j0, int j1);

/**
 * 2D range min/max query via a 2D sparse table (Amir, Fischer & Lewenstein 2007, as used by the paper).
 *
 * Table (kx, ky) holds, for every sample (i, j), the min and max over [i, i + 2^kx) × [j, j + 2^ky); a query
 * covers its rectangle with four overlapping power-of-two tables, so it costs four loads whatever its size.
 * Memory: 8 bytes × Σ_{kx,ky} (W − 2^kx + 1)(H − 2^ky + 1) ≈ 8·W·H·(⌊log₂W⌋+1)(⌊log₂H⌋+1) bytes, i.e. about
 * 2·(log₂ n)² times the float heightmap: 1024² samples need ~680 MiB, 512² ~135 MiB. It is the baseline, not
 * the structure to ship; the constructor refuses sizes above a byte limit. Immutable after construction;
 * concurrent queries are safe.
 */
class MinMaxRmq {
public:
  /** Default memory limit for the tables, bytes (1 GiB). */
  static constexpr std::size_t kDefaultMaxBytes = std::size_t{1} << 30;

  /** An empty structure; query() throws. */
  MinMaxRmq() = default;
  /**
   * Builds the tables for `field`. Throws sylva::Error for an empty field or when requiredBytes() exceeds
   * `maxBytes`, naming the size and the limit.
   */
  explicit MinMaxRmq(const HeightField& field, std::size_t maxBytes = kDefaultMaxBytes);

  /** Bytes the tables need for a `width`×`height` field (no allocation); saturates instead of overflowing. */
  static std::size_t requiredBytes(int width, int height);

  /**
   * Min and max valid height (metres) over samples [i0, i1] × [j0, j1], inclusive; O(1). Throws sylva::Error
   * when the rectangle is empty or leaves the field.
   */
  HeightRange query(int i0, int i1, int j0, int j1) const;

  /** Field width in samples. */
  int width() const { return mWidth; }
  /** Field height in samples. */
  int height() const { return mHeight; }
  /** Bytes held by the tables. */
  std::size_t memoryBytes() const { return mData.size() * sizeof(Entry); }

private:
  struct Entry {
    float lo;
    float hi;
  };

  int mWidth = 0;
  int mHeight = 0;
  int mLevelsX = 0;
  int mLevelsZ = 0;
  std::vector<std::size_t> mOffsets; // start of table (kx, ky) at kx · mLevelsZ + ky
  std::vector<Entry> mData;
};

/**
 * Min-max mip pyramid over quadtree-aligned blocks (CDLOD style).
 *
 * Level 0 holds one range per leaf block; block (bx, bz) of a pyramid built from a HeightField with leaf size
 * L covers samples [bx·L, bx·L + L] × [bz·L, bz·L + L] inclusive (clamped to the field), so neighbouring
 * blocks share their border samples, exactly like neighbouring patches share their edge vertices. Level k + 1
 * holds the union of the (up to) four children 2b, 2b + 1 of level k; level k has ⌈blocks₀ / 2^k⌉ blocks per
 * axis, and the last level is 1×1. A quadtree node at depth d of a tree whose deepest level is D reads level
 * D − d: O(1).
 *
 * Memory: 8 bytes × (4/3) × blocks₀ ≈ 10.7·W·H / L² bytes, i.e. ≤ 1/16 of a float heightmap (4·W·H bytes) for
 * L ≥ 8 (≈ 1/24 at L = 8, ≈ 1/1500 at L = 64). Immutable after construction; concurrent queries are safe.
 */
class MinMaxPyramid {
public:
  /** Computes the range of leaf block (bx, bz); called concurrently from worker threads, must be thread-safe.
   */
  using LeafFunction = std::function<HeightRange(int bx, int bz)>;

  /** An empty pyramid (no levels). */
  MinMaxPyramid() = default;
  /**
   * Builds the pyramid of `field` with leaf blocks of `leafSize` sample intervals (leafSize + 1 samples per
   * side, shared with the neighbours). Throws sylva::Error for an empty field or leafSize < 1.
   */
  MinMaxPyramid(const HeightField& field, int leafSize);

  /**
   * Builds a pyramid from leaf ranges supplied by `leaf` for a `blocksX`×`blocksZ` grid: the way to cover
   * fields that are never stored whole (a coarse source plus a bound, an analytic function) or blocks that
   * are not sample-aligned (quadtree node footprints). `leafSize` (samples per block, 0 = unknown) only
   * enables bound(). Throws sylva::Error for non-positive or absurd (> 2^26 blocks) grids.
   */
  static MinMaxPyramid fromLeaves(int blocksX, int blocksZ, const LeafFunction& leaf, int leafSize = 0);

  /** Number of levels (level 0 = leaf blocks; the last is 1×1); 0 when empty. */
  int levelCount() const { return static_cast<int>(mLevels.size()); }
  /** Blocks along x at `level`. */
  int blocksX(int level) const { return mLevels[static_cast<std::size_t>(level)].width; }
  /** Blocks along z at `level`. */
  int blocksZ(int level) const { return mLevels[static_cast<std::size_t>(level)].height; }
  /** Sample intervals per leaf block side; 0 when built from leaves without a size. */
  int leafSize() const { return mLeafSize; }

  /**
   * Range of block (bx, bz) at `level`, metres; absent when the block holds no valid sample or lies outside
   * the grid. O(1). `level` must be in [0, levelCount()).
   */
  HeightRange node(int level, int bx, int bz) const {
    const Level& l = mLevels[static_cast<std::size_t>(level)];
    if (bx < 0 || bz < 0 || bx >= l.width || bz >= l.height) {
      return HeightRange::absent();
    }
    const HeightRange& r = l.ranges[static_cast<std::size_t>(bz) * static_cast<std::size_t>(l.width) +
                                    static_cast<std::size_t>(bx)];
    return r.min <= r.max ? r : HeightRange::absent();
  }

  /**
   * Conservative range over samples [i0, i1] × [j0, j1] (inclusive) in O(1): the union of the ≤ 2×2 blocks of
   * the coarsest level that covers the rectangle with at most two blocks per axis. The result contains the
   * exact range (min ≤ true min, max ≥ true max) and equals it for block-aligned rectangles; it may report a
   * range for an all-absent rectangle that touches valid blocks. Requires leafSize() > 0; throws sylva::Error
   * otherwise or for an empty rectangle.
   */
  HeightRange bound(int i0, int i1, int j0, int j1) const;

  /** Bytes held by the pyramid. */
  std::size_t memoryBytes() const;

private:
  struct Level {
    int width = 0;
    int height = 0;
    std::vector<HeightRange> ranges; // absent stored as (+inf, -inf) so unions need no branches
  };
  void buildUpperLevels();

  int mLeafSize = 0;
  std::vector<Level> mLevels;
};

} // namespace sylva::terrain
