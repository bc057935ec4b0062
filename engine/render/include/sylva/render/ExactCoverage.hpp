#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace sylva::render {

/**
 * A triangle as the rasteriser receives it: the clip-space positions written by the last vertex-processing
 * stage (e.g. captured by transform feedback), plus a tag chosen by the caller (e.g. surface or skirt).
 */
struct ClipTriangle {
  std::array<glm::vec4, 3> clip{}; ///< clip-space positions (x, y, z, w) of the three vertices
  int tag = 0;                     ///< the caller's label (e.g. 0 surface, 1 skirt)
};

/** One triangle whose exact coverage contains a sample (see exactCoverage). */
struct ExactHit {
  std::size_t triangle = 0;  ///< index into the triangle list
  int tag = 0;               ///< the triangle's tag
  double depth = 0.0;        ///< window depth at the sample, 0 (near plane) .. 1 (far plane)
  double edgeDistance = 0.0; ///< pixels from the sample to the nearest edge of the clipped triangle
};

/**
 * Which triangles contain each sample, computed in double precision from the unsnapped clip-space vertices:
 * the coverage a rasteriser with infinite sub-pixel precision would produce. Triangles are clipped to the
 * view volume (0 < w, −w ≤ z ≤ w) and mapped to the window with viewport (0, 0, `viewport`) and depth range
 * 0..1. `samples` are window positions in pixels, origin at the bottom left as in GL (pixel (i, j) has its
 * centre at (i + 0.5, j + 0.5)). A sample on an edge counts as inside (edgeDistance 0); triangles with no
 * area on screen cover nothing. Result[k] lists the hits of samples[k], nearest first.
 *
 * Rasterisers snap vertices to a sub-pixel grid (GL_SUBPIXEL_BITS), which can move an edge by up to
 * 2^−bits pixels: a hit with edgeDistance below that may or may not be drawn, one above it must be. This is
 * the reference that tells a real hole in a mesh from a snapping effect at a silhouette.
 */
std::vector<std::vector<ExactHit>> exactCoverage(std::span<const ClipTriangle> triangles, glm::ivec2 viewport,
                                                 std::span<const glm::dvec2> samples);

} // namespace sylva::render
