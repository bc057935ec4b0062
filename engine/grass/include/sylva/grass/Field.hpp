#pragma once
// The field: a grid of tiles over the terrain, each drawing a contiguous range of the patch whose start comes
// from the tile's position (paper §4.5), thinned by a density map (seeded Perlin noise, paper Fig. 8, with
// rules on height, slope and an optional paint mask). Blade roots sit on the terrain surface as the terrain's
// tessellation evaluation shader samples it (bilinear, terrain::heightAt).

#include <sylva/core/Image.hpp>
#include <sylva/grass/Patch.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/TerrainMaps.hpp>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace sylva::grass {

/** Where grass grows. Densities are in [0, 1]: the fraction of a tile's blades drawn. */
struct DensitySettings {
  /** Overall density. */
  float base = 1.0f;
  /** Perlin density map: frequency per metre, fraction of ground it covers, and how sharp its edges are. */
  float noiseFrequency = 0.03f;
  /** Share of the ground the noise leaves grass on, [0, 1]. */
  float coverage = 0.7f;
  /** How sharp the noise map's edges are (a logistic slope). */
  float contrast = 8.0f;
  /** Seed of the noise map. */
  std::uint64_t seed = 3;
  /** Heights (metres) where grass grows, faded over heightFade metres at both ends. */
  float minHeight = -std::numeric_limits<float>::infinity();
  /** Highest height with grass, metres. */
  float maxHeight = std::numeric_limits<float>::infinity();
  /** Metres over which grass fades out at minHeight and maxHeight. */
  float heightFade = 2.0f;
  /** Steepest slope (degrees) with grass, faded over slopeFade degrees. */
  float maxSlopeDegrees = 38.0f;
  /** Degrees over which grass fades out below maxSlopeDegrees. */
  float slopeFade = 8.0f;
  /**
   * Optional paint mask (first channel, 0..1) over the world rectangle paintMin..paintMax (x, z metres),
   * bilinear, multiplied in; outside the rectangle the density is unchanged.
   */
  std::shared_ptr<const Image> paint;
  /** World (x, z) of the paint mask's first pixel's corner, metres. */
  glm::vec2 paintMin{0.0f};
  /** World (x, z) of the paint mask's opposite corner, metres. */
  glm::vec2 paintMax{0.0f};
  /**
   * Optional terrain splat layer (rules in true metres and degrees): the density is multiplied by its raw
   * weight (terrain::splatWeight), so grass grows where the terrain shows that layer (e.g. "grass").
   */
  std::optional<terrain::SplatLayer> layer;
  /** Vertical exaggeration of the heights given to at(): the layer rule sees height / scale and the true
   * slope. */
  float verticalScale = 1.0f;
};

/** Evaluates the density rules (thread-safe, pure). */
class DensityMap {
public:
  /** Throws sylva::Error naming the field for non-finite values, empty ranges, a paint mask with no area. */
  explicit DensityMap(DensitySettings settings);
  /** The Perlin part alone at world (x, z), [0, 1]. */
  float noise(float x, float z) const;
  /** Density at world (x, z) with terrain height (m) and slope (degrees) there, [0, 1]. */
  float at(float x, float z, float height, float slopeDegrees) const;
  /** The settings the map was made with. */
  const DensitySettings& settings() const { return mSettings; }

private:
  DensitySettings mSettings;
  terrain::ProceduralNoise mNoise;
};

/**
 * The density baked on a regular grid over the terrain (samples at (i·spacingX, j·spacingZ), like the
 * terrain's), read bilinearly in float by both the CPU reference and the culling shader, so both keep the
 * same blades. Absent terrain gives density 0.
 */
class DensityGrid {
public:
  DensityGrid() = default;
  /**
   * Bakes `map` over `terrain`'s footprint with the largest spacing ≤ `maxSpacing` metres that divides the
   * extent evenly (coarser when that would exceed 2^24 samples); height and slope come from the terrain at
   * each grid sample. Throws sylva::Error for a spacing that is not finite and > 0.
   */
  DensityGrid(const DensityMap& map, const terrain::HeightField& terrain, float maxSpacing = 2.0f);
  /** Bilinear density at world (x, z), clamped to the edge samples. */
  float at(float x, float z) const;
  /** Grid samples along x. */
  int width() const { return mWidth; }
  /** Grid samples along z. */
  int height() const { return mHeight; }
  /** Metres between grid samples along x and z. */
  glm::vec2 spacing() const { return mSpacing; }
  /** Row-major samples, width() × height(). */
  const std::vector<float>& values() const { return mValues; }

private:
  int mWidth = 0;
  int mHeight = 0;
  glm::vec2 mSpacing{1.0f};
  std::vector<float> mValues;
};

/**
 * The terrain height at world (x, z) as the terrain's tessellation evaluation shader computes it (bilinear in
 * float from the four samples around, clamped to the field), or NaN when any of the four is absent: the
 * culling shader's arithmetic, operation for operation.
 */
float rootHeight(const terrain::HeightField& terrain, float x, float z);

/** The grid of tiles. */
struct FieldLayout {
  /** World (x, z) of tile (0, 0)'s corner, metres. */
  glm::vec2 origin{0.0f};
  /** Tile side, metres. */
  float tileSize = 2.0f;
  /** Tiles along x. */
  int tilesX = 0;
  /** Tiles along z. */
  int tilesZ = 0;
  /** Blades a tile draws at density 1 (≤ the patch size). */
  int bladesPerTile = 64;
};

/**
 * Tiles covering the terrain's footprint (nothing is stored per tile, so a field over a 30 km DEM is fine).
 * Throws sylva::Error for a tile size ≤ 0 or more than 2^20 tiles along a side.
 */
FieldLayout layoutOver(const terrain::HeightField& terrain, float tileSize, int bladesPerTile);

/**
 * First patch blade of tile (tx, tz): a hash of the tile's position modulo the patch size, so neighbouring
 * tiles draw different ranges and nothing per tile is stored. The tile draws blades start, start + 1, … (mod
 * patch).
 */
std::uint32_t tileStart(int tx, int tz, std::uint32_t patchBlades);

/** One blade of the field, in world space. */
struct FieldBlade {
  /** Root on the terrain surface, world metres. */
  glm::vec3 root{0.0f};
  /** Index into the patch, and the blade's position j in its tile's range. */
  std::uint32_t patchIndex = 0;
  /** The blade's position j in its tile's range. */
  int rangeIndex = 0;
  /** The tile's column. */
  int tileX = 0;
  /** The tile's row. */
  int tileZ = 0;
  /** A tuft blade of the near layers (forEachTuftBlade): the range index of the field blade it stands
   * beside; −1 for the field's own blades. */
  int guide = -1;
};

/**
 * The blades tile (tx, tz) draws: the first layout.bladesPerTile entries of its range, where entry j is kept
 * when (j + 0.5) / bladesPerTile < density at its root (the patch is shuffled, so the kept ones are an
 * unbiased sample whatever the density). Roots outside the terrain's footprint and roots on absent terrain
 * (rootHeight NaN) are dropped.
 */
void forEachTileBlade(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                      const terrain::HeightField& terrain, const DensityGrid& density, int tx, int tz,
                      const std::function<void(const FieldBlade&)>& visit);

/** Blades of the whole field (every tile). */
std::size_t countFieldBlades(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                             const terrain::HeightField& terrain, const DensityGrid& density);

/** Most terrain samples tileHeightRange reads; tiles over more fall back to the terrain's whole range. */
inline constexpr int kMaxTileRangeSamples = 256;

/**
 * Height range (x min, y max, metres) of the terrain samples inside tile (tx, tz) and on its border; x > y
 * when none is valid. Tiles spanning more than kMaxTileRangeSamples samples (a terrain much finer than the
 * tiles) get `whole`, the terrain's range. With the tallest blade on top, the tile's box for culling;
 * computed when needed (by the CPU reference and the tile pass alike), so nothing is stored per tile.
 */
glm::vec2 tileHeightRange(const FieldLayout& layout, const terrain::HeightField& terrain, int tx, int tz,
                          glm::vec2 whole);

/** Tiles (x0, z0, countX, countZ) that can hold blades within `distance` metres of world (x, z) `eye`. */
glm::ivec4 tileWindow(const FieldLayout& layout, glm::vec2 eye, float distance);

} // namespace sylva::grass
