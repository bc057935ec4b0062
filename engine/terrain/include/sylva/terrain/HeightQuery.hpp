#pragma once

#include <sylva/terrain/HeightField.hpp>

#include <optional>

#include <glm/glm.hpp>

namespace sylva::terrain {

/**
 * Ground queries on a HeightField: height, normal and ray casts in world metres (y up), matching what the GPU
 * draws when the shaders follow the mapping below.
 *
 * World ↔ grid: sample (i, j) sits at world (x, z) = (i · spacingX, j · spacingZ). The grid coordinate
 * of a world position is (gx, gz) = (x / spacingX, z / spacingZ); queries clamp it to
 * [0, width − 1] × [0, height − 1] (clamp to edge): outside the footprint the edge heights continue.
 *
 * World ↔ texture (THE mapping every shader must use): with the height field uploaded as a W×H texture, texel
 * (i, j) holding sample (i, j) and texel centres at ((i + 0.5) / W, (j + 0.5) / H), a world position maps to
 *
 *     u = (x / spacingX + 0.5) / W,    v = (z / spacingZ + 0.5) / H.
 *
 * GL_LINEAR + GL_CLAMP_TO_EDGE at (u, v) is then Interpolation::Bilinear (up to the hardware's
 * reduced-precision filter weights — shaders that need centimetre agreement fetch the four texels with
 * texelFetch and interpolate in float, like heightAt). Bicubic needs 16 texelFetch reads with the Catmull-Rom
 * weights documented below.
 *
 * Absent (NaN) samples make the result NaN where they contribute with a non-zero weight.
 * All functions are pure and thread-safe.
 */
enum class Interpolation {
  /**
   * h = (1−s)·((1−t)·h₀₀ + t·h₁₀) + s·((1−t)·h₀₁ + t·h₁₁), t, s ∈ [0, 1] the fractional grid coordinates.
   * Reproduces planes exactly (up to float rounding) and is continuous (C⁰) across cells.
   */
  Bilinear,
  /**
   * Separable Catmull-Rom (Keys cubic convolution, a = −½) over the 4×4 samples around the cell, indices
   * clamped to the edge. Weights for fraction t: w₋₁ = (−t³ + 2t² − t)/2, w₀ = (3t³ − 5t² + 2)/2,
   * w₁ = (−3t³ + 4t² + t)/2, w₂ = (t³ − t²)/2. Interpolates the samples, is C¹, and reproduces polynomials up
   * to degree 2 (planes and quadratics) exactly where the 4×4 support lies inside the grid; near the edge the
   * clamped samples break this (a plane bends in the outermost cell). May overshoot the sample range.
   */
  Bicubic,
};

/**
 * Height in metres of the interpolated surface at world (x, z) metres, coordinates clamped to the footprint.
 * NaN if a contributing (non-zero weight) sample is absent.
 */
float heightAt(const HeightField& field, float x, float z,
               Interpolation interpolation = Interpolation::Bilinear);

/**
 * Unit surface normal (y up) at world (x, z) metres from central differences of the interpolated surface:
 * n = normalize(−∂h/∂x, 1, −∂h/∂z) with ∂h/∂x ≈ (h(x + ½·spacingX, z) − h(x − ½·spacingX, z)) / spacingX (and
 * likewise z). The offsets are clamped to the footprint (the divisor is the actual distance), and if one side
 * is absent the difference is one-sided against the centre; if no difference can be formed the slope on that
 * axis is 0. NaN vector only if the height at (x, z) itself is NaN.
 */
glm::vec3 normalAt(const HeightField& field, float x, float z,
                   Interpolation interpolation = Interpolation::Bilinear);

/** A ray–terrain intersection, world space. */
struct RayHit {
  /** Distance along the normalised ray direction, metres. */
  float distance = 0.0f;
  /** Hit point, world metres (y on the surface). */
  glm::vec3 position{0.0f};
  /** normalAt(hit x, hit z): unit, y up. */
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
};

/**
 * First intersection of the ray origin + t · normalize(dir), t ∈ [0, maxDistance] metres, with the terrain.
 * The terrain is the solid below the surface over the footprint [0, extentX] × [0, extentZ] (no skirts
 * outside; cells with an absent corner are holes): if the ray's first point over the footprint is on or below
 * the surface, that point is the hit (distance 0 for a ray starting over the footprint below the ground). The
 * ray is marched cell by cell (2D DDA over the grid). Bilinear: the patch along the ray is a quadratic in t,
 * solved exactly per cell (double precision). Bicubic: 8 steps per cell look for a sign change, then
 * bisection to 1e-6 m — a surface the ray enters and leaves within one step is missed (grazing rays). Throws
 * sylva::Error if dir is zero or not finite; returns nullopt for a miss.
 */
std::optional<RayHit> raycast(const HeightField& field, const glm::vec3& origin, const glm::vec3& dir,
                              float maxDistance, Interpolation interpolation = Interpolation::Bilinear);

} // namespace sylva::terrain
