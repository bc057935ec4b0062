#pragma once
// Skeleton refining (paper §4.4, eq. 1–3, Algorithm 1): adjacent knots that move alike over a sequence of
// frames are merged until the wanted knot count remains. Frames come from a recording of the moving blade or
// from swayFrames(), a kinematic model of a blade swaying in wind.

#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sylva::capture {

/**
 * Knot trajectories: frames[f][k] is knot k at frame f (metres, any fixed space). Every frame has the same
 * knot count; knot 0 is the root, the last knot the tip. A single frame is a valid (static) sequence.
 */
using KnotFrames = std::vector<std::vector<glm::vec3>>;

/** Options of refineKnots. */
struct RefineOptions {
  /** Knots to keep (≥ 2). Counts at or above the input count return the input unchanged. */
  int knots = 16;
  /** μ of eq. 1: weight of the mean distance against the variance of the distance, in [0, 1]. */
  double mu = 0.5;
  /**
   * Keep the root and the tip where they are: a merge that involves the first (last) knot replaces the pair
   * by that knot, its width included, instead of by the midpoint and mean width (the paper always takes the
   * midpoint, which shortens the blade).
   */
  bool keepEnds = true;
  /** What the variance term of D measures. */
  enum class Measure {
    /**
     * The paper's eq. 3: the variance of the scalar distance |a − b|. Adjacent knots of an inextensible blade
     * keep their distance however the blade bends, so this term sees stretching and noise only.
     */
    Distance,
    /**
     * The variance of the relative position a − b (a vector): it grows when the pair turns relative to the
     * rest of the motion, i.e. where the blade bends, which is what "moves differently" means for a blade.
     */
    Displacement,
  };
  /** Which variance term refining uses. */
  Measure measure = Measure::Distance;
  /**
   * Lengths are divided by this (metres) before D is formed, so that μ weighs comparable numbers: with a unit
   * of the mean knot spacing, dis ≈ 1 for neighbours and var is in spacings². 0: raw metres (the paper),
   * where var (m²) is negligible next to dis (m) at blade scale.
   */
  double unitMetres = 0.0;
};

/** Result of refining: the merged trajectories, widths and how many input knots each output knot stands for.
 */
struct RefineResult {
  /** The merged knots' trajectories (one per output knot). */
  KnotFrames frames;
  /** Full width of each output knot. */
  std::vector<float> widths;
  /** How many input knots each output knot stands for. */
  std::vector<int> merged;
};

/**
 * Movement difference D(a, b) = μ·dis + (1 − μ)·var over the n frames (eq. 1–3), with dis = Σd/n and
 * var = Σd²/n − (Σd)²/n², d = |a_i − b_i|. The paper's eq. 3 divides the squared sum by n; that is not a
 * variance (it grows with n), so the n² of the definition is used.
 */
double movementDifference(std::span<const glm::vec3> a, std::span<const glm::vec3> b, double mu);

/** D with the measure and unit of `options` (movementDifference is Distance in raw metres). */
double movementDifference(std::span<const glm::vec3> a, std::span<const glm::vec3> b,
                          const RefineOptions& options);

/**
 * Greedy refining in O(n log n): a binary heap of adjacent-pair differences with lazy invalidation over a
 * doubly linked knot list. Merges the pair of smallest D (ties: the pair nearer the root) into its per-frame
 * midpoint (see keepEnds), widths into their mean, until options.knots remain. Produces exactly the result of
 * refineKnotsReference. `widths` may be empty (then the result's widths are empty) or have one value per
 * knot. Throws sylva::Error for no frames, fewer than 2 knots, frames of different knot counts, knots < 2, μ
 * outside [0, 1], non-finite positions, or widths of the wrong count, non-finite or negative.
 */
RefineResult refineKnots(const KnotFrames& frames, std::span<const float> widths,
                         const RefineOptions& options);

/** The paper's Algorithm 1 as written (each iteration recomputes every difference: O(n²)); the oracle. */
RefineResult refineKnotsReference(const KnotFrames& frames, std::span<const float> widths,
                                  const RefineOptions& options);

/** A kinematic model of a blade swaying in wind, for refining without a recording. */
struct SwayOptions {
  /** Frames of the generated sequence. */
  int frames = 60;
  /** Frames per second of the generated sequence. */
  double fps = 30.0;
  /** Tip deflection angle amplitude in radians (the bend accumulated from root to tip). */
  double amplitude = 0.5;
  /** Sway frequency in Hz (a gust cycle). */
  double frequency = 0.7;
  /** Travelling-wave lag of the bend from root to tip, radians: the tip follows the root's motion late. */
  double lag = 1.2;
  /** Seed of the per-frame turbulence added to the sway (±10 % of the amplitude). */
  std::uint64_t seed = 1;
};

/**
 * Frames of a blade bending about `axis` (through each knot; any non-zero length, normalised; e.g. the
 * blade's width direction) with a cantilever-like profile: at time t = frame/fps, segment k (from knot k to k
 * + 1) is its rest direction turned by θ_k = (amplitude·sin(2π f t − lag·s_k/L) + turbulence)·(s_k/L)², with
 * s_k the rest arc length at the segment's far end, L the blade's length and turbulence one value per frame,
 * uniform in ±0.1·amplitude. So the root stays, the base barely moves, the tip moves most and turns by up to
 * the amplitude; segment lengths are preserved. frames[0] is the rest pose bent at t = 0. Throws sylva::Error
 * for fewer than 2 knots, a zero-length blade, non-finite input, a zero axis, frames < 1 or fps ≤ 0.
 */
KnotFrames swayFrames(std::span<const glm::vec3> restKnots, const glm::vec3& axis,
                      const SwayOptions& options);

} // namespace sylva::capture
