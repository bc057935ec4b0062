#pragma once
// The patch (paper §4.5): one list of blades scattered over a square the size of a tile. Every tile of the
// field draws a contiguous range of it, so a field of any size stores only the patch.

#include <shared/Grass.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace sylva::grass {

/** How the patch is made. */
struct PatchSettings {
  /** Blades in the patch (the paper: 16,384). */
  int blades = 16384;
  /** Tile side, metres: blade roots are spread over [0, tileSize)². */
  float tileSize = 2.0f;
  /** Scale range of the blades (uniform). */
  float minScale = 0.7f;
  /** Largest blade scale. */
  float maxScale = 1.3f;
  /** Relative frequency of each blade type (one per type; empty: equal). */
  std::vector<float> typeWeights;
  /** Seed of the blades' roots, types, scales and orientations. */
  std::uint64_t seed = 1;
};

/**
 * Makes the patch: roots by a jittered grid over the tile (even cover, no clumps; shuffled so any contiguous
 * range is an unbiased sample), seeded rotation, scale and type. Deterministic for the settings. Throws
 * sylva::Error for absurd counts (outside 1..2^22), non-positive or non-finite sizes, bad scale ranges, or
 * weights that do not match `types` or sum to zero.
 */
std::vector<gpu::GrassBlade> makePatch(const PatchSettings& settings, int types);

/** Bytes of a patch on the GPU (blades + the blade-type knot tables). */
std::size_t patchBytes(std::size_t blades, std::size_t types);

/**
 * Bytes the same field would take storing every blade with its own 16 knots (position vec4 and width, as the
 * paper's per-blade buffers do) — the comparison of the paper's 24 MB against 4 GB.
 */
std::size_t perBladeFieldBytes(std::size_t fieldBlades);

} // namespace sylva::grass
