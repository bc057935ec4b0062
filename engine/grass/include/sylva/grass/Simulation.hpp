#pragma once
// Per-blade simulation (docs/grass-simulation.md): the constraint solver of Han & Harada 2012 (AMD TressFX)
// on the field's blades, one fixed step at a time: Verlet with damping, global shape, local shape with frames
// propagated along the blade (keeps twist and curl), wind, edge lengths, collision with bodies and the ground
// (hard, last), a velocity clamp. The rest pose each blade returns to is its procedural pose at that moment
// (bladeCentreLine: the field's blade bent by the same wind the vertex shader uses), so a blade that starts
// simulating, or stops, does not pop. This CPU reference is multithreaded and deterministic; the compute
// shader shaders/grass/simulate.comp performs the same operations in the same order. The CPU solver runs on
// SIMD lanes (several blades at once, bit-identical to the scalar reference, which stays for comparisons).

#include <sylva/grass/BladeType.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace sylva::grass {

/** Knots of a simulated blade (the finest level). */
inline constexpr int kSimKnots = 16;

/**
 * How the CPU steps the blades: one blade at a time (the scalar reference the compute shader mirrors) or one
 * blade per SIMD lane (Highway, the best instruction set of the machine), with bit-identical results.
 */
enum class SolverKernel { Simd, Scalar };

/** Solver parameters; defaults from the TressFX sample where it has them. */
struct SolverSettings {
  /** Fixed steps per second, whatever the frame rate. */
  float rate = 60.0f;
  /** Velocity damping d: each step keeps exp(−d·Δt·60) of the velocity. */
  float damping = 0.068f;
  /** Global shape: pull towards the rest pose with this stiffness, for the knots below globalRange of the
   * blade. */
  float globalStiffness = 0.408f;
  /** Share of each blade (from the root) that gets global shape, [0, 1]. */
  float globalRange = 0.308f;
  /**
   * Local shape stiffness per step (corrected for the iteration count when correctStiffness), and passes:
   * each edge is corrected localIterations times before the next (see docs/grass-simulation.md). Not
   * TressFX's 0.908: corrected per edge, that pushes each edge's lower knot back hard enough to make blades
   * in steady wind flicker between two states; 0.6 bends within 15 % of it and is stable.
   */
  float localStiffness = 0.6f;
  /** Local shape passes per edge. */
  int localIterations = 2;
  /** Edge-length passes (even edges, then odd). */
  int lengthIterations = 2;
  /**
   * Use s' = 1 − (1 − s)^(1/K) per pass so K passes act like one of stiffness s: the apparent stiffness no
   * longer depends on the iteration count.
   */
  bool correctStiffness = true;
  /**
   * Downward acceleration, m/s². 0 by default: a captured or procedural blade's shape is already its shape
   * under its own weight, and gravity on top would sag it away from the pose the field draws.
   */
  float gravity = 0.0f;
  /** Wind force on top of the rest pose's wind bend: a = windDrag·|w⊥|·w⊥, w⊥ the wind across the segment. */
  float windDrag = 0.0f;
  /** Largest knot speed, m/s (velocity clamp). */
  float maxSpeed = 6.0f;
  /** Bodies at least this heavy (kg) trample the blades they touch. */
  float trampleMass = 2.0f;
  /** Fraction of the shape stiffness a freshly trampled blade loses; it comes back over trampleRecovery
   * seconds. */
  float trampleSoftening = 0.97f;
  /** Seconds over which a trampled blade recovers its stiffness. */
  float trampleRecovery = 6.0f;
  /** The CPU kernel (results do not depend on it; the scalar one is for comparisons and benchmarks). */
  SolverKernel kernel = SolverKernel::Simd;
  /** Throws sylva::Error naming the field for non-finite, negative or out-of-range values. */
  void validate() const;
  /** Δt of one step, seconds. */
  float step() const { return 1.0f / rate; }
};

/**
 * The constants of one step, computed once in float from the settings: the CPU solver and the compute shader
 * (GrassSimUniforms) use these same values.
 */
struct SolverConstants {
  /** Δt of one step, seconds. */
  float dt = 0.0f;
  /** Fraction of the velocity kept per step, exp(−d·Δt·60). */
  float keep = 1.0f;
  /** gravity·Δt², metres. */
  float gravityStep = 0.0f;
  /** Largest move of a knot per step (maxSpeed·Δt), metres. */
  float maxStep = 0.0f;
  /** Global shape stiffness per step. */
  float global = 0.0f;
  /** Knots with index < globalKnots get global shape. */
  float globalKnots = 0.0f;
  /** ½·min(s', 0.95) with s' the (corrected) per-pass local stiffness. */
  float localShare = 0.0f;
  /** SolverSettings::windDrag. */
  float windDrag = 0.0f;
  /** SolverSettings::trampleMass, kg. */
  float trampleMass = 0.0f;
  /** SolverSettings::trampleSoftening. */
  float softening = 0.0f;
  /** Trample lost per step, Δt / recovery time. */
  float recoveryStep = 0.0f;
  /** Local shape passes per step. */
  int localPasses = 1;
  /** Edge-length passes per step. */
  int lengthPasses = 1;
  /** The CPU kernel. */
  SolverKernel kernel = SolverKernel::Simd;
};
/** The constants of one step for `settings`. */
SolverConstants solverConstants(const SolverSettings& settings);

/** A body's collision shape for the blades, world metres: a capsule from a to b (a sphere when a == b). */
struct BladeCollider {
  /** One end of the capsule's axis, world metres. */
  glm::vec3 a{0.0f};
  /** The other end (equal to a for a sphere). */
  glm::vec3 b{0.0f};
  /** Capsule radius, metres. */
  float radius = 0.0f;
  /** kg (0 = static or unknown): heavy bodies trample. */
  float mass = 0.0f;
};

/**
 * Blades in simulation: knot positions (current and previous step) and the rest pose to return to,
 * blade-major (blade i's knots at [i·kSimKnots, (i + 1)·kSimKnots)), plus per blade how trampled it is
 * (0..1).
 */
struct SimBlades {
  /** Knot positions now, world metres. */
  std::vector<glm::vec3> position;
  /** Knot positions one step ago. */
  std::vector<glm::vec3> previous;
  /** The rest pose the blade returns to. */
  std::vector<glm::vec3> rest;
  /** How trampled each blade is (0..1). */
  std::vector<float> trample;
  /** Blades held. */
  std::size_t count() const { return trample.size(); }
  /** Appends a blade at rest: position = previous = rest = `pose` (kSimKnots knots), not trampled. */
  void add(const std::vector<glm::vec3>& pose);
};

/** Ground height (metres) at world (x, z), or NaN where there is none (no ground collision there). */
using GroundFunction = std::function<float(float x, float z)>;

/**
 * One solver step of blade `blade` of `blades` (its rest pose already set for this step) with `colliders`,
 * the wind at its root (world x, z, m/s) and the ground (may be empty: no ground).
 */
void simulateBlade(SimBlades& blades, std::size_t blade, const std::vector<BladeCollider>& colliders,
                   glm::vec2 wind, const GroundFunction& ground, const SolverConstants& constants);

/**
 * What the caller knows of the ground, so the SIMD kernel can skip calling `ground` knot by knot; results
 * are the same either way. The default knows nothing.
 */
struct GroundShortcuts {
  /**
   * The ground is rootHeight over this grid (at least 2 × 2 samples): the kernel samples it on its lanes,
   * with the same operations.
   */
  const terrain::HeightField* grid = nullptr;
  /** Inside [lo, hi] (world x, z, metres) the ground is nowhere higher than `ceiling` (metres), so knots
   * there above the ceiling need no lookup. */
  glm::vec2 lo{1.0f};
  /** Upper corner of that rectangle (lo > hi: none). */
  glm::vec2 hi{0.0f};
  /** Highest ground inside [lo, hi], metres. */
  float ceiling = 0.0f;
};

/**
 * One solver step of the blades `indices` of `blades` (rest poses already set), blade indices[i] in the wind
 * wind[i] (world x, z, m/s), on the kernel of `constants`, on the calling thread. Same results as
 * simulateBlade on each; `shortcuts` only save ground lookups (the SIMD kernel uses them).
 */
void simulateBlades(SimBlades& blades, std::span<const std::uint32_t> indices,
                    std::span<const glm::vec2> wind, const std::vector<BladeCollider>& colliders,
                    const GroundFunction& ground, const SolverConstants& constants,
                    const GroundShortcuts& shortcuts = {});

/**
 * One solver step of every blade in `blades` (rest poses already set for this step), with `colliders`, the
 * wind velocity at each blade's root (`wind[i]`, world x and z in m/s; may be empty: calm) and the ground.
 * Blades are independent: split over threads by parallelFor, the result does not depend on the thread count.
 * Colliders are tested against every blade; the tile manager gives each tile only the colliders near it.
 */
void simulateStep(SimBlades& blades, std::size_t first, std::size_t count,
                  const std::vector<BladeCollider>& colliders, const std::vector<glm::vec2>& wind,
                  const GroundFunction& ground, const SolverSettings& settings);

/** simulateStep over all blades. */
void simulateStep(SimBlades& blades, const std::vector<BladeCollider>& colliders,
                  const std::vector<glm::vec2>& wind, const GroundFunction& ground,
                  const SolverSettings& settings);

} // namespace sylva::grass
