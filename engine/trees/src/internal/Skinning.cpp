#include "internal/Skinning.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::trees::internal {

void blendInteriorWeights(Piece& piece) {
  const auto& rims = piece.rims;
  for (PieceVertex& v : piece.vertices) {
    if (v.rim >= 0) {
      continue;
    }
    if (rims.size() == 1) {
      v.joints = {0, 0, 0, 0};
      v.weights = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
      continue;
    }
    // Per leaf rim r: the parameter t along root → leaf (projection onto the segment between the rim centres)
    // and the distance d to that segment. The leaf's weight is smoothstep(t) times its share of the affinity
    // 1/d⁴, so a vertex on one child follows that child, and the crotch between children (equally near
    // both) follows all of them a little and mostly the root: bending one child never drags the crotch into
    // its sibling.
    const std::size_t leaves = std::min<std::size_t>(rims.size() - 1, 3);
    float t[3] = {0, 0, 0};
    float affinity[3] = {0, 0, 0};
    float total = 0.0f;
    for (std::size_t r = 1; r <= leaves; ++r) {
      const glm::vec3 b(rims[r].frame[3]);
      const float tr = std::clamp(glm::dot(v.position, b) / glm::dot(b, b), 0.0f, 1.0f);
      const float d = glm::length(v.position - b * tr);
      t[r - 1] = tr;
      affinity[r - 1] = 1.0f / std::pow(d + 0.05f, 4.0f);
      total += affinity[r - 1];
    }
    v.joints = {0, 0, 0, 0};
    v.weights = glm::vec4(0.0f);
    float leafSum = 0.0f;
    for (std::size_t r = 1; r <= leaves; ++r) {
      const float s = t[r - 1] * t[r - 1] * (3.0f - 2.0f * t[r - 1]);
      const float w = s * affinity[r - 1] / total;
      v.joints[r] = static_cast<std::uint8_t>(r);
      v.weights[static_cast<int>(r)] = w;
      leafSum += w;
    }
    v.weights.x = 1.0f - leafSum;
  }
}

} // namespace sylva::trees::internal
