#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <cstddef>

#include <glm/glm.hpp>

/**
 * Screen-space error of a drawn terrain, measured per pixel against the full-resolution surface (CPU, no GL).
 *
 * Questions answered: by how many pixels does a drawn (LOD) terrain differ from the terrain drawn at full
 * resolution, at each pixel and at worst? Used by `sylva bench terrain-error` and the screen-space-error LOD
 * tests (docs/terrain-lod.md, "Screen-space error").
 *
 * Spaces: world metres, y up; positions as the terrain's WorldPosition view writes them; `viewProj` maps
 * world to clip space; pixels of a width × height viewport.
 */
namespace sylva::terrain {

/**
 * Vertical distance (metres) from world point `p` to the full-resolution surface below or above it: to the
 * interval spanned by the two diagonal triangulations of the reference cell containing (p.x, p.z), so a
 * point on either triangulation (whichever the tessellator picks) has gap 0. The reference cells are those
 * of the sample grid when `latticeSpacing` is 0, else of a square lattice of that spacing (metres) from the
 * origin with bilinear heights (heightAt) at its points: the surface the deepest quadtree patches draw, for
 * QuadtreeConfig::finestVertexSpacing. NaN when a cell corner is absent or (p.x, p.z) is outside the field.
 */
float fullResolutionGap(const HeightField& field, const glm::vec3& p, float latticeSpacing = 0.0f);

/** Per-pixel screen-space error of one frame, pixels. */
struct ScreenErrorStats {
  /** Largest error over the covered pixels. */
  double worstPx = 0.0;
  /** 99.9th percentile over the covered pixels. */
  double p999Px = 0.0;
  /** Mean over the covered pixels. */
  double meanPx = 0.0;
  /** Pixels holding a terrain position (alpha > 0) with a defined gap. */
  std::size_t pixels = 0;
};

/**
 * Screen-space error of a frame from its world positions (`positions`: RGBA float, xyz = world position,
 * alpha > 0 where terrain was drawn; width × height of the viewport): at each covered pixel, the length in
 * pixels of the projection through `viewProj` of the vertical segment from the drawn point to the
 * full-resolution surface (fullResolutionGap with `latticeSpacing`). Throws sylva::Error for an image that is
 * not 4-channel float.
 */
ScreenErrorStats measureScreenError(const HeightField& field, const Image& positions,
                                    const glm::mat4& viewProj, float latticeSpacing = 0.0f);

} // namespace sylva::terrain
