#pragma once
// The ui module's image canvas (docs/engine.md): an image in an ImGui window, zoomed and panned through a
// render::CanvasView, shared by the fold viewer and the fold editor.

#include <sylva/core/Image.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/render/CanvasView.hpp>

#include <glm/glm.hpp>
#include <imgui.h>

namespace sylva::ui {

/**
 * An image filling the rest of the current ImGui window: the wheel zooms around the cursor, a right or middle
 * drag pans, requestFit() (Home) shows it whole, and a pixel grid appears at high zoom. Screen coordinates
 * are ImGui's (pixels, y down); image coordinates are the image's pixels (y down, origin at its top-left
 * corner).
 */
class ImageCanvas {
public:
  /** Shows the whole image at the next begin() (then at `fitZoom` around its centre when that is > 0). */
  void requestFit() { mFitPending = true; }

  /**
   * Lays the canvas over the window's remaining region (fitting it first when asked), fills it with a dark
   * background and draws `texture` (`imageSize` pixels; `flipV`: its first row is the image's last, as GL
   * draws) at the view. Returns the window's draw list clipped to the canvas, for overlays; call input()
   * after them.
   */
  ImDrawList* begin(ImTextureID texture, glm::ivec2 imageSize, bool flipV = false);
  /** Lines between pixels where each pixel is at least 8 screen pixels wide (with showGrid). */
  void drawPixelGrid(ImDrawList* drawList) const;
  /**
   * Ends the drawing (pops the clip) and covers the canvas with an invisible button `id` (left, right and
   * middle buttons), which is then ImGui's last item; zooms and pans by the mouse over it. Returns whether
   * the mouse is over the canvas.
   */
  bool input(const char* id = "canvas");

  /** Zooms by `factor` around the canvas's centre (keyboard zoom). */
  void zoomAtCentre(double factor);
  /** One image pixel per screen pixel, around the canvas's centre. */
  void actualSize() { zoomAtCentre(1.0 / view.zoom); }

  /** Screen position of image pixel coordinates `image` (as of the last begin()). */
  ImVec2 toScreen(glm::dvec2 image) const;
  /** Image pixel coordinates under screen position `screen`. */
  glm::dvec2 toImage(ImVec2 screen) const;
  /** Top-left corner and size of the canvas, screen pixels (as of the last begin()). */
  ImVec2 origin() const { return mOrigin; }
  /** Size of the canvas, screen pixels (as of the last begin()). */
  ImVec2 size() const { return mSize; }

  /** Zoom and pan: which image point is where on the canvas. */
  render::CanvasView view;
  double fitZoom = 0.0;    ///< > 0: the zoom a fit ends at (centred), instead of the whole image
  double fitMargin = 16.0; ///< screen pixels around a fitted image
  bool showGrid =
      true; ///< draw the pixel grid where image pixels are large enough (CanvasView::showsPixelGrid)
  /** A fit puts the image's corner on a whole screen pixel, so integer zooms show every texel exactly. */
  bool fitOnWholePixels = false;

private:
  ImVec2 mOrigin{0, 0};
  ImVec2 mSize{0, 0};
  glm::ivec2 mImageSize{0};
  bool mFitPending = true;
};

/** The ImGui handle of a GL texture (what ImGui::Image and ImDrawList::AddImage take). */
ImTextureID textureId(const gl::Texture& texture);

/** `image` as a texture for an ImageCanvas or ImGui::Image: RGBA8 when it is not 4-channel, texels kept sharp
 * when magnified. */
gl::Texture imageTexture(const Image& image);

/**
 * An offscreen RGBA8 image that GL draws into and an ImageCanvas (or ImGui::Image) shows: the fold viewer's
 * frame, the fold editor's preview. Shown at a zoom of 4 or more, its texels stay sharp squares (nearest
 * magnification) so single pixels can be inspected; below, it is filtered linearly.
 */
class CanvasImage {
public:
  /** Binds the image for drawing at `size` pixels (re-created when the size changes) and sets the viewport.
   */
  void bindForDraw(glm::ivec2 size);
  /** Chooses the magnification for showing at `zoom` screen pixels per texel. */
  void showAt(double zoom);
  /** The image as an ImGui texture, for ImGui::Image. */
  ImTextureID texture() const;
  /** The image's size, pixels (as of the last bindForDraw()). */
  glm::ivec2 size() const { return mSize; }

private:
  gl::Texture mTexture{gl::NoCreate};
  gl::Framebuffer mFramebuffer{gl::NoCreate};
  glm::ivec2 mSize{0};
  bool mNearest = false;
};

} // namespace sylva::ui
