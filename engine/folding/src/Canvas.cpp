// The editor canvas's snapping.
#include <sylva/folding/Canvas.hpp>

#include <glm/geometric.hpp>

#include <cmath>

namespace sylva::folding {

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
