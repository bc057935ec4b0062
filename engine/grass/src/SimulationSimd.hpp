#pragma once

// The grass constraint solver's SIMD kernel (SimulationSimd.cpp): the scalar reference of Simulation.cpp on
// lanes, one blade per lane, bit-identical to it. Internal to the grass module.

#include <sylva/grass/Simulation.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sylva::grass {

/** Penetration (metres) from which a contact is fully inelastic. */
inline constexpr float kContactDepth = 0.01f;

/** Blades stepped together: one AVX-512 register of floats (two AVX2 ones, four SSE4 or NEON ones). */
inline constexpr std::size_t kMaxSimdLanes = 16;

/**
 * A blade type's finest knot line as the rest pose walks it (walkBlade in Expand.cpp): the segments between
 * knots (blade space, metres before the blade's scale; [0] unused), each knot's arc length over the whole
 * (u, 0..1) and the type's stiffness.
 */
struct RestShape {
  std::array<glm::vec3, kSimKnots> segment{};
  std::array<float, kSimKnots> u{};
  float stiffness = 0.5f;
};

/** The rest shape of `type`'s finest level. */
RestShape restShape(const BladeType& type);

/** What one blade's rest pose depends on: its type, turn about the vertical and scale, root and wind. */
struct RestInput {
  std::uint32_t blade = 0;
  std::uint32_t type = 0;
  /** Radians about +Y. */
  float rotation = 0.0f;
  float scale = 1.0f;
  glm::vec3 root{0.0f};
  /** Wind at the root, world x and z, m/s. */
  glm::vec2 wind{0.0f};
};

/**
 * The rest poses (bladeCentreLine at the finest level) of `count` blades into blades.rest, several blades at
 * once: the same operations as the scalar walk (sines and cosines from the C library), bit for bit
 * bladeCentreLine's knots.
 */
void restPosesSimd(std::span<const RestShape> shapes, const RestInput* inputs, std::size_t count,
                   SimBlades& blades);

/**
 * One solver step of the `count` blades `indices[i]` of `blades`, blade `indices[i]` in the wind `wind[i]`,
 * with the instruction set Highway picks for this machine; each blade ends bit-identical to what
 * simulateBlade makes of it.
 */
void stepBladesSimd(SimBlades& blades, const std::uint32_t* indices, const glm::vec2* wind, std::size_t count,
                    const std::vector<BladeCollider>& colliders, const GroundFunction& ground,
                    const SolverConstants& constants, const GroundShortcuts& shortcuts);

} // namespace sylva::grass
