#include <sylva/trees/Tree.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>
#include <sylva/core/Random.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>

namespace sylva::trees {
namespace {

constexpr int kMaxDepth = 64;

/** An open leaf rim waiting for a piece. */
struct Open {
  int node;
  int rim;
  int order;
  int segment;   // I pieces so far on this axis
  float radius;  // rim radius in trunk radii
  float scale;   // bone scale of the terminal joint it belongs to
  int whorl = 0; // Branch pieces still to come in the whorl this stem rim is part of
};

float rimScale(const Piece& piece, int rim) {
  return glm::length(glm::vec3(piece.rims[static_cast<std::size_t>(rim)].frame[0]));
}

struct PieceIds {
  int i, y, psi, branch, cap, foot;
  explicit PieceIds(const PieceSet& pieces)
      : i(pieces.require("I", "pieces")), y(pieces.require("Y", "pieces")),
        psi(pieces.require("Psi", "pieces")), branch(pieces.require("Branch", "pieces")),
        cap(pieces.require("Cap", "pieces")), foot(pieces.require("Foot", "pieces")) {}
};

} // namespace

glm::mat4 leafBind(const Piece& piece, const TreeNode& node, std::size_t rim) {
  glm::mat4 bind = piece.joints[rim].bind;
  if (node.stretch != 1.0f) {
    bind[3].y *= node.stretch;
  }
  return bind;
}

float stretchReach(const Piece& piece, const TreeNode& node) {
  float top = 0.0f;
  for (std::size_t r = 1; r < piece.joints.size(); ++r) {
    top = std::max(top, std::abs(piece.joints[r].bind[3].y));
  }
  return std::abs(node.stretch - 1.0f) * top;
}

void indexJoints(const PieceSet& pieces, TreeTopology& tree) {
  tree.jointParent.assign(1, -1);
  tree.jointNode.assign(1, -1);
  tree.jointOrder.assign(1, 0);
  tree.jointScale.resize(std::max<std::size_t>(tree.jointScale.size(), 1), 1.0f);
  std::vector<float> scales = tree.jointScale;
  std::uint32_t next = 1;
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    TreeNode& node = tree.nodes[n];
    node.rootJoint =
        node.parent < 0 ? 0u : tree.terminalJoint(static_cast<std::size_t>(node.parent), node.parentRim);
    node.jointBase = next;
    const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
    for (std::size_t r = 1; r < piece.rims.size(); ++r) {
      tree.jointParent.push_back(static_cast<int>(node.rootJoint));
      tree.jointNode.push_back(static_cast<int>(n));
      tree.jointOrder.push_back(node.order);
      ++next;
    }
  }
  scales.resize(next, 1.0f);
  tree.jointScale = std::move(scales);
}

TreeTopology generateTree(const PieceSet& pieces, const Species& species, std::uint64_t seed) {
  validate(species, "species '" + species.name + "'");
  const PieceIds ids(pieces);
  Rng rng(hash64(seed ^ 0x7472656573ULL), hash64(seed + 17));
  TreeTopology tree;
  tree.species = species.name;
  tree.seed = seed;
  std::vector<float> scaleOfJoint{1.0f};

  auto addNode = [&](int piece, const Open* at, int order, std::deque<Open>& open, int segment,
                     float radius) {
    TreeNode node;
    node.piece = piece;
    node.order = order;
    if (at != nullptr) {
      node.parent = at->node;
      node.parentRim = at->rim;
      node.depth = tree.nodes[static_cast<std::size_t>(at->node)].depth + 1;
      node.rotation =
          species.rule == AssemblyRule::Alternate ? (node.depth * 2) % 6 : static_cast<int>(rng.below(6));
    }
    const OrderParams& params = species.order(order);
    // A whorl: Branch pieces on a whorled order, short, each turned a whorl step from the last.
    const bool whorl = piece == ids.branch && params.whorl >= 2 && species.rule == AssemblyRule::Grammar;
    if (whorl) {
      node.stretch = kMinStretch;
      if (at != nullptr && at->whorl > 0) {
        node.rotation = std::max(1, static_cast<int>(std::lround(6.0 / params.whorl)));
      }
    } else if ((piece == ids.i || piece == ids.branch) && params.stretch != 1.0f) {
      // ±15 % per piece from a hash of (seed, node), so the assembly's random stream is untouched.
      const std::uint64_t h = hash64(seed * 0x9E3779B97F4A7C15ULL ^ (tree.nodes.size() + 0x5bd1e995ULL));
      const float jitter = static_cast<float>(h >> 40) / 16777216.0f * 2.0f - 1.0f;
      node.stretch = std::clamp(params.stretch * (1.0f + 0.15f * jitter), kMinStretch, kMaxStretch);
    }
    tree.nodes.push_back(node);
    const int index = static_cast<int>(tree.nodes.size() - 1);
    const Piece& p = pieces[static_cast<std::size_t>(piece)];
    for (int r = 1; r < static_cast<int>(p.rims.size()); ++r) {
      Open o{index, r, order, segment + 1, radius * rimScale(p, r), 1.0f, 0};
      if (piece == ids.y || piece == ids.psi) {
        o.order = order + 1;
        o.segment = 0;
      } else if (piece == ids.branch && r == 2) {
        o.order = order + 1;
        o.segment = 0;
      } else if (whorl && r == 1) {
        // The stem goes on with the rest of the whorl, then grows a new internode.
        o.whorl = at != nullptr && at->whorl > 0 ? at->whorl - 1 : params.whorl - 1;
        o.segment = 0;
      }
      open.push_back(o);
    }
    // Thin side branches by bone scaling, the stem keeping the rest of the cross-section (pipe model).
    if (piece == ids.branch && params.sideRadius > 0.0f) {
      const std::size_t first = open.size() - 2;
      const float stem = std::sqrt(1.0f - params.sideRadius * params.sideRadius);
      open[first].scale = stem / rimScale(p, 1);
      open[first].radius = radius * stem;
      open[first + 1].scale = params.sideRadius / rimScale(p, 2);
      open[first + 1].radius = radius * params.sideRadius;
    }
    // Asymmetric forks by bone scaling: one child of a fork keeps its size, the other shrinks.
    if ((piece == ids.y || piece == ids.psi) && species.order(order).asymmetry > 0.0f) {
      const std::size_t first = open.size() - (p.rims.size() - 1);
      const std::size_t pick = first + rng.below(static_cast<std::uint32_t>(p.rims.size() - 1));
      open[pick].scale = 1.0f - species.order(order).asymmetry * rng.uniform(0.5f, 1.0f);
      open[pick].radius *= open[pick].scale;
    }
  };

  std::deque<Open> open;
  addNode(ids.foot, nullptr, 0, open, -1, 1.0f);
  // The foot's leaf rim starts the trunk: segment 0.
  for (Open& o : open) {
    o.segment = 0;
  }
  while (!open.empty()) {
    const Open at = open.front();
    open.pop_front();
    const int depth = tree.nodes[static_cast<std::size_t>(at.node)].depth + 1;
    const bool budget = tree.nodes.size() + open.size() + 3 >= static_cast<std::size_t>(species.maxPieces);
    const bool limit =
        depth >= std::min(species.maxDepth, kMaxDepth) || at.radius < species.minRadius || budget;
    int piece = ids.cap;
    if (!limit) {
      switch (species.rule) {
      case AssemblyRule::Alternate:
        piece = depth % 2 == 0 ? ids.y : ids.i;
        break;
      case AssemblyRule::UniformRandom:
        piece = rng.below(2) == 0 ? ids.i : ids.y;
        break;
      case AssemblyRule::Grammar: {
        const OrderParams& p = species.order(at.order);
        const bool canSplit = at.order < species.maxOrder;
        const float u = rng.uniform();
        if (at.order > species.maxOrder) {
          piece = ids.cap;
        } else if (at.whorl > 0 && canSplit) {
          piece = ids.branch;
        } else if (at.segment < p.minSegments) {
          piece = ids.i;
        } else if (!canSplit) {
          piece = at.segment >= p.maxSegments ? ids.cap : ids.i;
        } else {
          const float total = p.fork + p.trifurcation + p.sideBranch;
          const bool must = at.segment >= p.maxSegments;
          if (must && total <= 0.0f) {
            piece = ids.cap;
          } else {
            // When the axis must split, the split probabilities are renormalised.
            const float x = must ? u * total : u;
            piece = x < p.fork                                   ? ids.y
                    : x < p.fork + p.trifurcation                ? ids.psi
                    : x < p.fork + p.trifurcation + p.sideBranch ? ids.branch
                                                                 : ids.i;
          }
        }
        break;
      }
      }
    }
    // The bone scale of the rim this node sits on, kept by node index (joint indices come later).
    scaleOfJoint.push_back(at.scale);
    addNode(piece, &at, at.order, open, at.segment, at.radius);
  }
  // Joint scales: each node's root joint is its parent's terminal joint; the scale chosen for that rim was
  // recorded in scaleOfJoint in node order (entry n for node n).
  indexJoints(pieces, tree);
  for (std::size_t n = 1; n < tree.nodes.size(); ++n) {
    tree.jointScale[tree.nodes[n].rootJoint] = scaleOfJoint[n];
  }
  return tree;
}

void validate(const TreeTopology& tree, const PieceSet& pieces, const std::string& where) {
  if (tree.nodes.empty()) {
    fail("{}: nodes: a tree needs at least one node", where);
  }
  std::set<std::pair<int, int>> used;
  std::vector<int> depth(tree.nodes.size(), 0);
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    const TreeNode& node = tree.nodes[n];
    if (node.piece < 0 || node.piece >= static_cast<int>(pieces.size())) {
      fail("{}: /nodes/{}/piece: unknown piece index {}", where, n, node.piece);
    }
    if (!(node.stretch >= kMinStretch && node.stretch <= kMaxStretch)) {
      fail("{}: /nodes/{}/stretch: {} is not in [{}, {}]", where, n, node.stretch, kMinStretch, kMaxStretch);
    }
    if (n == 0) {
      if (node.parent != -1) {
        fail("{}: /nodes/0/parent: the root has no parent", where);
      }
      if (pieces[static_cast<std::size_t>(node.piece)].name != "Foot") {
        fail("{}: /nodes/0/piece: the root is always a Foot (the trunk's base), not '{}'", where,
             pieces[static_cast<std::size_t>(node.piece)].name);
      }
      continue;
    }
    if (node.parent < 0 || node.parent >= static_cast<int>(n)) {
      fail("{}: /nodes/{}/parent: {} must name an earlier node", where, n, node.parent);
    }
    const Piece& parent =
        pieces[static_cast<std::size_t>(tree.nodes[static_cast<std::size_t>(node.parent)].piece)];
    if (node.parentRim < 1 || node.parentRim > static_cast<int>(parent.leafRims())) {
      fail("{}: /nodes/{}/rim: piece '{}' has leaf rims 1 … {}, not {}", where, n, parent.name,
           parent.leafRims(), node.parentRim);
    }
    if (!used.insert({node.parent, node.parentRim}).second) {
      fail("{}: /nodes/{}/rim: rim {} of node {} is used twice", where, n, node.parentRim, node.parent);
    }
    if (node.rotation < 0 || node.rotation > 5) {
      fail("{}: /nodes/{}/rotation: {} is not in 0 … 5", where, n, node.rotation);
    }
    depth[n] = depth[static_cast<std::size_t>(node.parent)] + 1;
    if (depth[n] > kMaxDepth) {
      fail("{}: /nodes/{}: depth {} exceeds the recursion limit {}", where, n, depth[n], kMaxDepth);
    }
  }
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    const Piece& piece = pieces[static_cast<std::size_t>(tree.nodes[n].piece)];
    for (int r = 1; r <= static_cast<int>(piece.leafRims()); ++r) {
      if (used.count({static_cast<int>(n), r}) == 0) {
        fail("{}: /nodes/{}: leaf rim {} of piece '{}' is open (close it with a Cap)", where, n, r,
             piece.name);
      }
    }
  }
  for (std::size_t j = 0; j < tree.jointScale.size(); ++j) {
    if (!(std::isfinite(tree.jointScale[j]) && tree.jointScale[j] > 0.01f && tree.jointScale[j] <= 100.0f)) {
      fail("{}: joint {}: scale {} must be a finite number in (0.01, 100]", where, j, tree.jointScale[j]);
    }
  }
}

std::vector<glm::mat4> topologicalTransforms(const PieceSet& pieces, const TreeTopology& tree) {
  std::vector<glm::mat4> out(tree.nodes.size(), glm::mat4(1.0f));
  for (std::size_t n = 1; n < tree.nodes.size(); ++n) {
    const TreeNode& node = tree.nodes[n];
    const TreeNode& up = tree.nodes[static_cast<std::size_t>(node.parent)];
    const Piece& parent = pieces[static_cast<std::size_t>(up.piece)];
    const float s = tree.jointScale[node.rootJoint];
    out[n] = out[static_cast<std::size_t>(node.parent)] *
             leafBind(parent, up, static_cast<std::size_t>(node.parentRim)) *
             glm::scale(glm::mat4(1.0f), glm::vec3(s)) * rimRotation(node.rotation);
  }
  return out;
}

TreeStats treeStats(const PieceSet& pieces, const TreeTopology& tree) {
  TreeStats s;
  s.pieces = tree.nodes.size();
  s.piecesByType.assign(pieces.size(), 0);
  s.joints = tree.jointCount();
  const std::vector<glm::mat4> transforms = topologicalTransforms(pieces, tree);
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    const TreeNode& node = tree.nodes[n];
    const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
    s.piecesByType[static_cast<std::size_t>(node.piece)] += 1;
    s.quads += piece.quads.size();
    s.maxDepth = std::max(s.maxDepth, node.depth);
    s.maxOrder = std::max(s.maxOrder, node.order);
    for (const PieceVertex& v : piece.vertices) {
      s.height = std::max(s.height, (transforms[n] * glm::vec4(v.position, 1.0f)).y);
    }
  }
  return s;
}

nlohmann::json toJson(const TreeTopology& tree, const PieceSet& pieces) {
  nlohmann::json nodes = nlohmann::json::array();
  for (const TreeNode& node : tree.nodes) {
    nlohmann::json n{{"piece", pieces[static_cast<std::size_t>(node.piece)].name}};
    if (node.parent >= 0) {
      n["parent"] = node.parent;
      n["rim"] = node.parentRim;
      n["rotation"] = node.rotation;
      n["order"] = node.order;
      const float s = tree.jointScale[node.rootJoint];
      if (s != 1.0f) {
        n["scale"] = s;
      }
    }
    if (node.stretch != 1.0f) {
      n["stretch"] = node.stretch;
    }
    nodes.push_back(n);
  }
  return {{"version", 1}, {"species", tree.species}, {"seed", tree.seed}, {"nodes", nodes}};
}

TreeTopology treeFromJson(const nlohmann::json& json, const PieceSet& pieces, const std::string& where) {
  requireJsonVersion(json, 1, where);
  const JsonNode root(json, where, "");
  root.object({"version", "species", "seed", "nodes"});
  TreeTopology tree;
  tree.species = root.has("species") ? root["species"].string() : std::string("custom");
  if (root.has("seed")) {
    const JsonNode seed = root["seed"];
    if (!seed.value().is_number_unsigned()) {
      seed.error("expected a non-negative integer");
    }
    tree.seed = seed.value().get<std::uint64_t>();
  }
  const JsonNode nodes = root["nodes"];
  const std::size_t count = nodes.array(1, 200000);
  std::vector<float> childScale(count, 1.0f);
  for (std::size_t i = 0; i < count; ++i) {
    const JsonNode n = nodes[i];
    n.object({"piece", "parent", "rim", "rotation", "order", "scale", "stretch"});
    TreeNode node;
    node.piece = pieces.require(n["piece"].string(), fmt::format("{}: {}/piece", where, n.path()));
    if (n.has("stretch")) {
      node.stretch = static_cast<float>(n["stretch"].number(kMinStretch, kMaxStretch));
    }
    if (i > 0) {
      node.parent = n["parent"].integer(0, static_cast<int>(i) - 1);
      node.parentRim = n["rim"].integer(1, 15);
      node.rotation = n.has("rotation") ? n["rotation"].integer(0, 5) : 0;
      node.order = n.has("order") ? n["order"].integer(0, 16) : 0;
      childScale[i] = n.has("scale") ? static_cast<float>(n["scale"].number(0.02, 100)) : 1.0f;
    } else if (n.has("parent")) {
      n["parent"].error("the root node has no parent");
    }
    tree.nodes.push_back(node);
  }
  // Depth and rim checks before joints are indexed (they index by rim).
  for (std::size_t i = 1; i < count; ++i) {
    TreeNode& node = tree.nodes[i];
    node.depth = tree.nodes[static_cast<std::size_t>(node.parent)].depth + 1;
    const Piece& parent =
        pieces[static_cast<std::size_t>(tree.nodes[static_cast<std::size_t>(node.parent)].piece)];
    if (node.parentRim > static_cast<int>(parent.leafRims())) {
      nodes[i]["rim"].error(fmt::format("piece '{}' has leaf rims 1 … {}", parent.name, parent.leafRims()));
    }
    if (node.depth > kMaxDepth) {
      nodes[i].error(fmt::format("depth {} exceeds the recursion limit {}", node.depth, kMaxDepth));
    }
  }
  tree.jointScale.clear();
  indexJoints(pieces, tree);
  for (std::size_t i = 1; i < count; ++i) {
    tree.jointScale[tree.nodes[i].rootJoint] = childScale[i];
  }
  validate(tree, pieces, where);
  return tree;
}

TreeTopology loadTree(const std::filesystem::path& path, const PieceSet& pieces) {
  return treeFromJson(loadJsonFile(path), pieces, path.filename().string());
}

void saveTree(const std::filesystem::path& path, const TreeTopology& tree, const PieceSet& pieces) {
  saveJsonFile(path, toJson(tree, pieces));
}

} // namespace sylva::trees
