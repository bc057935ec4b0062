#pragma once
// The 2D view of an image on screen (the image canvases of the fold viewer and the fold editor): zoom and
// offset, pure math, so zoom, pan and fitting are unit-tested without a window.

#include <glm/glm.hpp>

namespace sylva::render {

/**
 * Maps image pixels (x right, y down, origin at the image's top-left corner) to screen pixels (x right, y
 * down, origin at the top-left of the canvas): screen = offset + zoom · image. Zoom is clamped to [kMinZoom,
 * kMaxZoom].
 */
struct CanvasView {
  static constexpr double kMinZoom = 1.0 / 8.0; ///< smallest zoom, screen pixels per image pixel
  static constexpr double kMaxZoom = 32.0;      ///< largest zoom
  double zoom = 1.0;                            ///< screen pixels per image pixel
  glm::dvec2 offset{0.0};                       ///< screen position of image point (0, 0)

  /** Screen position of image point `image`. */
  glm::dvec2 toScreen(glm::dvec2 image) const { return offset + zoom * image; }
  /** Image point under screen position `screen`. */
  glm::dvec2 toImage(glm::dvec2 screen) const { return (screen - offset) / zoom; }
  /** Multiplies the zoom by `factor` (clamped) keeping the image point under `screenPoint` fixed. */
  void zoomAround(glm::dvec2 screenPoint, double factor);
  /** Moves the image by `screenDelta` screen pixels. */
  void pan(glm::dvec2 screenDelta) { offset += screenDelta; }
  /** Zoom and offset that show all of an image of `imageSize` centred in `viewSize`, with a margin. */
  static CanvasView fit(glm::dvec2 imageSize, glm::dvec2 viewSize, double marginPx = 16.0);
  /** True when the pixel grid should be drawn (each pixel at least this many screen pixels wide). */
  bool showsPixelGrid(double minPixelPx = 8.0) const { return zoom >= minPixelPx; }
};

} // namespace sylva::render
