#pragma once
// Assembly (docs/trees.md, seed 000 §4.2–4.3): a tree is a list of piece nodes, each sitting on a leaf rim of
// its parent under one of the six rim rotations. Joints: joint 0 is the tree's base; every node's root joint
// IS its parent's terminal joint for that rim (rigid attachment), and its own terminal joints are numbered
// from jointBase. Topological transforms compose building transforms from the root down.

#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Species.hpp>

#include <nlohmann/json_fwd.hpp>

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::trees {

/** One placed piece. Nodes are stored parents first. */
struct TreeNode {
  /** Index into the PieceSet. */
  int piece = 0;
  /** Parent node, -1 for the root. */
  int parent = -1;
  /** The parent's leaf rim this node's root rim sits on (1 … parent's leaf rims); 0 for the root. */
  int parentRim = 0;
  /** Rotation of this piece about its root rim axis, in 60° steps (0 … 5). */
  int rotation = 0;
  /** Branching order (0: trunk) and depth (pieces from the root). */
  int order = 0;
  /** Pieces from the root. */
  int depth = 0;
  /**
   * Axial stretch (0.5 … 16): the piece's leaf rims sit this many times as far along its root rim's axis
   * (model +y) as in the piece's mesh, so a segment grows longer without growing thicker. Rims stay exact
   * similarities (only their joints move); linear blend skinning spreads the stretch over the interior.
   */
  float stretch = 1.0f;
  /** Global index of its root joint (the parent's terminal joint; 0 for the root node). */
  std::uint32_t rootJoint = 0;
  /** Global index of its first terminal joint (leaf rim 1); terminal of leaf rim r is jointBase + r − 1. */
  std::uint32_t jointBase = 0;
};

/** A tree's topology and rest parameters (no placement). */
struct TreeTopology {
  /** The piece instances, root first. */
  std::vector<TreeNode> nodes;
  /** Per global joint: parent joint (-1 for the base), the node whose terminal joint it is (-1 for the base).
   */
  std::vector<int> jointParent;
  /** Per global joint: the node whose terminal joint it is (-1 for the base). */
  std::vector<int> jointNode;
  /** Per global joint: bone scale (asymmetric forks), 1 by default. */
  std::vector<float> jointScale;
  /** Per global joint: branching order of the piece it ends (trunk 0). */
  std::vector<int> jointOrder;
  /** Name of the species it grew as. */
  std::string species;
  /** The seed it grew from. */
  std::uint64_t seed = 0;

  /** Joints over all nodes. */
  std::size_t jointCount() const { return jointParent.size(); }
  /** Terminal joint of `node`'s leaf rim `rim` (1-based). */
  std::uint32_t terminalJoint(std::size_t node, int rim) const { return nodes[node].jointBase + rim - 1; }
};

/**
 * Generates a tree of `species` from `seed` (deterministic; the same inputs give the same tree on every
 * platform). The root is the Foot; every open rim is filled by the rule and closed by a Cap at the limits.
 */
TreeTopology generateTree(const PieceSet& pieces, const Species& species, std::uint64_t seed);

/** Smallest and largest TreeNode::stretch a tree may carry. */
constexpr float kMinStretch = 0.5f;
/** Largest TreeNode::stretch. */
constexpr float kMaxStretch = 16.0f;

/**
 * The bind frame of leaf rim `rim` (1-based) of `node`, a `piece`: the piece's joint bind moved along the
 * root axis by the node's stretch (bind translation y × stretch). Every consumer of joint frames uses it.
 */
glm::mat4 leafBind(const Piece& piece, const TreeNode& node, std::size_t rim);

/**
 * How far, in the piece's model units, the node's stretch moves its farthest leaf rim along the root axis
 * ((stretch − 1) × largest leaf-rim height, 0 when unstretched): what culling adds to the piece's bounds.
 */
float stretchReach(const Piece& piece, const TreeNode& node);

/** Rebuilds jointParent/jointNode/jointOrder and the nodes' joint indices from pieces and parents. */
void indexJoints(const PieceSet& pieces, TreeTopology& tree);

/**
 * Checks a topology against `pieces`: parents before children, rims in range and each used once, rotations
 * 0 … 5, depth ≤ 64, no open leaf rim, finite positive scales, stretches in [kMinStretch, kMaxStretch].
 * Throws sylva::Error "<where>: nodes[i].<field>: <reason>".
 */
void validate(const TreeTopology& tree, const PieceSet& pieces, const std::string& where);

/**
 * Topological transforms (piece model space → tree space, rest pose, bone scales applied): one per node.
 * transform[root] = identity; a child's = parent's · joint bind of its rim · scale · rimRotation(rotation).
 */
std::vector<glm::mat4> topologicalTransforms(const PieceSet& pieces, const TreeTopology& tree);

/** Counts for `sylva tree info` and benchmarks. */
struct TreeStats {
  /** Piece instances. */
  std::size_t pieces = 0;
  /** Piece instances per piece type. */
  std::vector<std::size_t> piecesByType;
  /** Joints. */
  std::size_t joints = 0;
  /** Quads over all piece instances. */
  std::size_t quads = 0;
  /** Deepest node (pieces from the root). */
  int maxDepth = 0;
  /** Highest branching order. */
  int maxOrder = 0;
  /** Height of the rest pose, trunk-radius units, and tree-space bounds. */
  float height = 0.0f;
};
/** The counts of `tree`. */
TreeStats treeStats(const PieceSet& pieces, const TreeTopology& tree);

/** Tree JSON (version 1): species, seed and nodes by piece name; strict loading with errors naming the field.
 */
nlohmann::json toJson(const TreeTopology& tree, const PieceSet& pieces);
/** A tree from its JSON (pieces by name from `pieces`); errors name `where` and the field. */
TreeTopology treeFromJson(const nlohmann::json& json, const PieceSet& pieces, const std::string& where);
/** Reads a tree file; errors name the file and field. */
TreeTopology loadTree(const std::filesystem::path& path, const PieceSet& pieces);
/** Writes a tree file (JSON), atomically. */
void saveTree(const std::filesystem::path& path, const TreeTopology& tree, const PieceSet& pieces);

} // namespace sylva::trees
