#include <sylva/render/CanvasView.hpp>

#include <algorithm>

namespace sylva::render {

void CanvasView::zoomAround(glm::dvec2 screenPoint, double factor) {
  const glm::dvec2 anchor = toImage(screenPoint);
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

} // namespace sylva::render
