#include <sylva/terrain/gpu/TerrainError.hpp>

#include <sylva/gl/State.hpp>

namespace sylva::terrain {

PositionTarget::PositionTarget(int width, int height)
    : mWidth(width), mHeight(height), mPosition(gl::Texture::create2D(GL_RGBA32F, width, height)),
      mDepth(gl::Texture::create2D(GL_DEPTH_COMPONENT32F, width, height)) {
  mFramebuffer.attachColor(0, mPosition);
  mFramebuffer.attachDepth(mDepth);
  mFramebuffer.checkComplete();
}

Image PositionTarget::draw(TerrainRenderer& renderer, const QuadtreeSelection& selection,
                           const render::Camera& camera, TerrainDrawOptions options) {
  mFramebuffer.bindForDraw(mWidth, mHeight);
  mFramebuffer.clearColor(0, glm::vec4(0.0f));
  mFramebuffer.clearDepth();
  glEnable(GL_DEPTH_TEST);
  options.view = TerrainView::WorldPosition;
  options.skirts = false;
  options.vertexPoints = false;
  options.waterLevel.reset();
  renderer.draw(selection, camera, mWidth, mHeight, 0.0, nullptr, options);
  return mPosition.download(4, PixelType::F32);
}

ScreenErrorStats PositionTarget::measure(TerrainRenderer& renderer, const HeightField& field,
                                         const QuadtreeSelection& selection, const Image& reference,
                                         const render::Camera& camera, const TerrainDrawOptions& options) {
  const Image positions = draw(renderer, selection, camera, options);
  return measureScreenError(field, positions, reference, camera.viewProjection(aspect()),
                            selection.config.finestVertexSpacing());
}

} // namespace sylva::terrain
