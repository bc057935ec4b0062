#pragma once
// Skeleton and poses (docs/trees.md, seed 000 §4.3): every joint's world frame from the tree's base frame,
// the pieces' joint binds, bone scales and per-joint bends. A terminal joint's frame is
//   F[j] = F[root joint] · rimRotation(rotation) · bind · R(bend) · S(scale)
// and a child's root joint is that same matrix (copied, so rims meet bit for bit).

#include <sylva/trees/Tree.hpp>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace sylva::trees {

/** Rotation for a bend θ (radians) about the joint's local x (θ.x) and z (θ.y) axes; the bone is local +y. */
glm::mat4 bendRotation(glm::vec2 theta);

/**
 * World frames of every joint of `tree` (frames.size() = jointCount()): frames[0] = base, the others from the
 * formula above with bends[j] (empty span: rest pose). Similarities (rotation · uniform scale · translation).
 */
void jointFrames(const PieceSet& pieces, const TreeTopology& tree, const glm::mat4& base,
                 std::span<const glm::vec2> bends, std::vector<glm::mat4>& frames);

/**
 * A random pose (paper Fig. 6): bends per joint, uniform in a disc of the joint's order's `bend` amplitude,
 * plus its `droop` towards the ground (× the sine of the bone's angle from vertical as posed so far, parents
 * first, so hanging twigs come to rest pointing down); deterministic in (tree seed, seed).
 */
std::vector<glm::vec2> randomPose(const TreeTopology& tree, const Species& species, std::uint64_t seed);

/** The tree's base frame at world `position` (metres), turned `yaw` radians, one rim unit = `radius` m. */
glm::mat4 baseFrame(glm::vec3 position, float yaw, float radius);

} // namespace sylva::trees
