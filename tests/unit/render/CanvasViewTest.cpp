// render::CanvasView: the image canvases' view transform (fold viewer, fold editor).
#include <sylva/render/CanvasView.hpp>

#include <gtest/gtest.h>

namespace sylva::render {
namespace {

TEST(CanvasView, ZoomsAroundTheCursorWithinItsLimits) {
  CanvasView v = CanvasView::fit({400.0, 300.0}, {800.0, 632.0});
  EXPECT_DOUBLE_EQ(v.zoom, 1.92); // min((800 − 32) / 400, (632 − 32) / 300)
  const glm::dvec2 cursor(321.0, 123.0);
  const glm::dvec2 under = v.toImage(cursor);
  v.zoomAround(cursor, 3.0);
  EXPECT_NEAR(glm::distance(v.toImage(cursor), under), 0.0, 1e-9);
  for (int i = 0; i < 40; ++i) {
    v.zoomAround(cursor, 2.0);
  }
  EXPECT_DOUBLE_EQ(v.zoom, CanvasView::kMaxZoom);
  EXPECT_TRUE(v.showsPixelGrid());
  for (int i = 0; i < 80; ++i) {
    v.zoomAround(cursor, 0.5);
  }
  EXPECT_DOUBLE_EQ(v.zoom, CanvasView::kMinZoom);
  EXPECT_NEAR(glm::distance(v.toImage(cursor), under), 0.0, 1e-9);
  v.pan({10.0, -4.0});
  EXPECT_NEAR(glm::distance(v.toImage(cursor + glm::dvec2(10.0, -4.0)), under), 0.0, 1e-9);
}

TEST(CanvasView, FitCentresTheWholeImageAndMapsBothWays) {
  const CanvasView v = CanvasView::fit({100.0, 50.0}, {300.0, 300.0}, 0.0);
  EXPECT_DOUBLE_EQ(v.zoom, 3.0);
  EXPECT_EQ(v.toScreen({0.0, 0.0}), glm::dvec2(0.0, 75.0));
  EXPECT_EQ(v.toScreen({100.0, 50.0}), glm::dvec2(300.0, 225.0));
  EXPECT_EQ(v.toImage(v.toScreen({37.5, 12.25})), glm::dvec2(37.5, 12.25));
  EXPECT_FALSE(v.showsPixelGrid());
}

} // namespace
} // namespace sylva::render
