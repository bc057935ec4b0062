#pragma once
// Phong tessellation adapted to quads (Boubekeur & Alexa 2008, bilinear weights; docs/trees.md): the CPU twin
// of shaders/trees/piece.tese, for tests and for checking that pieces do not fold at high levels.

#include <sylva/trees/Piece.hpp>

#include <array>
#include <cstdint>

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

/** Most quads one indirect draw command of TreeRenderer draws. */
constexpr std::uint32_t kMaxQuadsPerCommand = 15;
/**
 * Tessellated vertices one command may make: what kMaxQuadsPerCommand quads make at the default largest level
 * 16 (fractional odd spacing: 17 segments, 18 × 18 vertices a quad).
 */
constexpr std::uint32_t kVerticesPerCommand = kMaxQuadsPerCommand * 18 * 18;

/**
 * Tessellated vertices of one quad at `level` (fractional odd spacing: the level rounds up to an odd segment
 * count, at most 63): (segments + 1)². Levels below 1 (and NaN) count as 1.
 */
std::uint32_t quadVertices(float level);

/**
 * Quads per indirect draw command when no edge's level exceeds `maxLevel`: as many as keep a command within
 * kVerticesPerCommand tessellated vertices, 1 … kMaxQuadsPerCommand (docs/trees.md, "Quads in chunks").
 * Mesa's draw module (llvmpipe) numbers one command instance's tessellated vertices with 16 bits, and a
 * command that goes through its primitive pipeline (clipping, for one) costs it the square of that count; a
 * GPU does not care. 15 at levels up to 16, 4 at 32, 1 at 64.
 */
std::uint32_t quadsPerCommand(float maxLevel);

} // namespace sylva::trees
