#pragma once
// From captured blades to blade models: tracking blades through a recording (their movement drives refining),
// simulated sway when there is no recording, the change from camera to blade space, and refining to levels.

#include <sylva/blades/BladeModel.hpp>
#include <sylva/capture/Extract.hpp>
#include <sylva/capture/Refine.hpp>

#include <vector>

namespace sylva::capture {

/**
 * One blade followed through the frames of a recording: its knots (camera space, metres) per frame, the
 * frames where it was not found (held from the previous frame), and the blade as captured in the reference
 * frame.
 */
struct TrackedBlade {
  CapturedBlade reference;
  KnotFrames motion;
  int missingFrames = 0;
};

/**
 * Follows the blades of results[0] (the reference frame) through the other frames: in each frame, the
 * unmatched captured blade whose tip is nearest the blade's previous tip (within `maxTipJumpPx`) continues
 * it; blades that are not found hold their previous knots. All captured blades must have the same knot count.
 */
std::vector<TrackedBlade> trackBlades(const std::vector<ExtractResult>& results, float maxTipJumpPx = 40.0f);

/** Options of makeBladeModel. */
struct ModelOptions {
  /** Knot counts of the levels of detail, finest first (e.g. 64, 32, 16). */
  std::vector<int> levels{64, 32, 16};
  /** μ of refining. */
  double mu = 0.5;
  /**
   * The variance term of refining: Displacement (default) sees where the blade bends; Distance is the paper's
   * eq. 3 as written. Lengths are measured in mean knot spacings of the captured skeleton either way, unless
   * rawMetres (the paper's units, where the variance term is negligible).
   */
  RefineOptions::Measure measure = RefineOptions::Measure::Displacement;
  bool rawMetres = false;
  /** Without a recording, refine over a simulated sway (swayFrames) instead of the static pose alone. */
  bool simulateSway = true;
  SwayOptions sway;
};

/**
 * Makes a blade model: camera space to blade space (root = knot 0 at the origin, +Y = image up, +Z towards
 * the camera), refining of `motion` (the blade's knots over frames in camera space; empty: the static pose,
 * or the simulated sway when options.simulateSway) to every level, widths and normals per level. `source` is
 * copied into the model (its motionFrames and mu are filled in). Throws sylva::Error for invalid levels (each
 * in 2..captured knots, strictly decreasing).
 */
blades::BladeModel makeBladeModel(const CapturedBlade& blade, const KnotFrames& motion,
                                  const ModelOptions& options, blades::BladeSource source);

} // namespace sylva::capture
