#pragma once

#include <sylva/terrain/HeightField.hpp>

#include <sylva/core/Image.hpp>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace sylva::terrain {

/**
 * CPU references for the terrain's normal map and splat map (the paper's two compute-shader passes). The GPU
 * compute shaders must reproduce these formulas exactly; tests compare both.
 *
 * Pixel (x, y) of every output image corresponds to height sample (i, j) = (x, y): same size as the field,
 * row 0 = sample row 0 (north), no flip.
 */

/** What the Sobel filter reads for neighbours outside the grid. */
enum class BorderMode {
  Clamp,    ///< the nearest edge sample (clamp-to-edge; default, no artificial cliff at the border)
  Constant, ///< SobelOptions::constantHeight metres (the paper: "usually 0")
};

/** Options of sobelNormalMap. */
struct SobelOptions {
  /** What the neighbours outside the field are: the edge sample (Clamp), or a constant height. */
  BorderMode border = BorderMode::Clamp;
  /** Height in metres of every outside neighbour with BorderMode::Constant. */
  float constantHeight = 0.0f;
};

/**
 * World-space unit normals (x, y, z; y up; NOT remapped to [0, 1]) per sample, as a width×height RGB F32
 * image. With h(a, b) the height of neighbour (i + a, j + b), a, b ∈ {−1, 0, 1}, in metres:
 *
 *     gx = [h(1,−1) + 2·h(1,0) + h(1,1) − h(−1,−1) − 2·h(−1,0) − h(−1,1)] / (8 · spacingX)
 *     gz = [h(−1,1) + 2·h(0,1) + h(1,1) − h(−1,−1) − 2·h(0,−1) − h(1,−1)] / (8 · spacingZ)
 *     n  = normalize(−gx, 1, −gz)
 *
 * (gx, gz are ∂h/∂x, ∂h/∂z: exact for a plane.) Neighbour lookup, in this order: an index outside the grid is
 * clamped to the edge (Clamp) or reads constantHeight (Constant); an absent (NaN) neighbour reads the centre
 * sample's height instead. An absent centre sample gives n = (0, 1, 0). Evaluated in 32-bit float as
 * ((h(1,−1) + 2·h(1,0) + h(1,1)) − (h(−1,−1) + 2·h(−1,0) + h(−1,1))) · (1 / (8 · spacingX)) (likewise gz),
 * then n = (−gx, 1, −gz) / sqrt(gx² + 1 + gz²). Thread-safe; runs on parallelFor.
 */
Image sobelNormalMap(const HeightField& field, const SobelOptions& options = {});

/**
 * One splat (blend) layer: where a terrain texture applies, by height and slope. Weights ramp linearly over a
 * soft edge of width heightBlend (metres) / slopeBlend (degrees) centred on each limit.
 */
struct SplatLayer {
  /** Unique, non-empty name (e.g. the texture it selects). */
  std::string name;
  /** Lowest height of the layer, metres (minHeight ≤ maxHeight). */
  float minHeight = -1.0e9f;
  /** Highest height of the layer, metres. */
  float maxHeight = 1.0e9f;
  /** Least slope, degrees from horizontal: 0 = flat, 90 = vertical (minSlope ≤ maxSlope). */
  float minSlope = 0.0f;
  /** Steepest slope, degrees from horizontal. */
  float maxSlope = 90.0f;
  /** Width of the soft edge at minHeight/maxHeight, metres (≥ 0; 0 = hard edge). */
  float heightBlend = 0.0f;
  /** Width of the soft edge at minSlope/maxSlope, degrees (≥ 0; 0 = hard edge). */
  float slopeBlend = 0.0f;

  /** Every field equal. */
  bool operator==(const SplatLayer&) const = default;
};

/** Most layers splatMap accepts (16 RGBA pages). */
inline constexpr int kMaxSplatLayers = 64;

/**
 * Raw (unnormalised) weight of `layer` at `height` metres and `slopeDegrees`:
 *     w = ramp(height; minHeight, maxHeight, heightBlend) · ramp(slope; minSlope, maxSlope, slopeBlend)
 *     ramp(v; lo, hi, b) = saturate((v − lo)/b + ½) · saturate((hi − v)/b + ½)   for b > 0
 *     ramp(v; lo, hi, 0) = (lo ≤ v ≤ hi) ? 1 : 0
 */
float splatWeight(const SplatLayer& layer, float height, float slopeDegrees);

/**
 * Splat weights per sample, normalised to sum 1 over the layers, as RGBA F32 pages for a GL texture array:
 * page k, channel c (R, G, B, A = 0..3) holds layer 4k + c; there are ceil(layers / 4) pages of width×height;
 * channels past the last layer are 0. Slope = acos(clamp(n.y, −1, 1)) in degrees from `normals` (RGB(A) F32,
 * same size, e.g. sobelNormalMap); height = the field sample. Where no layer applies (all raw weights 0) the
 * first layer gets weight 1 (the base layer). Absent height samples get all weights 0. Float arithmetic:
 * weight / sum of weights.
 *
 * `verticalScale` ≠ 1 says the field's heights were exaggerated by that factor (for display) while the rules
 * are in true metres and degrees: the rules then see height / verticalScale and the true slope
 * atan(sqrt(1 − n.y²) / (n.y · verticalScale)) in degrees.
 *
 * Throws sylva::Error for 0 or more than kMaxSplatLayers layers, or a normals image of the wrong size/type.
 */
std::vector<Image> splatMap(const HeightField& field, const Image& normals,
                            std::span<const SplatLayer> layers, float verticalScale = 1.0f);

/**
 * Default sand / grass / snow / rock rules for heights in [minHeight, maxHeight] metres (range r; 1 m if the
 * range is empty), in this layer order.
 *
 * Without a sea level: sand up to min + 0.12·r, grass from there to min + 0.7·r, snow above, all three on
 * slopes below 35°; rock on slopes above 35° at any height. Soft edges of 0.04·r metres and 6°.
 *
 * With `seaLevel` s (land relief L = max(maxHeight − s, 1 m)): sand covers everything below the beach line
 * s + max(2 m, 0.02·L) (sea floor and coast: no grass under water), grass from the beach line to s + 0.7·L,
 * snow above; rock on slopes above 35°. Soft edges of max(1 m, 0.01·L) at the beach line and 0.04·L above.
 *
 * The outer height limits lie r beyond [minHeight, maxHeight] so every sample is covered.
 */
std::vector<SplatLayer> defaultSplatLayers(float minHeight, float maxHeight,
                                           std::optional<float> seaLevel = std::nullopt);

/**
 * The tree line of splat rules: the lowest height, true metres, at which a layer named "snow" that covers
 * flat ground (minSlope 0) starts to show, minHeight − heightBlend / 2 (where its soft edge begins). nullopt
 * when no such layer has a lower limit (the rules have no snow, or snow from the bottom of the world).
 * Forests without a height band's top stop here (scene::forestSettings), so trees do not stand on snow.
 */
std::optional<float> snowLine(std::span<const SplatLayer> layers);

/**
 * JSON {"version": 1, "layers": [{"name", "minHeight", "maxHeight", "minSlope", "maxSlope",
 * "heightBlend", "slopeBlend"}, ...]}.
 */
nlohmann::json splatLayersToJson(std::span<const SplatLayer> layers);

/**
 * Parses layer rules. `version` (1) and `layers` (1..64 objects, each with a unique non-empty `name`) are
 * required; other layer fields default to SplatLayer's values; unknown fields are errors. Throws sylva::Error
 * `WHERE: field 'layers[2].maxSlope': REASON`.
 */
std::vector<SplatLayer> splatLayersFromJson(const nlohmann::json& json, const std::string& where);

/** Loads layer rules from a JSON file; errors name the file and the field. */
std::vector<SplatLayer> loadSplatLayers(const std::filesystem::path& path);

/** Saves layer rules atomically. */
void saveSplatLayers(const std::filesystem::path& path, std::span<const SplatLayer> layers);

} // namespace sylva::terrain
