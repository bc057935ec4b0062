#include <sylva/trees/Skeleton.hpp>

#include <sylva/core/Random.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace sylva::trees {

glm::mat4 bendRotation(glm::vec2 theta) {
  const float angle = std::sqrt(theta.x * theta.x + theta.y * theta.y);
  if (angle <= 0.0f) {
    return glm::mat4(1.0f);
  }
  return glm::rotate(glm::mat4(1.0f), angle, glm::vec3(theta.x / angle, 0.0f, theta.y / angle));
}

void jointFrames(const PieceSet& pieces, const TreeTopology& tree, const glm::mat4& base,
                 std::span<const glm::vec2> bends, std::vector<glm::mat4>& frames) {
  frames.resize(tree.jointCount());
  frames[0] = base;
  for (const TreeNode& node : tree.nodes) {
    const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
    const glm::mat4 root = frames[node.rootJoint] * rimRotation(node.rotation);
    for (std::size_t r = 1; r < piece.rims.size(); ++r) {
      const std::uint32_t j = node.jointBase + static_cast<std::uint32_t>(r) - 1;
      glm::mat4 f = root * leafBind(piece, node, r);
      if (j < bends.size()) {
        f = f * bendRotation(bends[j]);
      }
      const float s = tree.jointScale[j];
      frames[j] = s == 1.0f ? f : f * glm::scale(glm::mat4(1.0f), glm::vec3(s));
    }
  }
}

std::vector<glm::vec2> randomPose(const TreeTopology& tree, const Species& species, std::uint64_t seed) {
  std::vector<glm::vec2> bends(tree.jointCount(), glm::vec2(0.0f));
  static const PieceSet pieces = standardPieces();
  const bool standard = [&] {
    for (const TreeNode& n : tree.nodes) {
      if (n.piece < 0 || n.piece >= static_cast<int>(pieces.size())) {
        return false;
      }
    }
    return tree.jointScale.size() == tree.jointCount();
  }();
  // Droop needs each bone's direction as posed so far: frames are built parents first, so a twig feels the
  // droop of the branch it hangs from, and the droop fades as a bone comes to hang straight down.
  std::vector<glm::mat4> posed(standard ? tree.jointCount() : 0, glm::mat4(1.0f));
  auto randomBend = [&](std::size_t j) {
    const OrderParams& o = species.order(tree.jointOrder[j]);
    const std::uint64_t h = hash64(tree.seed * 0x9E3779B97F4A7C15ULL ^ hash64(seed) ^ j);
    const float a = static_cast<float>(h & 0xffffffu) / 16777216.0f;
    const float r = static_cast<float>((h >> 24) & 0xffffffu) / 16777216.0f;
    const float angle = 2.0f * std::numbers::pi_v<float> * a;
    return glm::vec2(std::cos(angle), std::sin(angle)) * (o.bend * std::sqrt(r));
  };
  if (!standard) {
    for (std::size_t j = 1; j < bends.size(); ++j) {
      bends[j] = randomBend(j);
    }
    return bends;
  }
  for (const TreeNode& node : tree.nodes) {
    const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
    const glm::mat4 root = posed[node.rootJoint] * rimRotation(node.rotation);
    for (std::size_t r = 1; r < piece.rims.size(); ++r) {
      const std::size_t j = node.jointBase + r - 1;
      const OrderParams& o = species.order(tree.jointOrder[j]);
      const glm::mat4 before = root * leafBind(piece, node, r);
      bends[j] = randomBend(j);
      if (o.droop != 0.0f) {
        const glm::mat3 m(before);
        const glm::vec3 up = glm::normalize(m[1]);
        const glm::vec3 axis = glm::cross(up, glm::vec3(0.0f, -1.0f, 0.0f));
        const float tilt = glm::length(axis); // sin of the bone's angle from vertical
        if (tilt > 1e-3f) {
          // The world axis in the joint's local frame (columns orthogonal, equal lengths).
          const glm::vec3 local = glm::transpose(m) * (axis / tilt) / glm::dot(m[0], m[0]);
          const glm::vec2 dir = glm::normalize(glm::vec2(local.x, local.z) + glm::vec2(1e-9f, 0.0f));
          bends[j] += dir * (o.droop * tilt);
        }
      }
      const float s = tree.jointScale[j];
      posed[j] = before * bendRotation(bends[j]) * glm::scale(glm::mat4(1.0f), glm::vec3(s));
    }
  }
  return bends;
}

glm::mat4 baseFrame(glm::vec3 position, float yaw, float radius) {
  return glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), position), yaw, glm::vec3(0.0f, 1.0f, 0.0f)),
                    glm::vec3(radius));
}

} // namespace sylva::trees
