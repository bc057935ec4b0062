#pragma once

#include <sylva/terrain/HeightRaster.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

/**
 * Tile pyramids (docs/terrain-data.md, "Tile pyramids"): a height raster cut into square tiles at every level
 * of detail, each tile a compressed file with its height range and geometric error, built tile by tile in
 * bounded memory and read back tile by tile. Level 0 holds the source's samples; level L + 1 keeps every
 * second sample of level L (decimation: a coarse vertex is always a fine vertex, as the quadtree's patches
 * need), up to the first level that fits in one tile.
 *
 * Coordinates: level L sample (i, j) sits at x = i · 2^L · spacingX, z = j · 2^L · spacingZ metres (the
 * HeightField convention at level 0). Level L + 1 sample i is level L sample min(2i, width_L − 1): where a
 * level's last interval is odd, its edge sample is repeated one coarse step beyond the edge (the edge heights
 * continue, as height queries outside the footprint do). Tile (x, y) of level L holds samples
 * [x·T, x·T + T] × [y·T, y·T + T] — (T + 1)² samples, sharing its border rows with its neighbours so that it
 * can be drawn and interpolated alone; samples beyond the level are NaN.
 */
namespace sylva::terrain {

/** Version written to `pyramid.json` and every tile; readers refuse others. */
inline constexpr int kPyramidVersion = 1;
/** Smallest tile size T (samples per tile edge, minus the shared border). */
inline constexpr int kMinTileSize = 16;
/** Largest tile size T. */
inline constexpr int kMaxTileSize = 4096;
/** Most tiles buildPyramid writes, all levels (it holds 12 bytes a tile of a level in memory while building).
 */
inline constexpr std::uint64_t kMaxPyramidTiles = std::uint64_t{1} << 26;

/** One level of a pyramid: its samples and tiles. */
struct PyramidLevel {
  int width = 0;  ///< samples along x
  int height = 0; ///< samples along z
  int tilesX = 0; ///< tiles along x: ceil((width − 1) / T)
  int tilesY = 0; ///< tiles along z
};

/** What `pyramid.json` records. */
struct PyramidInfo {
  int width = 0;           ///< level-0 samples along x
  int height = 0;          ///< level-0 samples along z
  float spacingX = 1.0f;   ///< level-0 metres between columns
  float spacingZ = 1.0f;   ///< level-0 metres between rows
  int tileSize = 256;      ///< T: a tile holds (T + 1)² samples
  int levels = 1;          ///< levels 0 .. levels − 1; the last fits in one tile
  float minHeight = 0.0f;  ///< lowest valid height of the whole pyramid, metres (NaN: not built yet)
  float maxHeight = 0.0f;  ///< highest valid height, metres
  std::string source;      ///< the source file as given (informative)
  bool complete = false;   ///< every tile and every level's index is written
  std::uint64_t tiles = 0; ///< tiles in all levels
  std::uint64_t bytes = 0; ///< bytes of all tile files (complete pyramids)

  /** Level `level`'s size and tile count (0 ≤ level < levels). */
  PyramidLevel level(int level) const;
  /** Tile counts for a raster of width × height at tile size T, and the levels it needs. */
  static PyramidInfo plan(int width, int height, float spacingX, float spacingZ, int tileSize);
};

/** A tile's address. */
struct TileKey {
  int level = 0; ///< level of detail (0 = source samples)
  int x = 0;     ///< tile column, from the west
  int y = 0;     ///< tile row, from the north
  /** Ordered by level, then x, then y (member order): keys of maps and sorted lists. */
  auto operator<=>(const TileKey&) const = default;
};

/** What a tile says about the surface it stands for; in each tile's header and in each level's index. */
struct TileSummary {
  /**
   * Lowest and highest height, metres, of the tile's samples and of every finer sample beneath it (what a
   * bounding box for culling and LOD needs); NaN when all are absent.
   */
  float minHeight = 0.0f;
  float maxHeight = 0.0f; ///< see minHeight
  /**
   * Geometric error, metres: an upper bound on the vertical distance between the bilinear surface of this
   * tile's samples and every level-0 sample it covers (0 at level 0; hierarchical: the largest distance to
   * the next finer level's samples plus the largest error of the tiles below).
   */
  float error = 0.0f;
};

/** One tile: its samples and summary. */
struct TileData {
  TileKey key;         ///< where it belongs
  int size = 0;        ///< T
  TileSummary summary; ///< range and error
  /** (T + 1)² heights, row-major (row = z), metres; NaN absent or beyond the level. */
  std::vector<float> heights;
  /** Height of tile sample (a, b), 0 ≤ a, b ≤ T. */
  float at(int a, int b) const { return heights[static_cast<std::size_t>(b) * (size + 1) + a]; }
};

/** Options of buildPyramid. */
struct PyramidOptions {
  int tileSize = 256; ///< T, kMinTileSize..kMaxTileSize
  /**
   * Builds only this share of level 0's tiles (tile k of the row-major order belongs to shard k mod n),
   * for Slurm job arrays; a build without shards (0/1) then completes the pyramid, reusing every finished
   * tile. Counted from 0, as `--shard` elsewhere.
   */
  int shardIndex = 0;
  int shardCount = 1; ///< n of the shards; 1: build everything
  std::string source; ///< recorded in pyramid.json
  /** Called with (tiles done, tiles to do) after each tile; may throw to cancel. Thread-safe calls. */
  std::function<void(std::size_t, std::size_t)> onTile;
};

/** What buildPyramid did. */
struct PyramidBuild {
  PyramidInfo info;               ///< the pyramid as written
  std::size_t written = 0;        ///< tiles written by this call
  std::size_t kept = 0;           ///< tiles already on disk and valid, reused
  std::uint64_t writtenBytes = 0; ///< bytes of the tiles this call wrote
};

/**
 * Builds (or completes) the pyramid of `raster` in folder `dir`: `pyramid.json`, one file per tile
 * (`<L>/<y>/<x>.tile`) and one index per level (`<L>/index.bin`). Memory stays bounded whatever the raster's
 * size: each worker holds one level-0 window or four child tiles and one tile at a time (about 5·(T + 1)²
 * floats), GDAL's block cache aside. Tiles are written atomically; valid tiles already in `dir` are kept, so
 * an interrupted build resumes and shards combine. Tiles are built on parallelFor's workers (SYLVA_THREADS).
 *
 * Errors (sylva::Error, one line naming the folder or file): tile size out of range, shard outside [0, n),
 * `dir` holding a pyramid of another size/spacing/tile size, `dir` not writable, a failed read, no valid
 * sample at all (found when level 0 is complete).
 */
PyramidBuild buildPyramid(const HeightRaster& raster, const std::filesystem::path& dir,
                          const PyramidOptions& options);

/** The tile file of `key` in pyramid folder `dir`. */
std::filesystem::path tilePath(const std::filesystem::path& dir, const TileKey& key);

/** Encodes a tile as its file's bytes (header, checksum, zlib over the floating-point predictor). */
std::vector<std::uint8_t> encodeTile(const TileData& tile);
/**
 * Decodes a tile file's bytes; `name` names it in errors. Checks the magic, version, sizes, checksum and that
 * the data inflates to exactly (T + 1)² floats; throws sylva::Error `<name>: <reason>` otherwise.
 */
TileData decodeTile(const std::uint8_t* bytes, std::size_t size, const std::string& name);

/**
 * Bilinear height (metres) at world (x, z) from `tile`'s samples, on its level's lattice of `layout`, with
 * the cell clamped into the tile (and the level's samples): what TilePyramid::heightAt computes once it has
 * found the tile. Absent corners with non-zero weight give NaN.
 */
float heightInTile(const PyramidInfo& layout, const TileData& tile, double x, double z);

/**
 * A complete pyramid opened for reading: tiles on demand through a cache bounded in bytes (least recently
 * used tiles are dropped first), and height queries at any level. Thread-safe.
 */
class TilePyramid {
public:
  /**
   * Opens folder `dir`: reads and checks `pyramid.json` (version, format, sizes consistent with the plan,
   * complete) and every level's index. Throws sylva::Error `<file>: <reason>` (naming the field).
   * `cacheBytes`: the tile cache's budget (at least one tile is always kept).
   */
  static std::shared_ptr<TilePyramid> open(const std::filesystem::path& dir,
                                           std::size_t cacheBytes = std::size_t{256} << 20);

  const PyramidInfo& info() const { return mInfo; }         ///< what pyramid.json says
  const std::filesystem::path& dir() const { return mDir; } ///< the folder
  /** Tile `key`'s summary from its level's index (no tile is read). */
  const TileSummary& summary(const TileKey& key) const;
  /** Tile `key`, from the cache or read and checked from disk (throws `<file>: <reason>`). */
  std::shared_ptr<const TileData> tile(const TileKey& key) const;
  /**
   * Bilinear height at world (x, z) metres from level `level`'s samples, clamped to the level's samples
   * (level 0 equals heightAt(field, x, z, Bilinear) of the source field exactly, absent samples included).
   */
  float heightAt(float x, float z, int level = 0) const;

  /** Bytes of the tiles the cache holds now. */
  std::size_t cachedBytes() const;
  /** Tiles read from disk so far. */
  std::size_t tilesRead() const;

private:
  TilePyramid() = default;
  void touch(std::list<TileKey>::iterator it) const;

  std::filesystem::path mDir;
  PyramidInfo mInfo;
  std::size_t mBudget = 0;
  std::vector<std::vector<TileSummary>> mIndex; ///< per level, row-major tiles
  mutable std::mutex mMutex;
  mutable std::list<TileKey> mOrder; ///< most recently used first
  struct Entry {
    std::shared_ptr<const TileData> tile;
    std::list<TileKey>::iterator order;
  };
  mutable std::map<TileKey, Entry> mCache;
  mutable std::size_t mCachedBytes = 0;
  mutable std::size_t mRead = 0;
};

} // namespace sylva::terrain
