#pragma once
// Phong tessellation adapted to quads (Boubekeur & Alexa 2008, bilinear weights; docs/trees.md): the CPU twin
// of shaders/trees/piece.tese, for tests and for checking that pieces do not fold at high levels.

#include <sylva/trees/Piece.hpp>

#include <array>

namespace sylva::trees {

/** Shape factor α of Phong tessellation (3/4 as in the paper). */
constexpr float kPhongAlpha = 0.75f;

/**
 * The Phong-tessellated point at (u, v) ∈ [0, 1]² of the quad with corners p (at (0,0), (1,0), (1,1), (0,1))
 * and unit normals n: p* = (1 − α)·p + α·Σ wᵢ πᵢ(p), p = Σ wᵢ pᵢ, πᵢ(q) = q − ((q − pᵢ)·nᵢ) nᵢ.
 */
glm::vec3 phongQuad(const std::array<glm::vec3, 4>& p, const std::array<glm::vec3, 4>& n, float u, float v);

/** The interpolated unit normal at (u, v): normalize(Σ wᵢ nᵢ). */
glm::vec3 phongQuadNormal(const std::array<glm::vec3, 4>& n, float u, float v);

/**
 * Folds of a piece at tessellation `level`: the number of triangles of a uniform level × level grid on every
 * quad whose geometric normal points against the interpolated normal (a fold would let the inside show).
 */
int countFolds(const Piece& piece, int level);

} // namespace sylva::trees
