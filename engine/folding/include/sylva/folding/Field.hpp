#pragma once

#include <sylva/folding/Project.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sylva::folding {

/** An anchor: at position (pixels) the backward jump vector (pixels) is `vector`. */
struct Anchor {
  /** Where the anchor is, pixels. */
  Vec2 position{0.0};
  /** The backward jump vector there, pixels. */
  Vec2 vector{0.0};
  /** Every field equal. */
  bool operator==(const Anchor&) const = default;
};

/**
 * Interpolates anchors over a zone with one of the Shepard variants. Modified variants bucket the anchors in
 * a uniform grid of cell size R, so evaluate() visits only the anchors within R and its cost follows the
 * nearby anchors, not all of them. Immutable after construction; evaluate() is thread-safe.
 */
class AnchorField {
public:
  /** A field over `anchors` interpolated as `interp` says; `seed` drives the randomised variant. */
  AnchorField(std::vector<Anchor> anchors, const Interpolation& interp, std::uint64_t seed);

  /**
   * J at `x` (pixels); `pixelId` feeds the randomised variant's hash (use y·width + x of the texel so the
   * result does not depend on evaluation order). If x coincides with an anchor, that anchor's vector exactly.
   * Shepard: Σ w v / Σ w, w = d^−p. Modified: w = (max(0, R − d)/(R d))²; no anchor within R gives 0.
   */
  Vec2 evaluate(Vec2 x, std::uint64_t pixelId) const;
  /** The anchors, as given. */
  const std::vector<Anchor>& anchors() const { return mAnchors; }

private:
  std::vector<Anchor> mAnchors;
  Interpolation mInterp;
  std::uint64_t mSeed;
  Vec2 mOrigin{0.0};
  double mCell = 1.0; ///< grid cell size, pixels (≥ R)
  int mCellsX = 0;
  int mCellsY = 0;
  std::vector<std::uint32_t> mCellStart; ///< CSR over cells
  std::vector<std::uint32_t> mCellItems;
};

/** Deterministic hash in [0, 1) of (pixel, anchor, seed) for the randomised ring (PCG-style mixing). */
double ringHash(std::uint64_t pixelId, std::uint64_t anchorId, std::uint64_t seed);

/** Even-odd point-in-polygon test (pixels). */
bool insidePolygon(std::span<const Vec2> polygon, Vec2 p);
/** Signed area (pixels²), positive for counter-clockwise in a y-up frame. */
double signedArea(std::span<const Vec2> polygon);
/** True when two non-adjacent edges cross or touch (a simple polygon has none). */
bool selfIntersects(std::span<const Vec2> polygon);

/**
 * Mean-value coordinates (Floater 2003, Hormann–Floater 2006 for arbitrary simple polygons) of `p` with
 * respect to `polygon`: weights λ_i ≥ … with Σλ_i = 1 and Σλ_i v_i = p; exact interpolation on edges and
 * vertices.
 */
std::vector<double> meanValueCoordinates(std::span<const Vec2> polygon, Vec2 p);

/** Cubic Bézier B(u) and N parameters u_j that sample it uniformly in arc length (u_0 = 0, u_{N−1} = 1). */
Vec2 bezier(const std::array<Vec2, 4>& c, double u);
/** The N = `samples` parameters u_j that sample the curve `c` uniformly in arc length. */
std::vector<double> arcLengthParameters(const std::array<Vec2, 4>& c, int samples);

/** One fold interval (t0, t1] in progress units, 0 ≤ t0 ≤ t1 ≤ 1. */
struct Interval {
  /** Start of the interval, progress units. */
  double t0 = 0.0;
  /** End of the interval, progress units. */
  double t1 = 1.0;
  /** Every field equal. */
  bool operator==(const Interval&) const = default;
};

/**
 * Intervals of s ∈ [0, 1] where the jump path P(s) = q + s·J lies inside the union of `polygons` (even-odd
 * per polygon, then union), by exact segment–edge intersection (half-open edge parameter so a vertex counts
 * once). Sorted, disjoint, each non-empty. Pixels (q, J) in zone-image pixels.
 */
std::vector<Interval> foldIntervals(std::span<const std::vector<Vec2>> polygons, Vec2 q, Vec2 jump);

/**
 * The same from a mask image sampled at P(s) (nearest pixel, ≥ 0.5 inside, outside the image = outside),
 * marching s in steps of 1/⌈‖J‖⌉ (at least one step per pixel): the runs where the mask is set.
 * `mask` is a W×H array of values in [0, 1], row 0 at the top.
 */
std::vector<Interval> foldIntervalsFromMask(std::span<const float> mask, int width, int height, Vec2 q,
                                            Vec2 jump);

/**
 * Anchors a zone's tools produce: points, curve samples, lasso outlines, zero polylines, zero anchors on the
 * zone border and on the freeze mask's border. `freezeMask` (image-sized, may be empty), `imageSize` pixels.
 * ZoneField interpolates their residuals over the base field of translate, scale and fly-over tools.
 */
std::vector<Anchor> zoneAnchors(const Zone& zone, std::span<const float> freezeMask, glm::ivec2 imageSize);

/** The analytic base field of a zone's translate, scale and fly-over tools at x (their sum). */
Vec2 baseJump(const Zone& zone, Vec2 x);

/**
 * Everything needed to evaluate a zone's jump field J(x) (pixels, backward): base field + interpolated
 * residuals of the anchors, exact mean-value deforms inside lasso polygons, zero inside the freeze mask.
 * Thread-safe evaluation. Keeps pointers to `zone` and `freezeMask`: they must outlive the field.
 */
class ZoneField {
public:
  /** The field of `zone` on an image of `imageSize` pixels (freezeMask: one value per pixel, or empty). */
  ZoneField(const Zone& zone, std::span<const float> freezeMask, glm::ivec2 imageSize, std::uint64_t seed);
  /** J at `x` (pixels); `pixelId` as in AnchorField::evaluate. */
  Vec2 evaluate(Vec2 x, std::uint64_t pixelId) const;
  /** The anchors the zone's tools made, interpolated. */
  const AnchorField& anchors() const { return mField; }

private:
  const Zone* mZone;
  std::span<const float> mFreeze;
  glm::ivec2 mImageSize;
  AnchorField mField;
  struct Deform {
    std::vector<Vec2> polygon; ///< destination polygon
    std::vector<Vec2> vectors; ///< backward vectors at its vertices
  };
  std::vector<Deform> mDeforms;
};

} // namespace sylva::folding
