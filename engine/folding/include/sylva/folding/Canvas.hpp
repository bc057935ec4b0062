#pragma once

// The editor canvas's snapping (its view transform is render::CanvasView): pure math, so snapping is
// unit-tested without a window.

#include <sylva/folding/Project.hpp>
#include <sylva/render/CanvasView.hpp>

#include <span>

namespace sylva::folding {

/** The canvas's view transform (render::CanvasView, shared with the fold viewer's canvas). */
using render::CanvasView;

/** What snapping may pull a point to. */
struct SnapOptions {
  bool pixelCentres = true; ///< (i + ½, j + ½)
  bool points = true;       ///< the candidate points (anchors, curve points, zone vertices)
  double radiusPx = 8.0;    ///< screen pixels: farther targets do not attract
};

/**
 * Snaps image point `p` (seen at `view`) to the nearest candidate point within the radius, else to the
 * nearest pixel centre when that is within the radius, else returns it unchanged. Candidates win over pixel
 * centres so anchors can be stacked exactly.
 */
Vec2 snapPoint(Vec2 p, const CanvasView& view, std::span<const Vec2> candidates, const SnapOptions& options);

} // namespace sylva::folding
