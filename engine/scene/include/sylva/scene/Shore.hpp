#pragma once

#include <sylva/core/Files.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sylva::scene {

/**
 * A lake or sea surface at a level with a folding-textured shore band (docs/scenes.md "Water with a
 * folding-textured shore"). Heights are those of the drawn height field (world metres, already multiplied by
 * the terrain's vertical exaggeration); depths, `band` and `wet` are true metres (divided by it).
 */
struct ShoreSettings {
  /** World height of the water surface, metres (same vertical scale as the drawn height field). */
  float level = 0.0f;
  /** True metres of water depth over which the shore band fades from 1 (waterline) to 0. */
  float band = 6.0f;
  /** True metres above the waterline over which the wet strip fades from 1 to 0. */
  float wet = 0.5f;
  /** World metres per repeat of the folding texture along the shore (its width); its height scales with it.
   */
  float tile = 12.0f;
  /** Seconds per swash cycle; 0 = the folding project's longest profile period (one cycle at its speed). */
  float period = 0.0f;
  /**
   * Where the water's edge lies in the folding image at rest (swash phase 0), as a fraction of the image
   * height from its top row (0.47 for data/folding/beach.json): that row is laid on the waterline.
   */
  float waterline = 0.47f;
  /** The folding project (sylva-fold JSON) whose frames animate the band; its water must advance down the
   * image. Default: the data folder's folding/beach.json (the wave swash; dataPath()). */
  std::string folding = dataPath("folding/beach.json").string();
};

/** Smallest slope (true metres per metre) used to turn depth into distance from the waterline. */
inline constexpr float kMinShoreSlope = 0.02f;
/** Directions (evenly spaced in angle) the swash texture is laid along; see swashCoords. */
inline constexpr int kSwashDirections = 8;

/** Throws sylva::Error naming the field when a setting is out of range (band, wet, tile > 0, period >= 0,
 * ...). */
void validate(const ShoreSettings& settings);

/**
 * True water depth at world (x, z) metres, metres, positive under water: (level − heightAt(field, x, z)) /
 * verticalScale (bilinear, clamped to the footprint). NaN where the height is absent.
 */
float waterDepth(const terrain::HeightField& field, float verticalScale, float level, float x, float z);

/**
 * The true slope vector (∂h/∂x, ∂h/∂z) / verticalScale at world (x, z) metres (points uphill): central
 * differences of the bilinear surface at x ± ½·spacingX (z ± ½·spacingZ), the offsets clamped to the
 * footprint and divided by the actual distance (0 on an axis where no difference can be formed). NaN heights
 * give (0, 0). Equals normalAt's slope where every sample is valid; the water shader computes exactly this.
 */
glm::vec2 shoreGradient(const terrain::HeightField& field, float verticalScale, float x, float z);

/**
 * Shore-band weight for a true water depth in metres: 1 − smoothstep(0, band, depth) under water, 1 −
 * smoothstep(0, wet, −depth) on the wet strip above the waterline, 0 beyond it and for NaN.
 */
float shoreBand(float depth, const ShoreSettings& settings);

/**
 * Where the swash texture is read (coordinates of the folding frame: u to the right, repeating; v down from
 * the top row, clamped to [0, 1] by the sampler). The image's "advance" direction (down the image, where the
 * water runs) is turned to point up the local slope so that waves run up the beach:
 *
 * - v = waterline + d / (tile · aspect), d = −depth / max(|gradient|, kMinShoreSlope) the horizontal distance
 *   (metres) uphill of the waterline, aspect = frame height / width, so the image's resting water edge lies
 * on the waterline and its rows follow the depth contours;
 * - u = dot(xz, t_k) / tile with t_k = (sin a_k, −cos a_k) for the k-th of kSwashDirections directions
 *   a_k = k · 2π / kSwashDirections: the texture tiles in world metres along a fixed axis (no swirling far
 * from the origin); the two directions around the uphill angle are blended, `mix` = smoothstep(0.3, 0.7, f)
 * with f the fraction between them, so the texture's u axis is within ±½·(2π / kSwashDirections) of the shore
 * line.
 *
 * With a zero gradient the uphill angle is taken as 0 (+x).
 */
struct SwashCoords {
  glm::vec2 uv[2]{}; ///< frame coordinates for the two directions around the uphill angle
  float mix = 0.0f;  ///< weight of uv[1] (uv[0] gets 1 − mix)
};
/** The swash texture coordinates at world (x, z) for water `depth` metres deep with the terrain's height
 * `gradient` there. */
SwashCoords swashCoords(glm::vec2 xz, float depth, glm::vec2 gradient, const ShoreSettings& settings,
                        float aspect);

/**
 * The water mesh's grid: cells of `stride` height samples per edge over the footprint (the last row and
 * column may be shorter), cellsX × cellsZ of them, so at most maxCells per axis.
 */
struct WaterGrid {
  /** Height-field samples per water grid cell side. */
  int stride = 1;
  /** Water grid cells along x. */
  int cellsX = 1;
  /** Water grid cells along z. */
  int cellsZ = 1;
};
/** The water grid over a field of the given samples: the smallest stride with at most `maxCells` cells along
 * its longer side. */
WaterGrid waterGrid(int fieldWidth, int fieldHeight, int maxCells);

/**
 * The cells of `grid` (index x + z · cellsX, ascending) where the water can show: those with a height sample
 * below `wetTop` (world metres: the level plus the wet strip) within the cell or the ring of samples around
 * it. The water shader discards every fragment whose bilinear ground height is at or above wetTop (dry
 * ground), and a fragment of a cell reads samples of that cell only (the ring covers rounding at its edges),
 * so leaving out the other cells changes no pixel. NaN (absent) samples count as dry. `tolerance` (world
 * metres, ≥ 0) keeps cells whose samples all lie less than that above wetTop (float rounding in the shader's
 * compare).
 */
std::vector<std::uint32_t> wetCells(const terrain::HeightField& field, const WaterGrid& grid, float wetTop,
                                    float tolerance);

/**
 * The wet cells `cells` (wetCells' indices, ascending) as rectangles of cells (x, z of the first cell, cells
 * along x, along z), each drawn as one quad. Cells whose four corner samples all lie at or below `level −
 * lift` (world metres) have their surface flat at `level` (the shader's max(level, height + lift)): aligned
 * square blocks of them (64, 32, 16 then 8 cells a side, largest first) become one rectangle each, which
 * waterTriangles draws as a fan with a fraction of the cells' vertices. Every other wet cell stays a 1 × 1
 * rectangle. Together the rectangles cover exactly `cells`, each once; absent (NaN) corners are never flat.
 */
std::vector<glm::uvec4> waterRects(const terrain::HeightField& field, const WaterGrid& grid,
                                   std::span<const std::uint32_t> cells, float level, float lift);

/**
 * The water mesh of `rects` (waterRects) as triangles, three grid points (cell corners, x and z) each: a 1 ×
 * 1 rectangle as its cell's two triangles, a larger one (at least 2 × 2 cells) as a fan from a grid point
 * inside it to every grid point of its border (2·(w + h) triangles instead of 2·w·h), so a neighbour's
 * corners on the border are corners of the fan too: no T-junction, no crack between the flat water and its
 * shore cells. Strips one cell wide stay cells. Every triangle turns the same way as the cells' (x, z) → (x,
 * z + 1) → (x + 1, z).
 */
std::vector<glm::ivec2> waterTriangles(std::span<const glm::uvec4> rects);

/**
 * Time (seconds) of the folding frame shown at scene time `time` seconds: fract(time / period) ·
 * projectPeriod in double, so a swash cycle of `period` seconds plays one cycle of the project (`period` 0 =
 * projectPeriod). Deterministic: equal times give equal frames. Throws sylva::Error for a period <= 0.
 */
double swashTime(double time, double period, double projectPeriod);

} // namespace sylva::scene
