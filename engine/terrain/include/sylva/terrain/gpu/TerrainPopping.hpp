#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>

namespace sylva::terrain {

/**
 * Fraction of pixels (0..1) whose colour differs by more than `threshold` (0..1) in any of the first three
 * channels between `a` and `b` (same size; the grass popping measure, docs/grass.md "Popping").
 */
double changedPixelFraction(const Image& a, const Image& b, float threshold = 0.05f);

/**
 * Leaves (depth, grid index) in exactly one of `a` and `b`: 0 when no patch changed level between the two
 * selections (compare selections made without frustum culling, or the frustum's edge counts too).
 */
int changedLeaves(const QuadtreeSelection& a, const QuadtreeSelection& b);

/** Popping figures of one camera step (TerrainRenderer frames, fractions of pixels changed by > 5 %). */
struct CameraStepChange {
  /** The step as drawn: the selection (and morph) re-made for the second camera. */
  double across = 0.0;
  /**
   * The same step with the first camera's selection (and morph) kept: no patch changes level, so this is
   * what the step costs inside one LOD band (parallax alone).
   */
  double inside = 0.0;
  /** changedLeaves of the two cameras' selections without frustum culling (patches that changed level). */
  int leavesChanged = 0;
};

/**
 * Renders `from`, then `to`, both with `quadtree`'s selection for each camera (frustum-culled at the target's
 * aspect), and `to` once more with the selection of `from`, into `target` (cleared to `clear`), and compares
 * them (changedPixelFraction at 5 %). `options` as for TerrainRenderer::draw (e.g. geomorph on or off).
 */
CameraStepChange measureCameraStep(TerrainRenderer& renderer, Quadtree& quadtree,
                                   render::RenderTarget& target, const render::Camera& from,
                                   const render::Camera& to, const TerrainDrawOptions& options,
                                   const glm::vec4& clear);

} // namespace sylva::terrain
