#pragma once
// Blade extraction from one depth frame (paper §4.1–4.3): depth-range mask → contour (mask tracing, or Canny
// on depth) → cluster centre → distance-from-centre signal along the contour, whose prominent local minima
// are the junctions between blades → each blade's contour → skeleton by matching symmetric contour points (or
// the medial axis when the blade is not symmetric) → width per knot → smoothing → resampling → metres.

#include <sylva/capture/Depth.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sylva::capture {

/** How the blob's outline is found. */
enum class ContourMethod {
  /** Trace the boundary of the depth-range mask (the paper's main method). */
  Mask,
  /** Canny edges on the depth values (the paper's alternative), closed and filled into regions. */
  Canny,
};

/** How a cluster's centre is chosen. */
enum class CentreMode {
  /** Core, unless it is unusable (then centroid, then base, with a warning). */
  Auto,
  /** The deepest point inside the blob (distance-transform maximum): where blades join. */
  Core,
  /** The blob's centroid (the paper's choice; right for star-shaped clusters). */
  Centroid,
  /** The lowest point of the blob (blades growing from the ground seen from the side). */
  Base,
  /** ExtractOptions::centrePx. */
  Manual,
};

/** Options of extractBlades; defaults suit a 640×480 Kinect frame of a grass tuft 0.5–1.5 m away. */
struct ExtractOptions {
  /** Depth range of the blades in metres; 0 for either means automatic (Otsu split of the valid depths). */
  float nearMetres = 0.0f;
  /** Far end of the blades' depth range, metres (0: automatic). */
  float farMetres = 0.0f;
  /** Region of interest x0, y0, x1, y1 in pixels (x1, y1 exclusive); all zero: the whole frame. */
  std::array<int, 4> roi{0, 0, 0, 0};
  /** How blobs are outlined: the depth-range mask, or Canny edges on depth. */
  ContourMethod contour = ContourMethod::Mask;
  /** Canny thresholds in depth metres per pixel step (the gradient of depth, not of grey). */
  double cannyLowMetres = 0.02;
  /** Canny's high threshold, metres of depth per pixel step. */
  double cannyHighMetres = 0.06;
  /**
   * Radius in pixels of the morphological close that fills cracks and pin holes (no opening: it would cut the
   * one-pixel tips of thin blades; speckle goes with minClusterAreaPx).
   */
  int cleanRadiusPx = 1;
  /** Holes in the mask smaller than this (pixels) are filled (sensor dropouts inside blades). */
  int fillHolesPx = 400;
  /** Blobs smaller than this (pixels) are ignored. */
  int minClusterAreaPx = 300;
  /** How each cluster's centre is chosen. */
  CentreMode centre = CentreMode::Auto;
  /** The centre with CentreMode::Manual, pixels. */
  glm::vec2 centrePx{0.0f};
  /** Gaussian smoothing of the distance signal along the contour, sigma in pixels of arc length. */
  double smoothSigmaPx = 3.0;
  /**
   * A local minimum of the distance signal is a junction when it is at least this prominent: the lower of the
   * two peaks that enclose it rises this far above it, as a fraction of the cluster's largest distance. Noise
   * makes shallow minima; blades make deep ones.
   */
  double prominence = 0.08;
  /**
   * A shallower minimum is a junction too when it is a notch between two tips: at least this prominent (a
   * fraction of the cluster's largest distance) and notchMinPx deep, with the outline turning inwards around
   * it (its chord passes outside the blob). The tips of neighbouring blades in a dense fan part only over
   * their last few centimetres. 0 turns notches off.
   */
  double notchProminence = 0.01;
  /** Least depth of a notch, and least height of the tip between two notches, pixels. */
  double notchMinPx = 3.0;
  /**
   * Notches are looked for in the distance signal smoothed by this sigma (pixels of arc length; the same as
   * smoothSigmaPx by default). Less smoothing keeps the notches of 3–4 px between tips 5–8 px apart, which
   * smoothSigmaPx flattens to under a pixel, but finds notches in the ripples of a wide leaf's edge too.
   */
  double notchSigmaPx = 3.0;
  /** A contour segment is a blade only if its tip is this far (pixels) above its higher junction... */
  double minBladeLengthPx = 15.0;
  /**
   * ...or, for a pointed tip, this fraction of it (1 turns the exception off). In a dense fan a blade's
   * neighbours overlap it up to near its end, so only a short tip shows beyond them; it is pointed when,
   * 80 % of the way down from the tip, the outline is at most 0.7 times as wide as the tip is high.
   */
  double pointedTipFraction = 0.6;
  /**
   * ...and it is at least this many times longer (from the centre) than wide (beyond its lowest tenth, as its
   * base, closed between two junctions, is wider than the blade): rejects pots, ground, the cluster's base.
   */
  double minElongation = 2.5;
  /** Knots of the captured skeleton before refining. */
  int knots = 128;
  /** Gaussian smoothing of skeleton points and widths along the blade, sigma in knots of the 128-knot line.
   */
  double skeletonSmoothKnots = 2.0;
  /**
   * Symmetric matching is trusted when the two sides of a blade differ in arc length by at most this ratio
   * and their midpoints stay inside the blade; otherwise the medial axis is used (asymmetric blades).
   */
  double symmetryRatio = 1.35;
  /**
   * ...and when matched pairs cross the skeleton squarely: their mean offset along the skeleton stays within
   * this fraction of their mean chord (0.3 ≈ 17° off perpendicular), or within 3 px of contour noise.
   */
  double maxObliqueness = 0.3;
  /** Extend each blade's skeleton straight from its lowest knot to the cluster centre (its root). */
  bool extendToCentre = true;
  /** Use a colour frame, when present, to move depth edges onto colour edges (joint bilateral). */
  bool colourRefine = true;
  /**
   * Split a blade whose outer half holds two or more surfaces that part in depth and each reach out towards
   * its tip (blades of crossing fans, or neighbours in a dense fan, merged in the outline).
   */
  bool depthSplit = true;
  /**
   * Where the middle of a blade's visible length shows one surface, the depth split looks again beyond this
   * share of its distance from the centre to its tip, measured from the tip (0 turns the second look off;
   * below 1). In a dense fan neighbours overlap up to near their tips, so only a blade's last 10–20 px show
   * beyond its junctions, too few pixels for two surfaces, while the blades part in depth over the outer
   * third of their length.
   */
  double depthSplitOuterShare = 0.35;
  /**
   * After the depth split, look for blades whose neighbours hide all but their outer end: over the
   * cluster's outer band (beyond 1 − this share of the median distance from the centre to the captured
   * tips), a depth surface whose far end is a free tip on which no captured blade ends is one blade more
   * (0 turns this off; below 1). Needs `depthSplit`.
   */
  double tipSurfacesOuterShare = 0.25;
  /**
   * Where a nearer surface hides one edge of a blade (a blade in front of it), take the blade's width there
   * from the samples on either side where both its edges show, instead of the narrower part that shows.
   */
  bool occludedWidths = true;
  /**
   * A blade found on a medial axis (its outline did not pair into two edges of its own) measures its widths
   * over its own depth surface, up to where a farther surface begins, when that is narrower along most of
   * it: blades in front of a neighbour no longer measure as wide as both.
   */
  bool surfaceWidths = true;
  /**
   * Smoothing of each blade's final widths along its seen part (after the hidden-edge and surface widths,
   * which correct knots one by one): a running median over ± this many knots of the 128-knot line, then a
   * Gaussian of 0.3 times that; 0: none. A sensor's edges jitter by a pixel or two from knot to knot; the
   * median keeps a lobe's rise and fall.
   */
  double widthSmoothKnots = 5.0;
  /**
   * Join a blade's outer part that broke off into a depth layer of its own (where a nearer blade crosses it
   * at a shallow angle) to the blade whose tip points at it.
   */
  bool joinBroken = true;
};

/** A junction between two blades: a prominent local minimum of the distance signal. */
struct Junction {
  /** Index into Cluster::contour. */
  int index = 0;
  /** The junction's position, pixels. */
  glm::vec2 px{0.0f};
  /** Smoothed distance from the centre, pixels. */
  float distancePx = 0.0f;
  /** Prominence as a fraction of the cluster's largest distance. */
  float prominence = 0.0f;
};

/** One connected blob of blades. */
struct Cluster {
  /** Closed outline, pixel coordinates (pixel centres), counter-clockwise on screen. */
  std::vector<glm::vec2> contour;
  /** The centre the distance signal is measured from, pixels. */
  glm::vec2 centre{0.0f};
  /** The mode that produced the centre (never Auto). */
  CentreMode centreMode = CentreMode::Core;
  /** Distance from the centre along the contour (pixels): raw and smoothed. */
  std::vector<float> signal;
  /** The distance signal smoothed along the contour (Gaussian, ExtractOptions::smoothSigmaPx). */
  std::vector<float> smoothed;
  /** The junctions found: prominent minima of the smoothed signal. */
  std::vector<Junction> junctions;
  /** Indices into ExtractResult::blades. */
  std::vector<int> blades;
  /** Segments between junctions that were not blades, with the reason ("too short", "not elongated"). */
  std::vector<std::string> rejected;
  /**
   * Blades that are probably two or more merged (`--explain`): much wider than the cluster's median blade,
   * with no depth step between them to split them by.
   */
  std::vector<std::string> merged;
  /**
   * Blades split between their tips because they were much wider than the cluster's narrow blades, and blades
   * split into the surfaces that part in depth towards their tips, and blades found by the depth surface
   * their free tip ends on where no captured blade ends (`--explain`).
   */
  std::vector<std::string> split;
  /**
   * Blades whose outer part broke off into this cluster (a depth layer of its own, where a nearer blade
   * crosses them) and was joined to them (`--explain`).
   */
  std::vector<std::string> joined;
  /** Pixels of the cluster. */
  int areaPx = 0;
  /**
   * The depth layer of its blob this cluster was cut from (0: the nearest), -1 when the blob is one layer.
   * A blade in front of others steps in depth all round its outline, so it is partitioned on its own layer.
   */
  int layer = -1;
  /** Depth layers of the blob (1 when it is one), and this layer's median depth, metres (0 when one). */
  int layerCount = 1;
  /** This layer's median depth, metres (0 when the blob is one layer). */
  float layerDepthMetres = 0.0f;
};

/** One captured blade. */
struct CapturedBlade {
  /** Index of the blade's cluster in ExtractResult::clusters. */
  int cluster = 0;
  /** The blade's outline from one junction over the tip to the next, pixels. */
  std::vector<glm::vec2> outline;
  /** Index of the tip within outline. */
  int tip = 0;
  /** Skeleton knots root → tip (pixels) and full widths (pixels), ExtractOptions::knots of them. */
  std::vector<glm::vec2> skeletonPx;
  /** Full width at each knot, pixels. */
  std::vector<float> widthsPx;
  /** The same knots in camera space (metres, x right, y down, z forward) and widths in metres. */
  std::vector<glm::vec3> knots;
  /** Full width at each knot, metres. */
  std::vector<float> widths;
  /** Unit width direction per knot in camera space (the blade's side). */
  std::vector<glm::vec3> sides;
  /** Length of the knot line, pixels and metres. */
  float lengthPx = 0.0f;
  /** Length of the knot line, metres. */
  float lengthMetres = 0.0f;
  /** Pixels of the skeleton that came from the extension to the centre (0 when none). */
  float extensionPx = 0.0f;
  /** True when the medial axis replaced symmetric matching. */
  bool medialAxis = false;
  /** Ratio of the longer to the shorter side's arc length (1: symmetric). */
  float sideRatio = 1.0f;
  /** Matched pairs' offset along the skeleton over their chord length (0: pairs straight across). */
  float obliqueness = 0.0f;
  /** The blade's outline touches the region of interest's border (it may be cut). */
  bool touchesBorder = false;
  /** Mean linear RGB of the blade's pixels when the frame has colour. */
  bool hasColour = false;
  /** Mean linear RGB of the blade's pixels (when hasColour). */
  glm::vec3 colour{0.0f};
};

/** Everything extractBlades found, including the intermediate stages (for overlays and docs). */
struct ExtractResult {
  /** Frame width, pixels. */
  int width = 0;
  /** Frame height, pixels. */
  int height = 0;
  /** Depth range used, metres. */
  float nearMetres = 0.0f;
  /** Far end of the depth range used, metres. */
  float farMetres = 0.0f;
  /** Foreground mask after cleaning (255 inside), width × height. */
  std::vector<std::uint8_t> mask;
  /** Canny edge map (255 on edges) when ContourMethod::Canny was used, else empty. */
  std::vector<std::uint8_t> edges;
  /** The clusters (blobs, or depth layers of blobs) found. */
  std::vector<Cluster> clusters;
  /** Every blade found, over all clusters. */
  std::vector<CapturedBlade> blades;
  /** Parts of depth layers too small to partition, each with its place and size (for `--explain`). */
  std::vector<std::string> droppedParts;
  /** Problems worth telling the user, each naming the frame (DepthFrame::label()). */
  std::vector<std::string> warnings;
  /** True when the frame's depth was refined with its colour frame. */
  bool colourRefined = false;
};

/**
 * Runs the pipeline on one frame. Never throws for content problems (an empty mask, no contour, no usable
 * centre): those come back as warnings naming the frame, with no blades. Throws sylva::Error for invalid
 * options (naming the option) or a frame with no pixels.
 */
ExtractResult extractBlades(const DepthFrame& frame, const ExtractOptions& options = {});

/**
 * The debug overlay: the depth as grey, the mask tinted, contours, the centre, junctions, each blade's
 * skeleton in its own colour with width ticks, and labels. RGB8, the frame's size (at least 640 wide: small
 * frames are scaled up by an integer factor).
 */
Image overlayImage(const DepthFrame& frame, const ExtractResult& result, const std::string& caption = {});

/** The distance signal of one cluster as a plot (RGB8, width × height): raw, smoothed and the junctions. */
Image signalPlot(const Cluster& cluster, int width, int height);

/**
 * Threads OpenCV may use inside extraction (cv::setNumThreads; process-wide); 0 restores OpenCV's default.
 * Benchmarks use 1 to measure on one core.
 */
void setExtractionThreads(int threads);

/** Rasterises blades (skeleton ± half width) into a width × height mask (255 inside); for accuracy checks. */
std::vector<std::uint8_t> rasteriseBlades(const std::vector<CapturedBlade>& blades, int width, int height);

} // namespace sylva::capture
