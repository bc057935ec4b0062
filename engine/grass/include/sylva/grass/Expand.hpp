#pragma once
// A blade's knot line expanded to a triangle strip (paper Fig. 7), bent by the wind: the CPU reference of the
// grass vertex shader.

#include <sylva/grass/BladeType.hpp>

#include <shared/Grass.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace sylva::grass {

/** One vertex of a blade's strip. */
struct BladeVertex {
  /** World position, metres. */
  glm::vec3 position{0.0f};
  /** Unit normal of the blade's face (towards its front). */
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  /** 0 at the root, 1 at the tip. */
  float along = 0.0f;
  /** −1 on the left edge, +1 on the right. */
  float side = 0.0f;
};

/**
 * The strip of `blade` (type `type`, level `lod` in 0..2) rooted at world `root`: two vertices per knot (left
 * then right). The knot line is scaled by blade.placement.w, turned about the vertical by placement.z, then
 * bent downwind: segment k turns by θ·(s_k/L)² about the horizontal axis across the wind, θ = min(1.3,
 * 0.12·|wind| / stiffness) radians, which keeps every segment's length (no stretching in strong wind). Throws
 * sylva::Error for a lod outside 0..2.
 */
std::vector<BladeVertex> expandBlade(const BladeType& type, int lod, const gpu::GrassBlade& blade,
                                     const glm::vec3& root, const glm::vec2& windVelocity);

/**
 * The blade's bent knot line alone (world metres, root first): the centres of expandBlade's vertex pairs. The
 * rest pose of a simulated blade (at level 0: kSimKnots knots).
 */
std::vector<glm::vec3> bladeCentreLine(const BladeType& type, int lod, const gpu::GrassBlade& blade,
                                       const glm::vec3& root, const glm::vec2& windVelocity);

/** bladeCentreLine at level 0 written into `out` (no allocation: the solver's rest poses). */
void bladeCentreLine(const BladeType& type, const gpu::GrassBlade& blade, const glm::vec3& root,
                     const glm::vec2& windVelocity, std::span<glm::vec3, SYLVA_GRASS_LOD0_KNOTS> out);

/** The bend angle θ (radians) for a wind speed (m/s) and stiffness. */
float bendAngle(float windSpeed, float stiffness);

} // namespace sylva::grass
