#include <sylva/ui/ImageCanvas.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sylva::ui {
namespace {

glm::dvec2 dv(ImVec2 v) {
  return {v.x, v.y};
}

} // namespace

ImDrawList* ImageCanvas::begin(ImTextureID texture, glm::ivec2 imageSize, bool flipV) {
  mOrigin = ImGui::GetCursorScreenPos();
  mSize = ImGui::GetContentRegionAvail();
  mImageSize = imageSize;
  if (mFitPending && mSize.x > 0 && mSize.y > 0) {
    view = render::CanvasView::fit(glm::dvec2(imageSize), dv(mSize), fitMargin);
    if (fitZoom > 0.0) {
      view.zoomAround(dv(mSize) * 0.5, fitZoom / view.zoom);
    }
    if (fitOnWholePixels) {
      view.offset = glm::round(view.offset);
    }
    mFitPending = false;
  }
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 end(mOrigin.x + mSize.x, mOrigin.y + mSize.y);
  dl->PushClipRect(mOrigin, end, true);
  dl->AddRectFilled(mOrigin, end, IM_COL32(38, 38, 42, 255));
  dl->AddImage(texture, toScreen(glm::dvec2(0.0)), toScreen(glm::dvec2(imageSize)),
               ImVec2(0.0f, flipV ? 1.0f : 0.0f), ImVec2(1.0f, flipV ? 0.0f : 1.0f));
  return dl;
}

void ImageCanvas::drawPixelGrid(ImDrawList* dl) const {
  if (!showGrid || !view.showsPixelGrid()) {
    return;
  }
  const glm::dvec2 lo = glm::max(glm::floor(view.toImage(glm::dvec2(0.0))), glm::dvec2(0.0));
  const glm::dvec2 hi = glm::min(glm::ceil(view.toImage(dv(mSize))), glm::dvec2(mImageSize));
  for (double x = lo.x; x <= hi.x; x += 1.0) {
    dl->AddLine(toScreen({x, lo.y}), toScreen({x, hi.y}), IM_COL32(0, 0, 0, 60));
  }
  for (double y = lo.y; y <= hi.y; y += 1.0) {
    dl->AddLine(toScreen({lo.x, y}), toScreen({hi.x, y}), IM_COL32(0, 0, 0, 60));
  }
}

bool ImageCanvas::input(const char* id) {
  ImGui::GetWindowDrawList()->PopClipRect();
  ImGui::SetCursorScreenPos(mOrigin);
  ImGui::InvisibleButton(id, ImVec2(std::max(mSize.x, 1.0f), std::max(mSize.y, 1.0f)),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  const bool hovered = ImGui::IsItemHovered();
  const ImGuiIO& io = ImGui::GetIO();
  if (hovered && io.MouseWheel != 0.0f) {
    view.zoomAround(dv(io.MousePos) - dv(mOrigin), std::pow(1.25, static_cast<double>(io.MouseWheel)));
  }
  if ((ImGui::IsItemActive() || hovered) && (ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0.0f) ||
                                             ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f))) {
    view.pan(dv(io.MouseDelta));
  }
  return hovered;
}

void ImageCanvas::zoomAtCentre(double factor) {
  view.zoomAround(dv(mSize) * 0.5, factor);
}

ImVec2 ImageCanvas::toScreen(glm::dvec2 image) const {
  const glm::dvec2 s = view.toScreen(image);
  return {mOrigin.x + static_cast<float>(s.x), mOrigin.y + static_cast<float>(s.y)};
}

glm::dvec2 ImageCanvas::toImage(ImVec2 screen) const {
  return view.toImage(dv(screen) - dv(mOrigin));
}

void CanvasImage::bindForDraw(glm::ivec2 size) {
  if (size != mSize) {
    mTexture = gl::Texture::create2D(GL_RGBA8, size.x, size.y);
    mTexture.setSampler(
        {GL_LINEAR, static_cast<GLenum>(mNearest ? GL_NEAREST : GL_LINEAR), GL_CLAMP_TO_EDGE});
    mFramebuffer = gl::Framebuffer();
    mFramebuffer.attachColor(0, mTexture);
    mFramebuffer.checkComplete();
    mSize = size;
  }
  mFramebuffer.bindForDraw(size.x, size.y);
}

void CanvasImage::showAt(double zoom) {
  const bool nearest = zoom >= 4.0;
  if (nearest != mNearest && mTexture.id() != 0) {
    mTexture.setSampler({GL_LINEAR, static_cast<GLenum>(nearest ? GL_NEAREST : GL_LINEAR), GL_CLAMP_TO_EDGE});
  }
  mNearest = nearest;
}

ImTextureID CanvasImage::texture() const {
  return textureId(mTexture);
}

gl::Texture imageTexture(const Image& image) {
  gl::Texture t = gl::Texture::fromImage(image.channels() == 4 ? image : image.converted(PixelType::U8));
  t.setSampler({GL_LINEAR, GL_NEAREST, GL_CLAMP_TO_EDGE});
  return t;
}

ImTextureID textureId(const gl::Texture& texture) {
  return reinterpret_cast<ImTextureID>(static_cast<std::intptr_t>(texture.id()));
}

} // namespace sylva::ui
