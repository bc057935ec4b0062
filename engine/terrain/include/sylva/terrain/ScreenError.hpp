#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <cstddef>

#include <glm/glm.hpp>

/**
 * Screen-space error of a drawn terrain, measured per pixel against the full-resolution surface (CPU, no GL).
 *
 * Questions answered: by how many pixels does a drawn (LOD) terrain differ from the terrain drawn at full
 * resolution, at each pixel and at worst? (And, for the CPU bound's model, how far is a point from the
 * full-resolution triangles?) Used by `sylva bench terrain-error` and the screen-space-error LOD
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
  /** Pixels measured (terrain in both images). */
  std::size_t pixels = 0;
  /** Pixels with terrain in exactly one of the two images (not measured). */
  std::size_t coverageMismatch = 0;
};

/**
 * Screen-space error of a frame against a reference render of the same view, from their world positions
 * (RGBA float images of the viewport, xyz = world position, alpha > 0 where terrain was drawn; usually the
 * same view drawn with every patch at the deepest level, whose vertices lie on the lattice of spacing
 * `latticeSpacing`, metres). At each pixel covered in both: R is the reference point nearest the drawn point
 * P in xz among the reference pixels within 3 pixels (the one on P's own view ray unless a silhouette moved);
 * the vertical offset of P from the reference surface's tangent plane at R (its slope from `field`'s bilinear
 * heights), or, when R is more than two lattice spacings from P in xz (the reference surface there is hidden
 * in the reference view), from the reference lattice triangulated either way (fullResolutionGap), is
 * projected through `viewProj` at P; its length in pixels is the pixel's error. Identical renders give 0
 * everywhere. Pixels covered in only one of the two (silhouettes, borders) are counted in
 * `coverageMismatch` and not measured. Throws sylva::Error for images that are not 4-channel float or differ
 * in size, or a non-positive spacing.
 */
ScreenErrorStats measureScreenError(const HeightField& field, const Image& positions, const Image& reference,
                                    const glm::mat4& viewProj, float latticeSpacing);

} // namespace sylva::terrain
