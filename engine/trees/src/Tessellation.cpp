#include <sylva/trees/Tessellation.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::trees {
namespace {

std::array<float, 4> weights(float u, float v) {
  return {(1.0f - u) * (1.0f - v), u * (1.0f - v), u * v, (1.0f - u) * v};
}

} // namespace

glm::vec3 phongQuad(const std::array<glm::vec3, 4>& p, const std::array<glm::vec3, 4>& n, float u, float v) {
  const std::array<float, 4> w = weights(u, v);
  glm::vec3 q(0.0f);
  for (std::size_t i = 0; i < 4; ++i) {
    q += w[i] * p[i];
  }
  glm::vec3 phong(0.0f);
  for (std::size_t i = 0; i < 4; ++i) {
    phong += w[i] * (q - glm::dot(q - p[i], n[i]) * n[i]);
  }
  return (1.0f - kPhongAlpha) * q + kPhongAlpha * phong;
}

glm::vec3 phongQuadNormal(const std::array<glm::vec3, 4>& n, float u, float v) {
  const std::array<float, 4> w = weights(u, v);
  return glm::normalize(w[0] * n[0] + w[1] * n[1] + w[2] * n[2] + w[3] * n[3]);
}

int countFolds(const Piece& piece, int level) {
  int folds = 0;
  const float step = 1.0f / static_cast<float>(level);
  for (const auto& q : piece.quads) {
    std::array<glm::vec3, 4> p{};
    std::array<glm::vec3, 4> n{};
    for (std::size_t i = 0; i < 4; ++i) {
      p[i] = piece.vertices[q[i]].position;
      n[i] = piece.vertices[q[i]].normal;
    }
    for (int j = 0; j < level; ++j) {
      for (int i = 0; i < level; ++i) {
        const float u0 = static_cast<float>(i) * step;
        const float v0 = static_cast<float>(j) * step;
        const glm::vec3 a = phongQuad(p, n, u0, v0);
        const glm::vec3 b = phongQuad(p, n, u0 + step, v0);
        const glm::vec3 c = phongQuad(p, n, u0 + step, v0 + step);
        const glm::vec3 d = phongQuad(p, n, u0, v0 + step);
        const glm::vec3 mid = phongQuadNormal(n, u0 + 0.5f * step, v0 + 0.5f * step);
        if (glm::dot(glm::cross(b - a, c - a), mid) <= 0.0f ||
            glm::dot(glm::cross(c - a, d - a), mid) <= 0.0f) {
          ++folds;
        }
      }
    }
  }
  return folds;
}

std::uint32_t quadVertices(float level) {
  const float clamped = level >= 1.0f ? std::min(level, 63.0f) : 1.0f;
  auto segments = static_cast<std::uint32_t>(std::ceil(clamped));
  segments += segments % 2 == 0 ? 1 : 0;
  return (segments + 1) * (segments + 1);
}

std::uint32_t quadsPerCommand(float maxLevel) {
  return std::clamp<std::uint32_t>(kVerticesPerCommand / quadVertices(maxLevel), 1, kMaxQuadsPerCommand);
}

} // namespace sylva::trees
