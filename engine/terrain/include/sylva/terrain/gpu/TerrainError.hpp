#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/ScreenError.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>

/**
 * Screen-space error of a drawn terrain (GPU side): draws a selection's world positions into a float target
 * and measures them against the full-resolution surface (measureScreenError). For the screen-space-error LOD
 * tests and `sylva bench terrain-error`; see docs/terrain-lod.md, "Screen-space error".
 */
namespace sylva::terrain {

/** An offscreen RGBA32F + depth target for the terrain's WorldPosition view. Needs a current GL context. */
class PositionTarget {
public:
  /** A target of `width` × `height` pixels. */
  PositionTarget(int width, int height);

  /** Width, pixels. */
  int width() const { return mWidth; }
  /** Height, pixels. */
  int height() const { return mHeight; }
  /** Width / height. */
  float aspect() const { return static_cast<float>(mWidth) / static_cast<float>(mHeight); }

  /**
   * Draws `selection` seen by `camera` with `options` (view forced to WorldPosition, no skirts, no water) and
   * returns the positions: RGBA float, xyz world metres, alpha 1 where terrain was drawn, 0 elsewhere.
   */
  Image draw(TerrainRenderer& renderer, const QuadtreeSelection& selection, const render::Camera& camera,
             TerrainDrawOptions options = {});

  /**
   * draw() followed by measureScreenError against `reference` (positions of the same view, e.g. draw() of a
   * selection made with QuadtreeConfig::fullDepth()); `field` is the heights the renderer was built from.
   */
  ScreenErrorStats measure(TerrainRenderer& renderer, const HeightField& field,
                           const QuadtreeSelection& selection, const Image& reference,
                           const render::Camera& camera, const TerrainDrawOptions& options = {});

private:
  int mWidth;
  int mHeight;
  gl::Texture mPosition;
  gl::Texture mDepth;
  gl::Framebuffer mFramebuffer;
};

} // namespace sylva::terrain
