#pragma once
// Synthetic ground truth: blade clusters of known shape drawn into depth frames with Kinect-like noise and
// quantisation, for accuracy tests, demos and refining without a recording.

#include <sylva/capture/Depth.hpp>
#include <sylva/capture/Extract.hpp>

#include <glm/vec2.hpp>
#include <nlohmann/json_fwd.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sylva {
class Progress;
}

namespace sylva::capture {

/** The five blade shapes of the paper's captures. */
enum class BladeShape { SlimGrass, QuadraticLeaf, SlenderLeaf, BambooLeaf, SharpTip };
/** Every blade shape, in the order above. */
inline constexpr BladeShape kBladeShapes[] = {BladeShape::SlimGrass, BladeShape::QuadraticLeaf,
                                              BladeShape::SlenderLeaf, BladeShape::BambooLeaf,
                                              BladeShape::SharpTip};
/** "slim", "quadratic", "slender", "bamboo", "sharp". */
const char* bladeShapeName(BladeShape shape);
/** The shape named `name` (bladeShapeName's names); nullopt for any other. */
std::optional<BladeShape> parseBladeShape(const std::string& name);

/** Width at t ∈ [0, 1] (root → tip) as a fraction of the blade's largest width. */
float bladeWidthProfile(BladeShape shape, float t);
/** Typical length and largest width of a shape, metres. */
float bladeShapeLength(BladeShape shape);
/** Typical largest width of a shape, metres. */
float bladeShapeWidth(BladeShape shape);

/** One blade of a synthetic cluster. */
struct SyntheticBlade {
  /** The width profile. */
  BladeShape shape = BladeShape::SlimGrass;
  /** Length along the centreline, metres. */
  float lengthMetres = 0.3f;
  /** Largest full width, metres. */
  float widthMetres = 0.012f;
  /** Lean from vertical in the image plane, radians (positive: to the right). */
  float leanRadians = 0.0f;
  /** Total turn of the tangent from root to tip in the image plane, radians (positive: to the right). */
  float bendRadians = 0.0f;
  /** Tilt of the blade towards the camera, radians. */
  float tiltRadians = 0.0f;
  /** Asymmetry in [0, 1): the right half is this much narrower than the left (0: symmetric). */
  float asymmetry = 0.0f;
  /**
   * A one-sided lobe: the right edge bulges out by lobe × width at mid-length (Gaussian, σ = 8 % of the
   * length), the kind of damage or side growth that breaks symmetric matching.
   */
  float lobe = 0.0f;
  /** Where this blade's root sits relative to the scene's root, camera space, metres (+z: farther away). */
  glm::vec3 rootOffsetMetres{0.0f};
  /**
   * The root moved this much nearer to the camera along the ray through the scene's root, metres: it stays
   * on the same pixel wherever the scene's root is (a blade just in front of another from the same tuft).
   */
  float nearerMetres = 0.0f;
};

/** A cluster scene. */
struct SyntheticScene {
  /** Frame width, pixels. */
  int width = 640;
  /** Frame height, pixels. */
  int height = 480;
  /** The camera (Kinect v1 by default). */
  CameraIntrinsics intrinsics = CameraIntrinsics::kinectV1();
  /** The root of every blade in camera space, metres. */
  glm::vec3 rootMetres{0.0f, 0.2f, 0.65f};
  /** The blades, all from rootMetres. */
  std::vector<SyntheticBlade> blades;
  /**
   * The camera turned about the cluster's root: roll about its optical axis (positive: the picture turns
   * clockwise), pitch about its horizontal axis (positive: looking further down on the cluster), radians.
   */
  float rollRadians = 0.0f;
  /** Camera pitch about the root, radians (see rollRadians). */
  float pitchRadians = 0.0f;
  /** Background wall depth, metres (0: none, no data). */
  float backgroundMetres = 1.8f;
  /** Kinect-like noise: axial Gaussian σ(z) = 1.2 mm + 1.9 mm·(z − 0.4 m)², lateral edge jitter, dropouts,
   * and 11-bit quantisation. */
  bool noise = true;
  /** Standard deviation of the edges' lateral jitter, pixels. */
  float lateralNoisePx = 0.5f;
  /** Fraction of edge pixels that lose their depth (Kinect shadows). */
  float edgeDropout = 0.15f;
  /** Also draw a registered RGB frame (green blades on a brown background). */
  bool colour = true;
  /** Seed of the blade variation and the noise. */
  std::uint64_t seed = 1;
};

/**
 * A fan of `count` blades of one shape from a common root: leans spread evenly over ±spread/2 around
 * `orientationRadians`, each bending by `bendRadians` away from the centre, with seeded variation of ±10 % in
 * length and width.
 */
SyntheticScene makeCluster(BladeShape shape, int count, float bendRadians, float orientationRadians,
                           std::uint64_t seed, float spreadRadians = 1.4f);

/** How the blades of a synthetic cluster are arranged (the classes of input capture must separate). */
enum class ClusterLayout {
  /** One root, leans spread evenly (makeCluster). */
  Fan,
  /** A fan with one extra blade just in front of a neighbour, narrower and shorter, so that from the camera
   * it lies inside the neighbour's outline: only the depth step tells them apart. */
  Occluded,
  /** Two fans from roots a few centimetres apart (sideways and in depth) leaning towards each other, so
   * blades of one cross blades of the other. */
  Crossing,
  /** Many blades (count ≥ 11 in the sweep) over a narrow fan of 60°. */
  Dense,
};
/** Every cluster layout, in the order above. */
inline constexpr ClusterLayout kClusterLayouts[] = {ClusterLayout::Fan, ClusterLayout::Occluded,
                                                    ClusterLayout::Crossing, ClusterLayout::Dense};
/** "fan", "occluded", "crossing", "dense". */
const char* clusterLayoutName(ClusterLayout layout);
/** The layout named `name` (clusterLayoutName's names); nullopt for any other. */
std::optional<ClusterLayout> parseClusterLayout(const std::string& name);

/**
 * A cluster of `count` blades (Occluded and Crossing need ≥ 2) of one shape in `layout`, with the fan's
 * parameters as in makeCluster (Dense ignores `spreadRadians` and fans over 60°). Deterministic for its
 * arguments; throws sylva::Error for a count outside the layout's range.
 */
SyntheticScene makeLayoutCluster(ClusterLayout layout, BladeShape shape, int count, float bendRadians,
                                 float orientationRadians, std::uint64_t seed, float spreadRadians = 1.4f);

/**
 * One random cluster of the capture sweep, drawn from `seed`: a layout (fans, occlusion, crossing, dense
 * fans in equal shares), a shape, a count that suits the layout (fan 3–7, occluded 4–7, crossing 4–8,
 * dense 11–14), bend, lean, camera roll (±0.5 rad) and pitch (±0.3 rad), distance (0.55–0.9 m) and edge
 * dropouts (5–30 %). Deterministic. `only` draws that layout instead of the seed's (the rest as the seed
 * draws it).
 */
SyntheticScene makeSweepCluster(std::uint64_t seed, ClusterLayout* layoutOut = nullptr,
                                std::optional<ClusterLayout> only = std::nullopt);

/** Ground truth of a rendered scene. */
struct SyntheticTruth {
  /** Per blade: centreline root → tip (pixels) and full widths (pixels) at 256 samples. */
  std::vector<std::vector<glm::vec2>> centrelinePx;
  /** Per blade: full widths, pixels, at the same samples. */
  std::vector<std::vector<float>> widthsPx;
  /** The same in camera space, metres. */
  std::vector<std::vector<glm::vec3>> centrelineMetres;
  /** Per blade: full widths, metres. */
  std::vector<std::vector<float>> widthsMetres;
  /** Noise-free silhouette of all blades (255 inside), width × height. */
  std::vector<std::uint8_t> mask;
  /** Front-most blade per pixel (−1: none), width × height. */
  std::vector<int> label;
};

/** A rendered synthetic frame with its truth. */
struct SyntheticFrame {
  /** The depth frame (and colour). */
  DepthFrame frame;
  /** The true blades. */
  SyntheticTruth truth;
};

/**
 * Renders the scene (z-buffered quads between cross-sections, noise as configured). `phase` bends every blade
 * about its width direction by an extra tip angle (radians, swaying). Deterministic for a scene and phase.
 */
SyntheticFrame renderScene(const SyntheticScene& scene, float extraBendRadians = 0.0f, int frameIndex = 0);

/**
 * A swaying sequence: frame i adds a bend of amplitude·sin(2π·frequency·i/fps + per-blade phase) to every
 * blade.
 */
std::vector<SyntheticFrame> swaySequence(const SyntheticScene& scene, int frames, double fps,
                                         float amplitudeRadians, double frequencyHz);

/**
 * The truth of `frames` of `scene` as JSON ("sylva-capture-truth" version 1): the intrinsics and, per frame
 * and blade, its shape and centreline in pixels (x, y, width) and metres (x, y, z, width).
 */
nlohmann::json syntheticTruthJson(const SyntheticScene& scene, const std::vector<SyntheticFrame>& frames);

/**
 * Writes `frames` to `out`: a .png path holds the first frame as a 16-bit depth PNG (and its colour beside it
 * as `STEM-colour.png` when it has one), any other path becomes a fakenect recording folder of every frame.
 * Returns the extra files written (the colour PNG).
 */
std::vector<std::string> saveSyntheticFrames(const std::string& out,
                                             const std::vector<SyntheticFrame>& frames);

/** Accuracy of a capture against the truth (tests and `sylva capture synth --evaluate`). */
struct AccuracyReport {
  /** Blades in the truth. */
  int bladesExpected = 0;
  /** Blades captured. */
  int bladesFound = 0;
  /** IoU of the rasterised captured blades with the noise-free silhouette. */
  double silhouetteIoU = 0.0;
  /** Mean over matched blades of mean |w − w_true| / max w_true over the middle 10–90 % of the captured
   * knots. */
  double widthError = 0.0;
  /** Worst matched blade's width error. */
  double widthErrorMax = 0.0;
  /** Mean distance (pixels) of captured skeleton knots from the true centreline, and the worst blade's mean.
   */
  double skeletonErrorPx = 0.0;
  /** The worst blade's mean skeleton distance, pixels. */
  double skeletonErrorMaxPx = 0.0;
  /** Skeleton error relative to the blade's length (worst blade). */
  double skeletonErrorRelative = 0.0;
  /** Captured length / true length beyond the junctions, mean over matched blades. */
  double lengthRatio = 0.0;
  /** Each matched blade's width error (the measure of widthError), in matching order. */
  std::vector<double> bladeWidthErrors;
};

/** Matches captured blades to true blades by their tips and measures. */
AccuracyReport evaluateCapture(const SyntheticTruth& truth, const ExtractResult& result);

/**
 * Whether each blade's tip stands free in the frame, so that one depth frame can tell the blade apart: some
 * point of its last 15 % is the front-most surface there, and no other blade's pixel lies within
 * max(2, 0.6 × the blade's width at 85 % of its length) pixels of that point at a depth within 5 mm of the
 * blade's (a neighbour clearly in front or behind steps in depth and does not merge with it). From the truth
 * (noise-free labels and centrelines); one entry per blade.
 */
std::vector<bool> tipsStandFree(const SyntheticTruth& truth, int width, int height);

/** Counts of a capture sweep over one class of clusters (or all). */
struct SweepTally {
  /** Clusters captured. */
  int clusters = 0;
  int exact = 0;         ///< clusters whose blade count came out exact
  int fewer = 0;         ///< clusters with blades missing (merged or dropped)
  int blades = 0;        ///< true blades
  int widthWithin10 = 0; ///< matched blades whose width error is ≤ 10 %
  /** Clusters whose every blade's tip stands free (tipsStandFree), and how many of them came out exact:
   * a blade whose tip is hidden, or touches a neighbour's at the same depth, leaves no trace one frame can
   * count. */
  int tipsFree = 0;
  /** Of those, clusters whose count came out exact. */
  int tipsFreeExact = 0;

  /** exact / clusters. */
  double exactShare() const { return clusters > 0 ? static_cast<double>(exact) / clusters : 0.0; }
  /** widthWithin10 / blades. */
  double widthShare() const { return blades > 0 ? static_cast<double>(widthWithin10) / blades : 0.0; }
  /** tipsFree / clusters. */
  double tipsFreeShare() const { return clusters > 0 ? static_cast<double>(tipsFree) / clusters : 0.0; }
  /** tipsFreeExact / tipsFree. */
  double tipsFreeExactShare() const {
    return tipsFree > 0 ? static_cast<double>(tipsFreeExact) / tipsFree : 0.0;
  }
};

/**
 * One line of a sweep's table (no newline), as `sylva capture synth --sweep` prints it and the sweep test
 * logs it: "occluded     45 clusters  count exact  95.6 %  (2 with blades missing)  width within 10 % on …
 * blades every tip free in 44 (exact 97.7 %)".
 */
std::string sweepLine(const char* name, const SweepTally& tally);

/** A capture sweep's result: per layout (index = the layout's place in kClusterLayouts) and over all. */
struct SweepReport {
  /** Tallies per layout, in kClusterLayouts' order. */
  std::array<SweepTally, 4> byLayout{};
  /** Tallies over every layout. */
  SweepTally all;
  /** Seeds of the clusters whose count came out wrong, in sweep order (makeSweepCluster redraws one). */
  std::vector<std::uint64_t> wrongSeeds;
};

/**
 * Captures `clusters` random clusters (makeSweepCluster with seeds firstSeed, firstSeed + 1, …) from depth
 * alone (no colour frame, the paper's setting) and tallies them against their truth; `only` sweeps one
 * layout. `progress` (optional) advances once per cluster. Deterministic.
 */
SweepReport captureSweep(int clusters, std::uint64_t firstSeed = 1, Progress* progress = nullptr,
                         std::optional<ClusterLayout> only = std::nullopt);

/**
 * What `sylva capture synth --sweep` prints: a sweepLine per layout swept and over all, then the first 12
 * seeds whose count came out wrong and how to redraw one (`only`: the layout the sweep was narrowed to).
 * Lines end in '\n'.
 */
std::string describeSweep(const SweepReport& report, std::optional<ClusterLayout> only);

} // namespace sylva::capture
