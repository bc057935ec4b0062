#pragma once
// From depth frames to blade models: extraction frame by frame, tracking blades through a recording (their
// movement drives refining), simulated sway when there is no recording, the change from camera to blade
// space, refining to levels, and the whole run as `sylva capture` makes it (captureBlades).

#include <sylva/blades/BladeModel.hpp>
#include <sylva/capture/Extract.hpp>
#include <sylva/capture/Refine.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace sylva::capture {

/**
 * One blade followed through the frames of a recording: its knots (camera space, metres) per frame, the
 * frames where it was not found (held from the previous frame), and the blade as captured in the reference
 * frame.
 */
struct TrackedBlade {
  /** The blade as captured in the reference frame. */
  CapturedBlade reference;
  /** Its knots per frame, camera space, metres. */
  KnotFrames motion;
  /** Frames where it was not found (held from the previous frame). */
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
  /** Measure lengths in metres (the paper's units) instead of mean knot spacings. */
  bool rawMetres = false;
  /** Without a recording, refine over a simulated sway (swayFrames) instead of the static pose alone. */
  bool simulateSway = true;
  /** The simulated sway (when simulateSway). */
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

/** How the blades of a run move while they are refined. */
enum class CaptureMotion {
  Auto,      ///< Recording when the run has several frames, else Sway
  Recording, ///< tracked through the frames (needs at least 2)
  Sway,      ///< a simulated sway of the reference frame's pose
  None,      ///< the static pose alone
};

/** What captureBlades() does with a run of depth frames. */
struct CaptureSettings {
  /** How blades are found in each frame. */
  ExtractOptions extract;
  /** Levels, μ and the variance measure (simulateSway is set from motion). */
  ModelOptions model;
  /** Whether refining sees a recording's motion or a simulated sway. */
  CaptureMotion motion = CaptureMotion::Auto;
  /** Models are named "<name>-<index>". */
  std::string name = "capture";
  /** > 0: every model is scaled so that the longest blade is this long, metres (relative depth has no scale).
   */
  double scaleToMetres = 0.0;
  /** The models file's generator line. */
  std::string generator;
};

/** What a capture run found and made. */
struct CaptureRun {
  std::vector<ExtractResult> results;         ///< per frame of the run, the first being the reference
  std::vector<TrackedBlade> tracks;           ///< the reference frame's blades through the run
  DepthFrame reference;                       ///< the first frame (its blades are the models)
  blades::BladeModelFile file;                ///< one model per tracked blade
  std::vector<std::string> warnings;          ///< every frame's extraction warnings, in order
  CaptureMotion motion = CaptureMotion::Auto; ///< the motion used (never Auto)
  float scale = 1.0f;                         ///< the factor scaleToMetres applied (1: none)
};

/**
 * Captures the blades of `frameCount` depth frames (`frame(i)` loads frame i of the run, 0-based, lazily:
 * recordings can be long): extraction per frame (a progress line `label` when there are several; Ctrl-C
 * cancels), tracking through the frames, one blade model per blade of the first frame with `source` as each
 * model's file label. Throws sylva::Error naming the frame when the first frame has no blade, when
 * CaptureMotion::Recording has fewer than 2 frames, and "capture: cancelled" when cancelled.
 */
CaptureRun captureBlades(int frameCount, const std::function<DepthFrame(int)>& frame,
                         const CaptureSettings& settings, const std::string& source,
                         const std::string& label);

/**
 * What `sylva capture` prints about `run`: the reference frame (label, `kind` of input, size, blades,
 * clusters, depth range), one line per blade (knots, length, widest width, skeleton method), the refinement
 * (`levels` as given, frames, motion), with `explain` every cluster's centre, junctions, depth layer and what
 * was not taken as a blade and why, and for several frames the blade-frames tracking did not find. Lines end
 * in '\n'.
 */
std::string describeCapture(const CaptureRun& run, const std::string& kind, const std::string& levels,
                            bool explain);

/**
 * The stages of extracting `frame` as PNGs in `dir` (each written atomically): 1-depth (the depth in grey),
 * 2-mask, 3-contour (clusters, centres and junctions), 4-signal (the first cluster's contour distance with
 * its junctions), 5-blades (the blades over the depth).
 */
void writeCaptureStages(const std::filesystem::path& dir, const DepthFrame& frame,
                        const ExtractResult& result);

} // namespace sylva::capture
