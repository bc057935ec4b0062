// The editor canvas's view transform and snapping.
#include <sylva/folding/Canvas.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::folding {

void CanvasView::zoomAround(Vec2 screenPoint, double factor) {
  const Vec2 anchor = toImage(screenPoint);
  zoom = std::clamp(zoom * factor, kMinZoom, kMaxZoom);
  offset = screenPoint - zoom * anchor;
}

CanvasView CanvasView::fit(glm::dvec2 imageSize, glm::dvec2 viewSize, double marginPx) {
  CanvasView v;
  const glm::dvec2 room = glm::max(viewSize - 2.0 * marginPx, glm::dvec2(1.0));
  v.zoom = std::clamp(std::min(room.x / std::max(imageSize.x, 1.0), room.y / std::max(imageSize.y, 1.0)),
                      kMinZoom, kMaxZoom);
  v.offset = (viewSize - v.zoom * imageSize) * 0.5;
  return v;
}

Vec2 snapPoint(Vec2 p, const CanvasView& view, std::span<const Vec2> candidates, const SnapOptions& options) {
  const double radius = options.radiusPx / view.zoom; // image pixels
  if (options.points) {
    const Vec2* best = nullptr;
    double bestDistance = radius;
    for (const Vec2& c : candidates) {
      const double d = glm::distance(c, p);
      if (d <= bestDistance) {
        bestDistance = d;
        best = &c;
      }
    }
    if (best) {
      return *best;
    }
  }
  if (options.pixelCentres) {
    const Vec2 centre = glm::floor(p) + 0.5;
    if (glm::distance(centre, p) <= radius) {
      return centre;
    }
  }
  return p;
}

} // namespace sylva::folding
