#pragma once

#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/TilePyramid.hpp>

#include <memory>
#include <string>

namespace sylva::terrain {

/**
 * Where streamed terrain tiles come from (docs/terrain-data.md, "Streaming"): a tile pyramid on disk
 * (TilePyramid) or a procedural world generated on demand (ProceduralWorld). Every source follows the tile
 * pyramid's layout and conventions exactly (PyramidInfo: levels by decimation, (T + 1)² samples per tile,
 * NaN beyond the data), so the streamer, the selection and the renderer do not know which one they read.
 * Thread-safe: load() and summary() are called from loader threads.
 */
class TileSource {
public:
  virtual ~TileSource() = default;
  /** Sizes, spacing, tile size and levels. */
  virtual const PyramidInfo& layout() const = 0;
  /**
   * Height range of the tile and of everything beneath it, and its error bound, without loading it (the
   * selection's bounding boxes); may be conservative.
   */
  virtual TileSummary tileSummary(const TileKey& key) const = 0;
  /** Tile `key`, read or generated (throws sylva::Error naming the file on damage). */
  virtual std::shared_ptr<const TileData> loadTile(const TileKey& key) const = 0;
  /** One line for logs and reports: "pyramid out/x (…)", "procedural world seed 7 (…)". */
  virtual std::string describe() const = 0;
};

/** A tile pyramid folder as a TileSource (its own cache is kept small: the streamer caches). */
std::shared_ptr<const TileSource> pyramidSource(const std::filesystem::path& dir);

/** Samples per side of the procedural world: 2^20 + 1 (1,048,576 m across at 1 m spacing). */
inline constexpr int kProceduralWorldSide = (1 << 20) + 1;

/**
 * A procedural world as a TileSource: side² samples of ProceduralNoise at `spacing` metres, generated tile by
 * tile on demand and never held whole. Level L sample (i, j) is the noise at (i·2^L·spacing, j·2^L·spacing),
 * computed from the integer sample index, so it is bit for bit level 0's sample there (decimation holds
 * exactly). Tile summaries are the noise's bound [0, heightScale] with an unknown error (+inf).
 */
class ProceduralWorld final : public TileSource {
public:
  /**
   * `side` samples per side (2..kMaxRasterSide), `tileSize` T (a power of two), `spacing` metres. Throws
   * sylva::Error for an invalid spec or sizes.
   */
  ProceduralWorld(const ProceduralSpec& spec, int side = kProceduralWorldSide, float spacing = 1.0f,
                  int tileSize = 64);
  const PyramidInfo& layout() const override { return mInfo; }
  TileSummary tileSummary(const TileKey& key) const override;
  std::shared_ptr<const TileData> loadTile(const TileKey& key) const override;
  std::string describe() const override;
  /** Level-0 height at world (x, z) metres: the bilinear surface of the samples (what heightAt would give).
   */
  float heightAt(double x, double z) const;
  /** The noise's spec. */
  const ProceduralSpec& spec() const { return mNoise.spec(); }

private:
  ProceduralNoise mNoise;
  PyramidInfo mInfo;
};

} // namespace sylva::terrain
