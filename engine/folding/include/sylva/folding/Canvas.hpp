#pragma once

// The editor canvas's view transform and snapping: pure math, so zoom, pan and snapping are unit-tested
// without a window.

#include <sylva/folding/Project.hpp>

#include <span>

namespace sylva::folding {

/**
 * Maps image pixels (Project.hpp coordinates) to screen pixels (x right, y down, origin at the top-left of
 * the canvas widget): screen = offset + zoom · image. Zoom is clamped to [kMinZoom, kMaxZoom].
 */
struct CanvasView {
  static constexpr double kMinZoom = 1.0 / 8.0;
  static constexpr double kMaxZoom = 32.0;
  double zoom = 1.0; ///< screen pixels per image pixel
  Vec2 offset{0.0};  ///< screen position of image point (0, 0)

  Vec2 toScreen(Vec2 image) const { return offset + zoom * image; }
  Vec2 toImage(Vec2 screen) const { return (screen - offset) / zoom; }
  /** Multiplies the zoom by `factor` (clamped) keeping the image point under `screenPoint` fixed. */
  void zoomAround(Vec2 screenPoint, double factor);
  /** Moves the image by `screenDelta` screen pixels. */
  void pan(Vec2 screenDelta) { offset += screenDelta; }
  /** Zoom and offset that show all of an image of `imageSize` centred in `viewSize`, with a margin. */
  static CanvasView fit(glm::dvec2 imageSize, glm::dvec2 viewSize, double marginPx = 16.0);
  /** True when the pixel grid should be drawn (each pixel at least this many screen pixels wide). */
  bool showsPixelGrid(double minPixelPx = 8.0) const { return zoom >= minPixelPx; }
};

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
