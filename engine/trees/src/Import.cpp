#include <sylva/trees/Import.hpp>

#include "internal/Finite.hpp"
#include "internal/Gltf.hpp"
#include "internal/Skinning.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include "internal/AssimpMath.hpp"
#include "internal/AssimpRead.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <vector>

namespace sylva::trees {
namespace {

using internal::finite;

namespace fs = std::filesystem;
using internal::appendBytes;
using internal::base64;
using internal::matrixJson;

constexpr std::size_t kMaxLeafRims = 15;
constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

std::string vec3Text(const glm::vec3& v) {
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", v.x, v.y, v.z);
}

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

/** A rim vertex group read from a bone: its vertices (weight over 0.5) and the bone's frame, model space. */
struct BoneGroup {
  std::vector<std::uint32_t> vertices;
  std::optional<glm::mat4> frame;
};

/** The mesh as read: welded vertices, quads in file order, and the rim groups its bones mark. */
struct RawMesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec2> uvs;
  /** Sum of the file's unit normals of each welded vertex; used when hasNormals. */
  std::vector<glm::vec3> normals;
  bool hasNormals = true;
  std::vector<std::array<std::uint32_t, 4>> quads;
  /** Bone groups by rim index: 0 root, r leaf rim r (absent when no bone names it). */
  std::map<int, BoneGroup> groups;
  bool hasRimBones = false;
};

/** The rim a bone names (0: rim_root, N: rim_leaf_N), -1 for other bones; throws for other rim_ names. */
int rimOfBone(const std::string& file, const std::string& name) {
  if (name == "rim_root") {
    return 0;
  }
  if (!name.starts_with("rim_")) {
    return -1;
  }
  const std::string prefix = "rim_leaf_";
  if (name.starts_with(prefix) && name.size() > prefix.size() && name.size() <= prefix.size() + 2 &&
      std::all_of(name.begin() + static_cast<std::ptrdiff_t>(prefix.size()), name.end(),
                  [](char c) { return c >= '0' && c <= '9'; }) &&
      name[prefix.size()] != '0') {
    const int n = std::stoi(name.substr(prefix.size()));
    if (n <= static_cast<int>(kMaxLeafRims)) {
      return n;
    }
  }
  fail("{}: bone '{}' is not a rim (rim bones are rim_root and rim_leaf_1 … rim_leaf_{})", file, name,
       kMaxLeafRims);
}

/** Reads every mesh of the scene (node transforms applied), welds by position and builds quads. */
RawMesh readMesh(const aiScene& scene, const std::string& file, bool trianglePairs,
                 const ImportOptions& options) {
  RawMesh raw;
  // Weld by exact position: split normals and UV seams give one point several vertices in most formats.
  std::unordered_map<std::string, std::uint32_t> welded;
  auto weld = [&](const glm::vec3& p, const glm::vec2& uv, const glm::vec3& normal) {
    const glm::vec3 q = p + glm::vec3(0.0f); // -0 → +0
    std::string key(sizeof q, '\0');
    std::memcpy(key.data(), &q, sizeof q);
    const auto [it, inserted] =
        welded.emplace(std::move(key), static_cast<std::uint32_t>(raw.positions.size()));
    if (inserted) {
      raw.positions.push_back(q);
      raw.uvs.push_back(uv);
      raw.normals.emplace_back(0.0f);
    }
    raw.normals[it->second] += normal;
    return it->second;
  };
  std::size_t faceIndex = 0;
  std::size_t meshCount = 0;
  // Model-space frames of the nodes by name: a rim bone's node is its frame.
  std::unordered_map<std::string, glm::mat4> nodeFrames;
  {
    std::vector<std::pair<const aiNode*, glm::mat4>> open{{scene.mRootNode, glm::mat4(1.0f)}};
    while (!open.empty()) {
      const auto [node, parent] = open.back();
      open.pop_back();
      if (node == nullptr) {
        continue;
      }
      const glm::mat4 global = parent * internal::toGlm(node->mTransformation);
      nodeFrames.emplace(node->mName.C_Str(), global);
      for (unsigned c = 0; c < node->mNumChildren; ++c) {
        open.emplace_back(node->mChildren[c], global);
      }
    }
  }

  std::vector<std::pair<const aiNode*, glm::mat4>> stack{{scene.mRootNode, glm::mat4(1.0f)}};
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (node == nullptr) {
      continue;
    }
    const glm::mat4 global = parent * internal::toGlm(node->mTransformation);
    // Children in order: push in reverse so the first child is read first.
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      stack.emplace_back(node->mChildren[c], global);
    }
    for (unsigned m = 0; m < node->mNumMeshes; ++m) {
      if (node->mMeshes[m] >= scene.mNumMeshes) {
        continue;
      }
      const aiMesh& mesh = *scene.mMeshes[node->mMeshes[m]];
      ++meshCount;
      raw.hasNormals = raw.hasNormals && mesh.HasNormals();
      std::vector<std::uint32_t> index(mesh.mNumVertices, kNone);
      const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(global)));
      auto vertexOf = [&](unsigned i) {
        if (i >= mesh.mNumVertices) {
          fail("{}: corrupt mesh (a face refers to vertex {} of {})", file, i, mesh.mNumVertices);
        }
        if (index[i] == kNone) {
          const aiVector3D& p = mesh.mVertices[i];
          const glm::vec3 position(global * glm::vec4(p.x, p.y, p.z, 1.0f));
          if (!finite(position)) {
            fail("{}: a vertex position is not finite {}", file, vec3Text(glm::vec3(p.x, p.y, p.z)));
          }
          glm::vec2 uv(0.0f);
          if (mesh.HasTextureCoords(0)) {
            uv = glm::vec2(mesh.mTextureCoords[0][i].x, mesh.mTextureCoords[0][i].y);
            if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) {
              uv = glm::vec2(0.0f);
            }
          }
          glm::vec3 normal(0.0f);
          if (mesh.HasNormals()) {
            const glm::vec3 n(normalMatrix *
                              glm::vec3(mesh.mNormals[i].x, mesh.mNormals[i].y, mesh.mNormals[i].z));
            if (finite(n) && glm::length(n) > 1e-6f) {
              normal = glm::normalize(n);
            }
          }
          index[i] = weld(position, uv, normal);
        }
        return index[i];
      };
      auto addQuad = [&](const std::array<std::uint32_t, 4>& q) {
        if (raw.quads.size() >= options.maxQuads) {
          fail("{}: more than {} quads", file, options.maxQuads);
        }
        raw.quads.push_back(q);
      };
      if (trianglePairs) {
        // glTF has no quads: quad i is triangles 2i and 2i + 1, which share one edge in opposite directions.
        for (unsigned f = 0; f < mesh.mNumFaces; ++f, ++faceIndex) {
          if (mesh.mFaces[f].mNumIndices != 3) {
            fail("{}: not a quad mesh (face {} has {} corners; glTF stores each quad as two triangles)", file,
                 faceIndex, mesh.mFaces[f].mNumIndices);
          }
        }
        if (mesh.mNumFaces % 2 != 0) {
          fail("{}: not a quad mesh ({} triangles: glTF stores each quad as two consecutive triangles)", file,
               mesh.mNumFaces);
        }
        for (unsigned f = 0; f + 1 < mesh.mNumFaces; f += 2) {
          std::array<std::uint32_t, 3> t1{};
          std::array<std::uint32_t, 3> t2{};
          for (unsigned k = 0; k < 3; ++k) {
            t1[k] = vertexOf(mesh.mFaces[f].mIndices[k]);
            t2[k] = vertexOf(mesh.mFaces[f + 1].mIndices[k]);
          }
          std::optional<std::array<std::uint32_t, 4>> quad;
          for (std::size_t e = 0; e < 3 && !quad; ++e) {
            const std::uint32_t a = t1[e];
            const std::uint32_t b = t1[(e + 1) % 3];
            for (std::size_t k = 0; k < 3; ++k) {
              if (t2[k] == b && t2[(k + 1) % 3] == a) {
                const std::uint32_t extra = t2[(k + 2) % 3];
                std::array<std::uint32_t, 4> q{};
                std::size_t n = 0;
                for (std::size_t i = 0; i < 3; ++i) {
                  q[n++] = t1[i];
                  if (i == e) {
                    q[n++] = extra;
                  }
                }
                quad = q;
                break;
              }
            }
          }
          const std::size_t first = faceIndex - mesh.mNumFaces + f;
          if (!quad || (*quad)[0] == (*quad)[1] || (*quad)[0] == (*quad)[2] || (*quad)[0] == (*quad)[3] ||
              (*quad)[1] == (*quad)[2] || (*quad)[1] == (*quad)[3] || (*quad)[2] == (*quad)[3]) {
            fail("{}: not a quad mesh (triangles {} and {} do not form a quad: glTF stores each quad as two "
                 "consecutive triangles sharing an edge)",
                 file, first, first + 1);
          }
          addQuad(*quad);
        }
      } else {
        for (unsigned f = 0; f < mesh.mNumFaces; ++f, ++faceIndex) {
          const aiFace& face = mesh.mFaces[f];
          if (face.mNumIndices != 4) {
            fail("{}: not a quad mesh (face {} has {} corners)", file, faceIndex, face.mNumIndices);
          }
          std::array<std::uint32_t, 4> q{};
          for (unsigned k = 0; k < 4; ++k) {
            q[k] = vertexOf(face.mIndices[k]);
          }
          addQuad(q);
        }
      }
      // Bones: rim groups.
      for (unsigned b = 0; b < mesh.mNumBones; ++b) {
        const aiBone& bone = *mesh.mBones[b];
        const int rim = rimOfBone(file, bone.mName.C_Str());
        if (rim < 0) {
          continue;
        }
        raw.hasRimBones = true;
        BoneGroup& group = raw.groups[rim];
        if (!group.frame) {
          // The bone's node in model space, else its bind pose (the inverse of the offset matrix).
          const auto node = nodeFrames.find(bone.mName.C_Str());
          const glm::mat4 frame = node != nodeFrames.end()
                                      ? node->second
                                      : global * glm::inverse(internal::toGlm(bone.mOffsetMatrix));
          bool ok = true;
          for (int c = 0; c < 4; ++c) {
            ok = ok && finite(glm::vec3(frame[c]));
          }
          if (ok) {
            group.frame = frame;
          }
        }
        for (unsigned w = 0; w < bone.mNumWeights; ++w) {
          const aiVertexWeight& weight = bone.mWeights[w];
          if (weight.mVertexId < mesh.mNumVertices && weight.mWeight > 0.5f) {
            const std::uint32_t v = index[weight.mVertexId];
            if (v != kNone &&
                std::find(group.vertices.begin(), group.vertices.end(), v) == group.vertices.end()) {
              group.vertices.push_back(v);
            }
          }
        }
      }
    }
  }
  if (meshCount == 0 || raw.quads.empty()) {
    fail("{}: no quads in the file", file);
  }
  return raw;
}

/** Edges of the quads: how many quads use each (undirected); where each vertex is first used; its quads. */
struct Topology {
  std::unordered_map<std::uint64_t, int> uses;
  /** Position of each vertex's first use in the face list (4 · quad + corner). */
  std::vector<std::size_t> firstUse;
  std::vector<std::vector<std::size_t>> quadsOf;

  explicit Topology(const RawMesh& raw)
      : firstUse(raw.positions.size(), std::numeric_limits<std::size_t>::max()) {
    quadsOf.resize(raw.positions.size());
    for (std::size_t q = 0; q < raw.quads.size(); ++q) {
      for (std::size_t k = 0; k < 4; ++k) {
        const std::uint32_t a = raw.quads[q][k];
        const std::uint32_t b = raw.quads[q][(k + 1) % 4];
        uses[edgeKey(a, b)] += 1;
        firstUse[a] = std::min(firstUse[a], 4 * q + k);
        quadsOf[a].push_back(q);
      }
    }
  }
  bool joined(std::uint32_t a, std::uint32_t b) const { return uses.count(edgeKey(a, b)) > 0; }
};

/** A rim found in the file: its six vertices in loop order (either direction) and what decides corner 0. */
struct FoundRim {
  std::string name;
  std::vector<std::uint32_t> loop;
  /**
   * The rim bone's frame (model space): its +x picks corner 0 (otherwise the first vertex the faces reach),
   * and it is the rim frame itself when it maps the standard rim onto the corners within the tolerance.
   */
  std::optional<glm::mat4> boneFrame;
};

/** Orders a bone's vertex set into a loop along the mesh's edges. */
std::vector<std::uint32_t> loopOfGroup(const std::string& where, const std::vector<std::uint32_t>& set,
                                       const Topology& topo) {
  if (set.size() != static_cast<std::size_t>(kRimCorners)) {
    fail("{}: {} vertices (a rim has {})", where, set.size(), kRimCorners);
  }
  std::vector<std::uint32_t> loop{set[0]};
  std::vector<bool> used(set.size(), false);
  used[0] = true;
  for (std::size_t step = 1; step < set.size(); ++step) {
    std::size_t next = set.size();
    for (std::size_t i = 0; i < set.size(); ++i) {
      if (!used[i] && topo.joined(loop.back(), set[i])) {
        next = i;
        break;
      }
    }
    if (next == set.size()) {
      fail("{}: its six vertices do not form a loop of edges", where);
    }
    used[next] = true;
    loop.push_back(set[next]);
  }
  if (!topo.joined(loop.back(), loop.front())) {
    fail("{}: its six vertices do not form a loop of edges", where);
  }
  return loop;
}

/** Boundary loops (edges used by one quad), in the direction of their quads' winding. */
std::vector<std::vector<std::uint32_t>> boundaryLoops(const std::string& file, const RawMesh& raw,
                                                      const Topology& topo) {
  std::unordered_map<std::uint32_t, std::uint32_t> next;
  std::vector<std::uint32_t> starts;
  for (const auto& q : raw.quads) {
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t a = q[k];
      const std::uint32_t b = q[(k + 1) % 4];
      if (topo.uses.at(edgeKey(a, b)) == 1) {
        if (!next.emplace(a, b).second) {
          fail("{}: the boundary passes vertex {} twice (rims must not touch)", file,
               vec3Text(raw.positions[a]));
        }
        starts.push_back(a);
      }
    }
  }
  std::vector<std::vector<std::uint32_t>> loops;
  std::unordered_map<std::uint32_t, bool> seen;
  for (std::uint32_t start : starts) {
    if (seen[start]) {
      continue;
    }
    std::vector<std::uint32_t> loop;
    std::uint32_t v = start;
    while (!seen[v]) {
      seen[v] = true;
      loop.push_back(v);
      const auto it = next.find(v);
      if (it == next.end()) {
        fail("{}: the boundary is not closed at vertex {}", file, vec3Text(raw.positions[v]));
      }
      v = it->second;
    }
    if (v != start) {
      fail("{}: the boundary is not a set of closed loops at vertex {}", file, vec3Text(raw.positions[v]));
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

/** The six vertices at the standard rim's corners (corner k at rimCorner(k)), or a one-line reason. */
std::vector<std::uint32_t> findRootByPosition(const std::string& file, const RawMesh& raw, float tolerance) {
  std::vector<std::uint32_t> corners;
  for (int k = 0; k < kRimCorners; ++k) {
    const glm::vec3 target = rimCorner(k);
    float best = std::numeric_limits<float>::infinity();
    std::uint32_t bestIndex = 0;
    for (std::uint32_t i = 0; i < raw.positions.size(); ++i) {
      const float d = glm::length(raw.positions[i] - target);
      if (d < best) {
        best = d;
        bestIndex = i;
      }
    }
    if (!(best <= tolerance)) {
      if (best < 0.25f) {
        fail("{}: root rim is not the standard rim (corner {} is {:.3g} off)", file, k, best);
      }
      fail("{}: missing root rim (no vertex at corner {} {} of the standard rim: the unit hexagon in the "
           "y = 0 plane around the origin, axis +y)",
           file, k, vec3Text(target));
    }
    corners.push_back(bestIndex);
  }
  return corners;
}

/** The neighbours of a rim on the piece's side: the other vertices of the quads holding its edges. */
glm::vec3 ringSide(const RawMesh& raw, const Topology& topo, const std::vector<std::uint32_t>& loop,
                   const glm::vec3& centre) {
  glm::vec3 sum(0.0f);
  int count = 0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const std::uint32_t a = loop[k];
    const std::uint32_t b = loop[(k + 1) % loop.size()];
    for (std::size_t q : topo.quadsOf[a]) {
      const auto& quad = raw.quads[q];
      if (std::find(quad.begin(), quad.end(), b) == quad.end()) {
        continue;
      }
      for (std::uint32_t v : quad) {
        if (std::find(loop.begin(), loop.end(), v) == loop.end()) {
          sum += raw.positions[v] - centre;
          ++count;
        }
      }
    }
  }
  return count > 0 ? sum / static_cast<float>(count) : sum;
}

/** A rim fitted: corners in order (corner k at frame · rimCorner(k)) and the frame. */
struct FittedRim {
  std::array<std::uint32_t, kRimCorners> corners{};
  glm::mat4 frame{1.0f};
};

/** The root rim: the standard rim, corner k nearest rimCorner(k). */
FittedRim fitRoot(const std::string& where, const RawMesh& raw, const Topology& topo,
                  const std::vector<std::uint32_t>& loop, float tolerance) {
  FittedRim fit;
  for (int k = 0; k < kRimCorners; ++k) {
    float best = std::numeric_limits<float>::infinity();
    for (std::uint32_t v : loop) {
      const float d = glm::length(raw.positions[v] - rimCorner(k));
      if (d < best) {
        best = d;
        fit.corners[static_cast<std::size_t>(k)] = v;
      }
    }
    if (!(best <= tolerance)) {
      fail("{} is not the standard rim (corner {} is {:.3g} off; the root rim is the unit hexagon in the "
           "y = 0 plane around the origin)",
           where, k, best);
    }
  }
  for (int k = 0; k < kRimCorners; ++k) {
    for (int j = 0; j < k; ++j) {
      if (fit.corners[static_cast<std::size_t>(k)] == fit.corners[static_cast<std::size_t>(j)]) {
        fail("{} is not the standard rim (corners {} and {} are one vertex)", where, j, k);
      }
    }
  }
  for (int k = 0; k < kRimCorners; ++k) {
    if (!topo.joined(fit.corners[static_cast<std::size_t>(k)],
                     fit.corners[static_cast<std::size_t>((k + 1) % kRimCorners)])) {
      fail("{}: corners {} and {} are not joined by an edge", where, k, (k + 1) % kRimCorners);
    }
  }
  return fit;
}

/** A leaf rim: the similarity that best maps the standard rim onto its corners; checks regularity. */
FittedRim fitLeaf(const std::string& where, const RawMesh& raw, const Topology& topo, const FoundRim& found,
                  float tolerance) {
  const std::vector<std::uint32_t>& loop = found.loop;
  std::array<glm::vec3, kRimCorners> p{};
  glm::vec3 centre(0.0f);
  for (std::size_t k = 0; k < loop.size(); ++k) {
    p[k] = raw.positions[loop[k]];
    centre += p[k] / static_cast<float>(kRimCorners);
  }
  // Plane normal (Newell) in loop order, turned to point away from the piece.
  glm::vec3 normal(0.0f);
  for (std::size_t k = 0; k < loop.size(); ++k) {
    normal += glm::cross(p[k] - centre, p[(k + 1) % loop.size()] - centre);
  }
  float size = 0.0f;
  for (const glm::vec3& q : p) {
    size = std::max(size, glm::length(q - centre));
  }
  if (!(glm::length(normal) > 1e-6f * size * size) || !(size > 1e-4f)) {
    fail("{} is degenerate (its corners do not span a hexagon)", where);
  }
  glm::vec3 axis = glm::normalize(normal);
  const float side = glm::dot(ringSide(raw, topo, loop, centre), axis);
  if (!(std::abs(side) > 1e-4f * size)) {
    fail("{}: cannot tell which side of it the piece lies on", where);
  }
  if (side > 0.0f) {
    axis = -axis;
  }
  auto inPlane = [&](const glm::vec3& v) { return v - axis * glm::dot(v, axis); };
  // Corner 0: nearest the bone's +x, else the first vertex the faces reach.
  std::size_t zero = 0;
  bool chosen = false;
  if (found.boneFrame) {
    const glm::vec3 boneX((*found.boneFrame)[0]);
    const glm::vec3 x = inPlane(boneX);
    if (glm::length(x) > 0.5f * glm::length(boneX)) {
      float best = -std::numeric_limits<float>::infinity();
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const float d = glm::dot(glm::normalize(inPlane(p[k] - centre)), glm::normalize(x));
        if (d > best) {
          best = d;
          zero = k;
        }
      }
      chosen = true;
    }
  }
  if (!chosen) {
    for (std::size_t k = 1; k < loop.size(); ++k) {
      if (topo.firstUse[loop[k]] < topo.firstUse[loop[zero]]) {
        zero = k;
      }
    }
  }
  const glm::vec3 e1 = glm::normalize(inPlane(p[zero] - centre));
  const glm::vec3 e2 = glm::cross(e1, axis); // the z axis of a frame whose x is e1 and y the rim axis
  // Corner 1 lies at 60° from corner 0 towards e2: pick the loop direction that goes there.
  const std::size_t n = loop.size();
  const glm::vec3 towards = 0.5f * e1 + 0.8660254f * e2;
  const bool forward = glm::dot(inPlane(p[(zero + 1) % n] - centre), towards) >=
                       glm::dot(inPlane(p[(zero + n - 1) % n] - centre), towards);
  FittedRim fit;
  std::array<glm::vec3, kRimCorners> corner{};
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = forward ? (zero + k) % n : (zero + n - k) % n;
    fit.corners[k] = loop[i];
    corner[k] = p[i];
  }
  // A bone placed exactly on the rim is its frame (exact: no refitting noise).
  if (found.boneFrame && glm::dot(glm::vec3((*found.boneFrame)[1]), axis) > 0.0f) {
    const float boneScale = glm::length(glm::vec3((*found.boneFrame)[0]));
    bool fits = true;
    for (int k = 0; k < kRimCorners && fits; ++k) {
      const glm::vec3 expected(*found.boneFrame * glm::vec4(rimCorner(k), 1.0f));
      fits = glm::length(corner[static_cast<std::size_t>(k)] - expected) <=
             tolerance * std::max(1.0f, boneScale);
    }
    if (fits) {
      fit.frame = *found.boneFrame;
      return fit;
    }
  }
  // Least-squares in-plane rotation and scale: Σ (x_k + i y_k) e^{-i 60° k} = 6 s e^{i θ}.
  double re = 0.0;
  double im = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const glm::vec3 d = corner[k] - centre;
    const double x = glm::dot(d, e1);
    const double y = glm::dot(d, e2);
    const double a = -std::numbers::pi / 3.0 * static_cast<double>(k);
    re += x * std::cos(a) - y * std::sin(a);
    im += x * std::sin(a) + y * std::cos(a);
  }
  const double theta = std::atan2(im, re);
  const auto scale = static_cast<float>(std::sqrt(re * re + im * im) / 6.0);
  const glm::vec3 x =
      glm::normalize(static_cast<float>(std::cos(theta)) * e1 + static_cast<float>(std::sin(theta)) * e2);
  const glm::vec3 z = glm::normalize(glm::cross(x, axis));
  fit.frame = glm::mat4(glm::vec4(x * scale, 0.0f), glm::vec4(axis * scale, 0.0f), glm::vec4(z * scale, 0.0f),
                        glm::vec4(centre, 1.0f));
  // Regularity: every corner on the fitted hexagon.
  float worst = 0.0f;
  int worstCorner = 0;
  for (int k = 0; k < kRimCorners; ++k) {
    const glm::vec3 expected(fit.frame * glm::vec4(rimCorner(k), 1.0f));
    const float off = glm::length(corner[static_cast<std::size_t>(k)] - expected);
    if (!(off <= worst)) {
      worst = off;
      worstCorner = k;
    }
  }
  if (!(worst <= tolerance * std::max(1.0f, scale))) {
    fail("{} is not a regular hexagon (corner {} is {:.3g} off)", where, worstCorner, worst);
  }
  return fit;
}

/**
 * The quads next to each rim must lie on the fixed cone and face outwards: at every corner the normal of the
 * quads holding its rim edges, on the piece's side, is within `tolerance` radians of the fixed normal.
 */
void checkRimNormals(const std::string& where, const RawMesh& raw, const Topology& topo, const FittedRim& fit,
                     bool root, float tolerance) {
  const glm::mat3 linear(fit.frame);
  const glm::vec3 axis = glm::normalize(linear[1]);
  const glm::vec3 centre(fit.frame[3]);
  for (int k = 0; k < kRimCorners; ++k) {
    const std::uint32_t v = fit.corners[static_cast<std::size_t>(k)];
    glm::vec3 sum(0.0f);
    for (int side : {-1, 1}) {
      const std::uint32_t other =
          fit.corners[static_cast<std::size_t>((k + side + kRimCorners) % kRimCorners)];
      for (std::size_t q : topo.quadsOf[v]) {
        const auto& quad = raw.quads[q];
        if (std::find(quad.begin(), quad.end(), other) == quad.end()) {
          continue;
        }
        const glm::vec3 p0 = raw.positions[quad[0]];
        const glm::vec3 p1 = raw.positions[quad[1]];
        const glm::vec3 p2 = raw.positions[quad[2]];
        const glm::vec3 p3 = raw.positions[quad[3]];
        // Only the ring on the piece's side: above the root rim, below a leaf rim.
        const float height = glm::dot(0.25f * (p0 + p1 + p2 + p3) - centre, axis);
        if (root ? height <= 0.0f : height >= 0.0f) {
          continue;
        }
        const glm::vec3 area = glm::cross(p2 - p0, p3 - p1);
        if (glm::length(area) > 0.0f) {
          sum += glm::normalize(area);
        }
      }
    }
    const glm::vec3 expected = glm::normalize(linear * rimNormal(k));
    const float length = glm::length(sum);
    const float angle = length > 0.0f ? std::acos(std::clamp(glm::dot(sum / length, expected), -1.0f, 1.0f))
                                      : std::numbers::pi_v<float>;
    if (!(angle <= tolerance)) {
      fail("{}: wrong normals (at corner {} the quads next to the rim are {:.3g} rad off the fixed cone "
           "normal; they must continue the rim's cone and face outwards)",
           where, k, angle);
    }
  }
}

std::string rimLabel(bool fromBones, int rim) {
  if (fromBones) {
    return rim == 0 ? std::string("rim_root") : fmt::format("rim_leaf_{}", rim);
  }
  return rim == 0 ? std::string("root rim") : fmt::format("leaf rim {}", rim);
}

/** glTF's JSON text stores quads as triangle pairs. */
bool isGltf(const fs::path& file) {
  const std::string ext = lowerExtension(file);
  return ext == ".gltf" || ext == ".glb";
}

} // namespace

Piece importPiece(const fs::path& file, const ImportOptions& options) {
  const std::string name = file.filename().string();
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  // Join identical vertices (files store one per face corner); never triangulate: pieces are quads.
  const aiScene* scene = internal::readScene(importer, file, name, aiProcess_JoinIdenticalVertices);
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mRootNode == nullptr) {
    fail("{}: no mesh in the file", name);
  }
  const RawMesh raw = readMesh(*scene, name, isGltf(file), options);
  const Topology topo(raw);

  // Find the rims.
  std::vector<FoundRim> found;
  const bool fromBones = raw.hasRimBones;
  if (fromBones) {
    if (raw.groups.count(0) == 0 || raw.groups.at(0).vertices.empty()) {
      fail("{}: missing root rim (no vertices with weight over 0.5 on a bone 'rim_root')", name);
    }
    int expected = 0;
    for (const auto& [rim, group] : raw.groups) {
      if (rim != expected) {
        fail("{}: {} without {} (leaf rims are numbered 1, 2, … without gaps)", name, rimLabel(true, rim),
             rimLabel(true, expected));
      }
      ++expected;
      FoundRim f;
      f.name = rimLabel(true, rim);
      f.loop = loopOfGroup(fmt::format("{}: {}", name, f.name), group.vertices, topo);
      if (rim > 0 && group.frame) {
        f.boneFrame = group.frame;
      }
      found.push_back(std::move(f));
    }
  } else {
    FoundRim root;
    root.name = rimLabel(false, 0);
    root.loop = findRootByPosition(name, raw, options.tolerance);
    found.push_back(root);
    std::vector<std::vector<std::uint32_t>> loops = boundaryLoops(name, raw, topo);
    std::vector<std::vector<std::uint32_t>> leaves;
    for (auto& loop : loops) {
      std::size_t onRoot = 0;
      for (std::uint32_t v : loop) {
        onRoot += static_cast<std::size_t>(std::count(root.loop.begin(), root.loop.end(), v));
      }
      if (onRoot == loop.size() && loop.size() == static_cast<std::size_t>(kRimCorners)) {
        continue; // the root rim is open
      }
      if (loop.size() != static_cast<std::size_t>(kRimCorners) || onRoot > 0) {
        fail("{}: a boundary loop of {} vertices through {} is not a rim (the piece must be closed apart "
             "from its hexagonal rims)",
             name, loop.size(), vec3Text(raw.positions[loop[0]]));
      }
      leaves.push_back(std::move(loop));
    }
    if (leaves.size() > kMaxLeafRims) {
      fail("{}: {} leaf rims (at most {})", name, leaves.size(), kMaxLeafRims);
    }
    // Leaf rims in the order the face list first reaches them.
    auto reach = [&](const std::vector<std::uint32_t>& loop) {
      std::size_t first = std::numeric_limits<std::size_t>::max();
      for (std::uint32_t v : loop) {
        first = std::min(first, topo.firstUse[v]);
      }
      return first;
    };
    std::sort(leaves.begin(), leaves.end(),
              [&](const auto& a, const auto& b) { return reach(a) < reach(b); });
    for (std::size_t r = 0; r < leaves.size(); ++r) {
      FoundRim f;
      f.name = rimLabel(false, static_cast<int>(r + 1));
      f.loop = std::move(leaves[r]);
      found.push_back(std::move(f));
    }
  }
  // Rims must not share vertices.
  {
    std::unordered_map<std::uint32_t, std::size_t> owner;
    for (std::size_t r = 0; r < found.size(); ++r) {
      for (std::uint32_t v : found[r].loop) {
        const auto [it, inserted] = owner.emplace(v, r);
        if (!inserted) {
          fail("{}: {} and {} share the vertex at {}", name, found[it->second].name, found[r].name,
               vec3Text(raw.positions[v]));
        }
      }
    }
  }

  // Fit frames and check them.
  std::vector<FittedRim> fits;
  for (std::size_t r = 0; r < found.size(); ++r) {
    const std::string where = fmt::format("{}: {}", name, found[r].name);
    fits.push_back(r == 0 ? fitRoot(where, raw, topo, found[r].loop, options.tolerance)
                          : fitLeaf(where, raw, topo, found[r], options.tolerance));
  }
  for (std::size_t r = 0; r < found.size(); ++r) {
    checkRimNormals(fmt::format("{}: {}", name, found[r].name), raw, topo, fits[r], r == 0,
                    options.normalTolerance);
  }

  // Build the piece.
  Piece piece;
  piece.name = options.name.empty() ? file.stem().string() : options.name;
  piece.vertices.resize(raw.positions.size());
  for (std::size_t i = 0; i < raw.positions.size(); ++i) {
    piece.vertices[i].position = raw.positions[i];
    piece.vertices[i].u = raw.uvs[i].x;
    piece.vertices[i].v = raw.uvs[i].y;
  }
  piece.quads = raw.quads;
  piece.tileClass.assign(piece.quads.size(), 0);
  for (std::size_t r = 0; r < fits.size(); ++r) {
    Rim rim;
    rim.vertices = fits[r].corners;
    rim.frame = fits[r].frame;
    rim.joint = static_cast<int>(r);
    piece.rims.push_back(rim);
    piece.joints.push_back(Joint{rim.frame, static_cast<int>(r)});
    for (int k = 0; k < kRimCorners; ++k) {
      PieceVertex& v = piece.vertices[rim.vertices[static_cast<std::size_t>(k)]];
      v.rim = static_cast<int>(r);
      v.corner = k;
    }
  }
  piece.bearsFoliage = piece.rims.size() == 1;
  snapRims(piece);
  internal::blendInteriorWeights(piece);
  computeNormals(piece);
  // Interior normals as the file gives them (the artist's shading), averaged over a point's copies.
  if (raw.hasNormals) {
    for (std::size_t i = 0; i < piece.vertices.size(); ++i) {
      const float length = glm::length(raw.normals[i]);
      if (piece.vertices[i].rim < 0 && std::isfinite(length) && length > 1e-6f) {
        piece.vertices[i].normal = raw.normals[i] / length;
      }
    }
  }
  validatePiece(piece, name);
  return piece;
}

PieceSet loadPieceSet(const fs::path& folder, const ImportOptions& options) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    fail("{}: not a folder", folder.string());
  }
  static const std::array<const char*, 5> kExtensions = {".gltf", ".glb", ".obj", ".dae", ".fbx"};
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    const std::string ext = lowerExtension(entry.path());
    if (entry.is_regular_file(ec) &&
        std::find(kExtensions.begin(), kExtensions.end(), ext) != kExtensions.end()) {
      files.push_back(entry.path());
    }
  }
  if (ec) {
    fail("{}: cannot list the folder: {}", folder.string(), ec.message());
  }
  std::sort(files.begin(), files.end());
  PieceSet set = standardPieces();
  const std::size_t builtIn = set.size();
  std::vector<bool> replaced(builtIn, false);
  std::vector<bool> used(files.size(), false);
  // Replacements first, by extension preference.
  for (std::size_t p = 0; p < builtIn; ++p) {
    for (const char* ext : kExtensions) {
      for (std::size_t f = 0; f < files.size() && !replaced[p]; ++f) {
        if (files[f].stem().string() == set.pieces[p].name && lowerExtension(files[f]) == ext) {
          ImportOptions o = options;
          o.name = set.pieces[p].name;
          Piece piece = importPiece(files[f], o);
          if (piece.leafRims() != set.pieces[p].leafRims()) {
            fail("{}: replaces the built-in piece '{}', which has {} leaf rims, but has {}",
                 files[f].filename().string(), set.pieces[p].name, set.pieces[p].leafRims(),
                 piece.leafRims());
          }
          piece.bearsFoliage = set.pieces[p].bearsFoliage;
          set.pieces[p] = std::move(piece);
          replaced[p] = true;
          used[f] = true;
        }
      }
    }
  }
  for (std::size_t f = 0; f < files.size(); ++f) {
    const std::string stem = files[f].stem().string();
    if (used[f] || set.find(stem) >= 0) {
      continue; // another file of a built-in piece, or a second format of one already added
    }
    ImportOptions o = options;
    o.name = stem;
    set.pieces.push_back(importPiece(files[f], o));
  }
  return set;
}

void exportPieceObj(const Piece& piece, const fs::path& path) {
  std::string text =
      fmt::format("# Sylva tree piece '{}': {} vertices, {} quads, {} leaf rims (docs/trees.md)\n"
                  "o {}\n",
                  piece.name, piece.vertices.size(), piece.quads.size(), piece.leafRims(),
                  piece.name.empty() ? std::string("piece") : piece.name);
  for (const PieceVertex& v : piece.vertices) {
    text += fmt::format("v {:.9g} {:.9g} {:.9g}\n", v.position.x, v.position.y, v.position.z);
  }
  for (const PieceVertex& v : piece.vertices) {
    text += fmt::format("vt {:.9g} {:.9g}\n", v.u, v.v);
  }
  for (const PieceVertex& v : piece.vertices) {
    text += fmt::format("vn {:.9g} {:.9g} {:.9g}\n", v.normal.x, v.normal.y, v.normal.z);
  }
  for (const auto& q : piece.quads) {
    text += fmt::format("f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2} {3}/{3}/{3}\n", q[0] + 1, q[1] + 1, q[2] + 1,
                        q[3] + 1);
  }
  writeTextFile(path, text);
}

void exportPieceGltf(const Piece& piece, const fs::path& path) {
  const std::size_t n = piece.vertices.size();
  const std::size_t rims = piece.rims.size();
  std::vector<std::uint8_t> buffer;
  nlohmann::json views = nlohmann::json::array();
  nlohmann::json accessors = nlohmann::json::array();
  auto addView = [&](std::size_t offset, std::optional<int> target) {
    nlohmann::json view{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", buffer.size() - offset}};
    if (target) {
      view["target"] = *target;
    }
    views.push_back(view);
    return views.size() - 1;
  };
  auto addAccessor = [&](std::size_t view, int componentType, std::size_t count, const char* type) {
    accessors.push_back(
        {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}});
    return accessors.size() - 1;
  };
  constexpr int kFloat = 5126;
  constexpr int kUnsignedByte = 5121;
  constexpr int kUnsignedInt = 5125;
  constexpr int kArrayBuffer = 34962;
  constexpr int kElementArrayBuffer = 34963;

  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  std::size_t offset = buffer.size();
  for (const PieceVertex& v : piece.vertices) {
    appendBytes(buffer, &v.position, sizeof v.position);
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
  }
  const std::size_t position = addAccessor(addView(offset, kArrayBuffer), kFloat, n, "VEC3");
  accessors[position]["min"] = {lo.x, lo.y, lo.z};
  accessors[position]["max"] = {hi.x, hi.y, hi.z};
  offset = buffer.size();
  for (const PieceVertex& v : piece.vertices) {
    appendBytes(buffer, &v.normal, sizeof v.normal);
  }
  const std::size_t normal = addAccessor(addView(offset, kArrayBuffer), kFloat, n, "VEC3");
  offset = buffer.size();
  for (const PieceVertex& v : piece.vertices) {
    // glTF's texture space starts at the top left (v down); ours, as OBJ's and GL's, at the bottom left.
    const std::array<float, 2> uv{v.u, 1.0f - v.v};
    appendBytes(buffer, uv.data(), sizeof uv);
  }
  const std::size_t texcoord = addAccessor(addView(offset, kArrayBuffer), kFloat, n, "VEC2");
  // Skin joint 0 is the skeleton root `piece`; joint r + 1 is rim r.
  offset = buffer.size();
  for (const PieceVertex& v : piece.vertices) {
    const std::array<std::uint8_t, 4> joints{static_cast<std::uint8_t>(v.rim >= 0 ? v.rim + 1 : 0), 0, 0, 0};
    appendBytes(buffer, joints.data(), joints.size());
  }
  const std::size_t jointsAccessor = addAccessor(addView(offset, kArrayBuffer), kUnsignedByte, n, "VEC4");
  offset = buffer.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::array<float, 4> weights{1.0f, 0.0f, 0.0f, 0.0f};
    appendBytes(buffer, weights.data(), sizeof weights);
  }
  const std::size_t weightsAccessor = addAccessor(addView(offset, kArrayBuffer), kFloat, n, "VEC4");
  offset = buffer.size();
  for (const auto& q : piece.quads) {
    const std::array<std::uint32_t, 6> triangles{q[0], q[1], q[2], q[0], q[2], q[3]};
    appendBytes(buffer, triangles.data(), sizeof triangles);
  }
  const std::size_t indices =
      addAccessor(addView(offset, kElementArrayBuffer), kUnsignedInt, piece.quads.size() * 6, "SCALAR");
  offset = buffer.size();
  const glm::mat4 identity(1.0f);
  appendBytes(buffer, &identity, sizeof identity);
  for (const Rim& rim : piece.rims) {
    const glm::mat4 inverse = glm::inverse(rim.frame);
    appendBytes(buffer, &inverse, sizeof inverse);
  }
  const std::size_t inverseBind = addAccessor(addView(offset, std::nullopt), kFloat, rims + 1, "MAT4");

  const std::string meshName = piece.name.empty() ? std::string("piece") : piece.name;
  nlohmann::json nodes = nlohmann::json::array();
  nodes.push_back({{"name", meshName}, {"mesh", 0}, {"skin", 0}});
  nlohmann::json children = nlohmann::json::array();
  nlohmann::json joints = nlohmann::json::array({1});
  for (std::size_t r = 0; r < rims; ++r) {
    children.push_back(2 + r);
    joints.push_back(2 + r);
  }
  nodes.push_back({{"name", "piece"}, {"children", children}});
  for (std::size_t r = 0; r < rims; ++r) {
    nlohmann::json node{{"name", rimLabel(true, static_cast<int>(r))}};
    if (piece.rims[r].frame != identity) {
      node["matrix"] = matrixJson(piece.rims[r].frame);
    }
    nodes.push_back(node);
  }
  const nlohmann::json gltf{
      {"asset", {{"version", "2.0"}, {"generator", "Sylva (sylva::trees::exportPieceGltf)"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0, 1}}}}},
      {"nodes", nodes},
      {"meshes",
       {{{"name", meshName},
         {"primitives",
          {{{"attributes",
             {{"POSITION", position},
              {"NORMAL", normal},
              {"TEXCOORD_0", texcoord},
              {"JOINTS_0", jointsAccessor},
              {"WEIGHTS_0", weightsAccessor}}},
            {"indices", indices},
            {"mode", 4}}}}}}},
      {"skins",
       {{{"name", meshName + " rims"},
         {"joints", joints},
         {"skeleton", 1},
         {"inverseBindMatrices", inverseBind}}}},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers",
       {{{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}}}},
      {"extras", {{"sylvaPiece", meshName}, {"leafRims", piece.leafRims()}}}};
  writeTextFile(path, gltf.dump(1) + "\n");
}

} // namespace sylva::trees
