#include <sylva/trees/Export.hpp>

#include "internal/Gltf.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/trees/FarField.hpp>
#include <sylva/trees/Skeleton.hpp>
#include <sylva/trees/Tessellation.hpp>

#include <memory>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <optional>
#include <span>
#include <unistd.h>
#include <unordered_map>

namespace sylva::trees {
namespace {

namespace fs = std::filesystem;
using internal::GltfBuffer;
using internal::kGltfArrayBuffer;
using internal::kGltfElementArrayBuffer;
using internal::kGltfFloat;
using internal::kGltfUnsignedInt;
using internal::kGltfUnsignedShort;

constexpr int kMaxLevel = 64;

/** A piece vertex in the rest pose: world position and normal, global joints and weights. */
struct RestVertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  std::array<std::uint32_t, 4> joints{0, 0, 0, 0};
  glm::vec4 weights{1.0f, 0.0f, 0.0f, 0.0f};
};

float metresPerRimUnit(const Species& species, const TreeExportOptions& options) {
  return options.scale > 0.0f ? options.scale : species.trunkRadius;
}

/** Skins every vertex of `node` as shaders/trees/piece.vert does. */
void skinNode(const Piece& piece, const TreeNode& node, const std::vector<glm::mat4>& frames,
              std::vector<RestVertex>& out) {
  const auto global = [&](std::size_t j) {
    return j == 0 ? node.rootJoint : node.jointBase + static_cast<std::uint32_t>(j) - 1;
  };
  std::vector<glm::mat4> skin(piece.joints.size());
  skin[0] = frames[node.rootJoint] * rimRotation(node.rotation);
  for (std::size_t j = 1; j < piece.joints.size(); ++j) {
    skin[j] = frames[global(j)] * glm::inverse(piece.joints[j].bind);
  }
  out.resize(piece.vertices.size());
  for (std::size_t i = 0; i < piece.vertices.size(); ++i) {
    const PieceVertex& v = piece.vertices[i];
    RestVertex& r = out[i];
    if (v.rim >= 0) {
      const int corner = v.rim == 0 ? (v.corner + node.rotation) % kRimCorners : v.corner;
      const std::size_t joint = static_cast<std::size_t>(piece.rims[static_cast<std::size_t>(v.rim)].joint);
      const glm::mat4& f = frames[global(joint)];
      r.position = glm::vec3(f * glm::vec4(rimCorner(corner), 1.0f));
      r.normal = glm::normalize(glm::mat3(f) * rimNormal(corner));
      r.joints = {global(joint), 0, 0, 0};
      r.weights = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
      continue;
    }
    glm::vec3 p(0.0f);
    glm::vec3 n(0.0f);
    for (int k = 0; k < 4; ++k) {
      const float w = v.weights[k];
      if (w == 0.0f) {
        r.joints[static_cast<std::size_t>(k)] = 0;
        continue;
      }
      const glm::mat4& m = skin[v.joints[static_cast<std::size_t>(k)]];
      p += w * glm::vec3(m * glm::vec4(v.position, 1.0f));
      n += w * (glm::mat3(m) * v.normal);
      r.joints[static_cast<std::size_t>(k)] = global(v.joints[static_cast<std::size_t>(k)]);
    }
    r.position = p;
    r.normal = glm::normalize(n);
    r.weights = v.weights;
  }
}

/** Key of a grid point shared between quads of one piece instance: a corner or a point on an edge. */
struct GridKey {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  std::uint32_t step = 0;
  bool operator==(const GridKey&) const = default;
};
struct GridKeyHash {
  std::size_t operator()(const GridKey& k) const {
    return std::hash<std::uint64_t>()((std::uint64_t(k.a) << 32 | k.b) * 0x9E3779B97F4A7C15ULL ^ k.step);
  }
};

/** The four largest of the blended influences, renormalised to sum 1 (slot 0 absorbs the rounding). */
void blendInfluences(const std::array<const RestVertex*, 4>& corners, const std::array<float, 4>& w,
                     std::array<std::uint16_t, 4>& joints, glm::vec4& weights) {
  std::array<std::pair<float, std::uint32_t>, 16> all{};
  std::size_t count = 0;
  for (std::size_t c = 0; c < 4; ++c) {
    if (w[c] == 0.0f) {
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      const float x = w[c] * corners[c]->weights[k];
      if (x <= 0.0f) {
        continue;
      }
      const std::uint32_t j = corners[c]->joints[static_cast<std::size_t>(k)];
      std::size_t i = 0;
      while (i < count && all[i].second != j) {
        ++i;
      }
      if (i == count) {
        all[count++] = {0.0f, j};
      }
      all[i].first += x;
    }
  }
  std::sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(count), [](const auto& x, const auto& y) {
    return x.first > y.first || (x.first == y.first && x.second < y.second);
  });
  count = std::min<std::size_t>(count, 4);
  float sum = 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    sum += all[i].first;
  }
  joints = {0, 0, 0, 0};
  weights = glm::vec4(0.0f);
  float rest = 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    joints[i] = static_cast<std::uint16_t>(all[i].second);
    if (i > 0) {
      weights[static_cast<int>(i)] = all[i].first / sum;
      rest += weights[static_cast<int>(i)];
    }
  }
  weights.x = 1.0f - rest;
}

glm::vec2 bilinear(const std::array<glm::vec2, 4>& c, const std::array<float, 4>& w) {
  return w[0] * c[0] + w[1] * c[1] + w[2] * c[2] + w[3] * c[3];
}

/** Tessellates every quad of every piece instance at `level` into `lod`. */
void tessellate(const PieceSet& pieces, const TreeTopology& tree,
                const std::vector<std::vector<RestVertex>>& rest, const TreeExportOptions& options, int level,
                const std::string& where, TreeMeshLod& lod) {
  lod.level = level;
  const auto L = static_cast<std::uint32_t>(level);
  const float step = 1.0f / static_cast<float>(level);
  std::unordered_map<GridKey, std::uint32_t, GridKeyHash> shared;
  std::vector<std::uint32_t> grid((L + 1) * (L + 1));
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    const Piece& piece = pieces[static_cast<std::size_t>(tree.nodes[n].piece)];
    const std::vector<RestVertex>& verts = rest[n];
    shared.clear();
    for (std::size_t q = 0; q < piece.quads.size(); ++q) {
      const auto& quad = piece.quads[q];
      std::array<glm::vec3, 4> p{};
      std::array<glm::vec3, 4> nn{};
      std::array<const RestVertex*, 4> corners{};
      for (std::size_t c = 0; c < 4; ++c) {
        corners[c] = &verts[quad[c]];
        p[c] = corners[c]->position;
        nn[c] = corners[c]->normal;
      }
      QuadUvs uvs;
      if (options.barkUv) {
        uvs = options.barkUv(n, q);
        if (uvs.strips.empty() || uvs.strips.size() > 1024) {
          fail("{}: {} texture strips for quad {} of piece instance {} (1 … 1024)", where, uvs.strips.size(),
               q, n);
        }
      } else {
        // The piece's own (u, v), unwrapped across the seam where u goes round from 1 to 0.
        float top = 0.0f;
        for (std::size_t c = 0; c < 4; ++c) {
          top = std::max(top, piece.vertices[quad[c]].u);
        }
        std::array<glm::vec2, 4> uv{};
        for (std::size_t c = 0; c < 4; ++c) {
          const PieceVertex& v = piece.vertices[quad[c]];
          uv[c] = glm::vec2(v.u < top - 0.5f ? v.u + 1.0f : v.u, 1.0f - v.v);
        }
        uvs.strips.push_back(uv);
      }
      // Strips cut the quad's domain along s or t; each is an L × L grid, so the quad is (strips · L) × L.
      const auto strips = static_cast<std::uint32_t>(uvs.strips.size());
      const std::uint32_t cellsS = uvs.alongS ? L * strips : L;
      const std::uint32_t cellsT = uvs.alongS ? L : L * strips;
      // The grid point's key when it lies on the quad's boundary (shared with the neighbouring quad): edge
      // from corner `from` to `to`, `s` of its `cells` steps from `from`.
      auto edge = [&](std::uint32_t from, std::uint32_t to, std::uint32_t s, std::uint32_t cells) {
        const std::uint32_t a = quad[from];
        const std::uint32_t b = quad[to];
        if (s == 0) {
          return GridKey{a, a, 0};
        }
        if (s == cells) {
          return GridKey{b, b, 0};
        }
        return a < b ? GridKey{a, b, s} : GridKey{b, a, cells - s};
      };
      for (std::uint32_t strip = 0; strip < strips; ++strip) {
        const std::uint32_t firstS = uvs.alongS ? strip * L : 0;
        const std::uint32_t firstT = uvs.alongS ? 0 : strip * L;
        for (std::uint32_t j = 0; j <= L; ++j) {
          for (std::uint32_t i = 0; i <= L; ++i) {
            const std::uint32_t gs = firstS + i;
            const std::uint32_t gt = firstT + j;
            std::optional<GridKey> key;
            if (gt == 0) {
              key = edge(0, 1, gs, cellsS);
            } else if (gt == cellsT) {
              key = edge(3, 2, gs, cellsS);
            } else if (gs == 0) {
              key = edge(0, 3, gt, cellsT);
            } else if (gs == cellsS) {
              key = edge(1, 2, gt, cellsT);
            }
            // The same grid point computes the same (s, t) in every strip and quad that has it.
            const float s =
                gs == cellsS ? 1.0f : static_cast<float>(gs) * (1.0f / static_cast<float>(cellsS));
            const float t =
                gt == cellsT ? 1.0f : static_cast<float>(gt) * (1.0f / static_cast<float>(cellsT));
            const std::array<float, 4> w{(1.0f - s) * (1.0f - t), s * (1.0f - t), s * t, (1.0f - s) * t};
            const float ls = i == L ? 1.0f : static_cast<float>(i) * step;
            const float lt = j == L ? 1.0f : static_cast<float>(j) * step;
            const glm::vec2 texcoord = bilinear(
                uvs.strips[strip], {(1.0f - ls) * (1.0f - lt), ls * (1.0f - lt), ls * lt, (1.0f - ls) * lt});
            std::uint32_t index = 0;
            std::optional<std::uint32_t> same;
            if (key) {
              if (const auto it = shared.find(*key); it != shared.end()) {
                same = it->second;
              }
            }
            if (same && glm::all(glm::lessThanEqual(glm::abs(lod.uvs[*same] - texcoord), glm::vec2(1e-6f)))) {
              index = *same;
            } else {
              if (lod.positions.size() >= std::numeric_limits<std::uint32_t>::max()) {
                fail("{}: level {} makes over 2^32 vertices", where, level);
              }
              index = static_cast<std::uint32_t>(lod.positions.size());
              if (same) {
                // Same point, another texture coordinate: a copy of the shared vertex (watertight).
                lod.positions.push_back(lod.positions[*same]);
                lod.normals.push_back(lod.normals[*same]);
                lod.joints.push_back(lod.joints[*same]);
                lod.weights.push_back(lod.weights[*same]);
              } else {
                lod.positions.push_back(phongQuad(p, nn, s, t));
                lod.normals.push_back(phongQuadNormal(nn, s, t));
                std::array<std::uint16_t, 4> joints{};
                glm::vec4 weights{};
                blendInfluences(corners, w, joints, weights);
                lod.joints.push_back(joints);
                lod.weights.push_back(weights);
                if (key) {
                  shared.emplace(*key, index);
                }
              }
              lod.uvs.push_back(texcoord);
            }
            grid[j * (L + 1) + i] = index;
          }
        }
        for (std::uint32_t j = 0; j < L; ++j) {
          for (std::uint32_t i = 0; i < L; ++i) {
            const std::uint32_t a = grid[j * (L + 1) + i];
            const std::uint32_t b = grid[j * (L + 1) + i + 1];
            const std::uint32_t c = grid[(j + 1) * (L + 1) + i + 1];
            const std::uint32_t d = grid[(j + 1) * (L + 1) + i];
            lod.indices.insert(lod.indices.end(), {a, b, c, a, c, d});
          }
        }
      }
    }
  }
}

/** A similarity's translation, rotation and uniform scale. */
struct Trs {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  double scale = 1.0;

  glm::dmat4 matrix() const {
    glm::dmat4 m = glm::mat4_cast(rotation);
    m[0] *= scale;
    m[1] *= scale;
    m[2] *= scale;
    m[3] = glm::dvec4(translation, 1.0);
    return m;
  }
};

Trs decompose(const glm::dmat4& m) {
  Trs t;
  t.translation = glm::dvec3(m[3]);
  t.scale = std::cbrt(glm::determinant(glm::dmat3(m)));
  t.rotation = glm::normalize(glm::quat_cast(glm::dmat3(m) / t.scale));
  return t;
}

nlohmann::json vec3Json(const glm::dvec3& v) {
  return {v.x, v.y, v.z};
}

/** PNG bytes of an image (through a temporary file: sylva::savePng writes files). */
std::vector<std::uint8_t> pngBytes(const Image& image, const fs::path& forFile) {
  static std::atomic<unsigned> counter{0};
  const fs::path tmp = fs::temp_directory_path() /
                       fmt::format("sylva-export-{}-{}.png", static_cast<long>(::getpid()), counter++);
  try {
    Image copy = image.type() == PixelType::F32 ? image.converted(PixelType::U16) : image;
    savePng(tmp, copy);
  } catch (const Error& e) {
    fail("{}: cannot encode an image as PNG: {}", forFile.string(), e.what());
  }
  std::ifstream in(tmp, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  std::error_code ec;
  fs::remove(tmp, ec);
  if (bytes.empty()) {
    fail("{}: cannot encode an image as PNG", forFile.string());
  }
  return bytes;
}

/** Direction a cell of an octahedral atlas looks from (full sphere, y up). */
glm::vec3 octahedralDirection(int i, int j, int n) {
  glm::vec2 p((static_cast<float>(i) + 0.5f) / static_cast<float>(n) * 2.0f - 1.0f,
              (static_cast<float>(j) + 0.5f) / static_cast<float>(n) * 2.0f - 1.0f);
  float y = 1.0f - std::abs(p.x) - std::abs(p.y);
  if (y < 0.0f) {
    const glm::vec2 folded((1.0f - std::abs(p.y)) * (p.x >= 0.0f ? 1.0f : -1.0f),
                           (1.0f - std::abs(p.x)) * (p.y >= 0.0f ? 1.0f : -1.0f));
    p = folded;
  }
  return glm::normalize(glm::vec3(p.x, y, p.y));
}

void checkOptions(const TreeExportOptions& options, const TreeTopology& tree, const std::string& where) {
  if (options.levels.empty()) {
    fail("{}: needs at least one LOD level", where);
  }
  for (int l : options.levels) {
    if (l < 1 || l > kMaxLevel) {
      fail("{}: LOD level {} is out of range [1, {}]", where, l, kMaxLevel);
    }
  }
  if (!options.pose.empty() && options.pose.size() != tree.jointCount()) {
    fail("{}: pose has {} bends for {} joints", where, options.pose.size(), tree.jointCount());
  }
  if (!(std::isfinite(options.scale) && options.scale >= 0.0f)) {
    fail("{}: scale must be a finite number ≥ 0 metres per rim unit", where);
  }
  if (tree.jointCount() > 65535) {
    fail("{}: {} joints (at most 65,535 fit glTF's JOINTS_0)", where, tree.jointCount());
  }
  if (options.barkAtlas && options.barkAtlas->empty()) {
    fail("{}: the bark atlas is empty", where);
  }
  if (options.impostor) {
    if (options.impostor->image.empty()) {
      fail("{}: the impostor atlas is empty", where);
    }
    if (options.impostor->viewsPerSide < 1 || options.impostor->viewsPerSide > 64) {
      fail("{}: impostor views per side {} is out of range [1, 64]", where, options.impostor->viewsPerSide);
    }
    if (const std::optional<glm::vec4>& s = options.impostor->sphere;
        s && !(std::isfinite(s->x) && std::isfinite(s->y) && std::isfinite(s->z) && std::isfinite(s->w) &&
               s->w > 0.0f)) {
      fail("{}: the impostor sphere must be finite with a radius > 0", where);
    }
  }
}

} // namespace

TreeMesh buildTreeMesh(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                       const TreeExportOptions& options, const std::string& where) {
  checkOptions(options, tree, where);
  validate(tree, pieces, where);
  TreeMesh mesh;
  const float scale = metresPerRimUnit(species, options);
  jointFrames(pieces, tree, baseFrame(glm::vec3(0.0f), 0.0f, scale), options.pose, mesh.jointFrames);
  std::vector<std::vector<RestVertex>> rest(tree.nodes.size());
  for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
    skinNode(pieces[static_cast<std::size_t>(tree.nodes[n].piece)], tree.nodes[n], mesh.jointFrames, rest[n]);
  }
  for (int level : options.levels) {
    tessellate(pieces, tree, rest, options, level, where, mesh.lods.emplace_back());
  }
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (const glm::vec3& p : mesh.lods.front().positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  mesh.bounds = {lo, hi};
  return mesh;
}

TreeExportStats exportTreeGltf(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                               const fs::path& path, const TreeExportOptions& options) {
  const std::string where = path.string();
  const std::string ext = lowerExtension(path);
  if (ext != ".gltf" && ext != ".glb") {
    fail("{}: a glTF file must end in .gltf or .glb", where);
  }
  const TreeMesh mesh = buildTreeMesh(pieces, tree, species, options, where);
  const std::size_t jointCount = tree.jointCount();
  GltfBuffer buffer;
  TreeExportStats stats;
  stats.joints = jointCount;

  // Joint nodes: TRS of each joint relative to its parent, and the world transforms a reader composes from
  // them (double precision), whose inverses are the inverse bind matrices.
  std::vector<glm::dmat4> world(jointCount);
  std::vector<Trs> local(jointCount);
  for (std::size_t j = 0; j < jointCount; ++j) {
    const int parent = tree.jointParent[j];
    const glm::dmat4 frame(mesh.jointFrames[j]);
    if (parent < 0) {
      local[j] = decompose(frame);
      world[j] = local[j].matrix();
    } else {
      const glm::dmat4 parentFrame(mesh.jointFrames[static_cast<std::size_t>(parent)]);
      local[j] = decompose(glm::inverse(parentFrame) * frame);
      world[j] = world[static_cast<std::size_t>(parent)] * local[j].matrix();
    }
  }
  std::vector<float> inverseBind;
  inverseBind.reserve(jointCount * 16);
  for (std::size_t j = 0; j < jointCount; ++j) {
    glm::dmat4 inv = glm::inverse(world[j]);
    inv[0][3] = inv[1][3] = inv[2][3] = 0.0;
    inv[3][3] = 1.0;
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) {
        inverseBind.push_back(static_cast<float>(inv[c][r]));
      }
    }
  }
  const std::size_t ibmAccessor =
      buffer.addAccessor(buffer.addView(inverseBind.data(), inverseBind.size() * sizeof(float), std::nullopt),
                         kGltfFloat, jointCount, "MAT4");

  // Wind: per-joint springs as the renderer computes them for this tree at this placement and pose.
  JointWindTree windTree;
  windTree.topology = &tree;
  windTree.species = &species;
  windTree.base = mesh.jointFrames[0];
  windTree.pose = options.pose;
  validate(options.wind, where + ": wind");
  const JointWindRest windRest = buildJointWindRest(pieces, std::span(&windTree, 1), options.wind);

  // Materials and images.
  nlohmann::json images = nlohmann::json::array();
  nlohmann::json textures = nlohmann::json::array();
  nlohmann::json materials = nlohmann::json::array();
  nlohmann::json samplers = nlohmann::json::array();
  auto addImage = [&](const Image& image, const std::string& name, int wrap) {
    const std::vector<std::uint8_t> png = pngBytes(image, path);
    images.push_back({{"name", name},
                      {"mimeType", "image/png"},
                      {"bufferView", buffer.addView(png.data(), png.size(), std::nullopt)}});
    samplers.push_back({{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", wrap}, {"wrapT", wrap}});
    textures.push_back({{"source", images.size() - 1}, {"sampler", samplers.size() - 1}});
    return textures.size() - 1;
  };
  constexpr int kRepeat = 10497;
  constexpr int kClampToEdge = 33071;
  {
    nlohmann::json pbr{{"metallicFactor", 0.0}, {"roughnessFactor", 0.9}};
    if (options.barkAtlas) {
      pbr["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
      pbr["baseColorTexture"] = {
          {"index", addImage(*options.barkAtlas, "bark atlas", options.barkUv ? kClampToEdge : kRepeat)}};
    } else {
      pbr["baseColorFactor"] = {species.barkColour.r, species.barkColour.g, species.barkColour.b, 1.0};
    }
    materials.push_back({{"name", "bark"}, {"pbrMetallicRoughness", pbr}});
  }

  // LOD meshes.
  nlohmann::json meshes = nlohmann::json::array();
  for (const TreeMeshLod& lod : mesh.lods) {
    const std::size_t n = lod.positions.size();
    const glm::vec3 lo = std::accumulate(lod.positions.begin(), lod.positions.end(),
                                         glm::vec3(std::numeric_limits<float>::max()),
                                         [](glm::vec3 a, glm::vec3 b) { return glm::min(a, b); });
    const glm::vec3 hi = std::accumulate(lod.positions.begin(), lod.positions.end(),
                                         glm::vec3(std::numeric_limits<float>::lowest()),
                                         [](glm::vec3 a, glm::vec3 b) { return glm::max(a, b); });
    const std::size_t position = buffer.addAccessor(
        buffer.addView(lod.positions.data(), n * sizeof(glm::vec3), kGltfArrayBuffer), kGltfFloat, n, "VEC3");
    buffer.accessors[position]["min"] = {lo.x, lo.y, lo.z};
    buffer.accessors[position]["max"] = {hi.x, hi.y, hi.z};
    const std::size_t normal = buffer.addAccessor(
        buffer.addView(lod.normals.data(), n * sizeof(glm::vec3), kGltfArrayBuffer), kGltfFloat, n, "VEC3");
    const std::size_t texcoord = buffer.addAccessor(
        buffer.addView(lod.uvs.data(), n * sizeof(glm::vec2), kGltfArrayBuffer), kGltfFloat, n, "VEC2");
    const std::size_t joints =
        buffer.addAccessor(buffer.addView(lod.joints.data(), n * sizeof(lod.joints[0]), kGltfArrayBuffer),
                           kGltfUnsignedShort, n, "VEC4");
    const std::size_t weights = buffer.addAccessor(
        buffer.addView(lod.weights.data(), n * sizeof(glm::vec4), kGltfArrayBuffer), kGltfFloat, n, "VEC4");
    const std::size_t indices =
        buffer.addAccessor(buffer.addView(lod.indices.data(), lod.indices.size() * sizeof(std::uint32_t),
                                          kGltfElementArrayBuffer),
                           kGltfUnsignedInt, lod.indices.size(), "SCALAR");
    meshes.push_back({{"name", fmt::format("tree LOD{} (level {})", meshes.size(), lod.level)},
                      {"primitives",
                       {{{"attributes",
                          {{"POSITION", position},
                           {"NORMAL", normal},
                           {"TEXCOORD_0", texcoord},
                           {"JOINTS_0", joints},
                           {"WEIGHTS_0", weights}}},
                         {"indices", indices},
                         {"material", 0},
                         {"mode", 4}}}}});
    stats.vertices.push_back(n);
    stats.triangles.push_back(lod.indices.size() / 3);
  }

  // Nodes: LOD0, the joints (node 1 + j), the coarser LODs, the impostor.
  nlohmann::json nodes = nlohmann::json::array();
  const std::size_t lodCount = mesh.lods.size();
  nodes.push_back({{"name", "tree LOD0"},
                   {"mesh", 0},
                   {"skin", 0},
                   {"extras", {{"lod", {{"level", 0}, {"tessellation", mesh.lods[0].level}}}}}});
  std::vector<nlohmann::json> children(jointCount, nlohmann::json::array());
  for (std::size_t j = 1; j < jointCount; ++j) {
    children[static_cast<std::size_t>(tree.jointParent[j])].push_back(1 + j);
  }
  nlohmann::json skinJoints = nlohmann::json::array();
  for (std::size_t j = 0; j < jointCount; ++j) {
    const Trs& t = local[j];
    nlohmann::json node{{"name", fmt::format("joint_{}", j)},
                        {"translation", vec3Json(t.translation)},
                        {"rotation", {t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w}},
                        {"scale", vec3Json(glm::dvec3(t.scale))}};
    if (!children[j].empty()) {
      node["children"] = children[j];
    }
    const JointSpring& s = windRest.springs[j];
    if (s.frequency > 0.0f) {
      node["extras"] = {{"wind",
                         {{"frequencyHz", s.frequency},
                          {"dampingRatio", species.damping},
                          {"stiffnessNmPerRad", s.stiffness},
                          {"dampingNmsPerRad", s.damping},
                          {"inertiaKgM2", s.inertia},
                          {"massKg", s.mass},
                          {"frontalAreaM2", s.area},
                          {"order", s.order}}}};
    }
    nodes.push_back(node);
    skinJoints.push_back(1 + j);
  }
  nlohmann::json lodIds = nlohmann::json::array();
  for (std::size_t l = 1; l < lodCount; ++l) {
    lodIds.push_back(nodes.size());
    nodes.push_back({{"name", fmt::format("tree LOD{}", l)},
                     {"mesh", l},
                     {"skin", 0},
                     {"extras", {{"lod", {{"level", l}, {"tessellation", mesh.lods[l].level}}}}}});
  }
  if (options.impostor) {
    const ImpostorAtlas& atlas = *options.impostor;
    const int views = atlas.viewsPerSide;
    // The view that looks at the tree from +z (horizontal): the quad shows it.
    int bi = 0;
    int bj = 0;
    glm::vec3 dir(0.0f, 0.0f, 1.0f);
    if (atlas.layout == "hemi-octahedral") {
      // The most horizontal view towards +z (hemi-octahedral grid vertices; rows from the bottom).
      float best = -2.0f;
      for (int j = 0; j < views; ++j) {
        for (int i = 0; i < views; ++i) {
          const glm::vec3 d = impostorViewDirection({i, j}, views);
          if (d.z - std::abs(d.y) > best + 1e-6f) {
            best = d.z - std::abs(d.y);
            bi = i;
            bj = views - 1 - j; // rows of the image from the top
            dir = d;
          }
        }
      }
    } else if (atlas.layout == "octahedral") {
      float best = -2.0f;
      for (int j = 0; j < views; ++j) {
        for (int i = 0; i < views; ++i) {
          const glm::vec3 d = octahedralDirection(i, j, views);
          if (d.z > best + 1e-6f) {
            best = d.z;
            bi = i;
            bj = j;
            dir = d;
          }
        }
      }
    }
    const Bounds& b = mesh.bounds;
    float cx = 0.5f * (b.min.x + b.max.x);
    float cz = 0.5f * (b.min.z + b.max.z);
    float half = 0.5f * std::max(b.max.x - b.min.x, b.max.z - b.min.z);
    float y0 = b.min.y;
    float y1 = b.max.y;
    if (atlas.sphere) {
      // The views frame this sphere: the quad is its square, so the view shows at the tree's size.
      cx = atlas.sphere->x;
      cz = atlas.sphere->z;
      half = atlas.sphere->w;
      y0 = atlas.sphere->y - atlas.sphere->w;
      y1 = atlas.sphere->y + atlas.sphere->w;
    }
    const std::array<glm::vec3, 4> corners{glm::vec3(cx - half, y0, cz), glm::vec3(cx + half, y0, cz),
                                           glm::vec3(cx + half, y1, cz), glm::vec3(cx - half, y1, cz)};
    const float u0 = static_cast<float>(bi) / static_cast<float>(views);
    const float u1 = static_cast<float>(bi + 1) / static_cast<float>(views);
    const float v0 = static_cast<float>(bj) / static_cast<float>(views);
    const float v1 = static_cast<float>(bj + 1) / static_cast<float>(views);
    const std::array<glm::vec2, 4> uvs{glm::vec2(u0, v1), glm::vec2(u1, v1), glm::vec2(u1, v0),
                                       glm::vec2(u0, v0)};
    const std::array<glm::vec3, 4> normals{glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1),
                                           glm::vec3(0, 0, 1)};
    const std::array<std::uint32_t, 6> quad{0, 1, 2, 0, 2, 3};
    const std::size_t position = buffer.addAccessor(
        buffer.addView(corners.data(), sizeof corners, kGltfArrayBuffer), kGltfFloat, 4, "VEC3");
    buffer.accessors[position]["min"] = {cx - half, y0, cz};
    buffer.accessors[position]["max"] = {cx + half, y1, cz};
    const std::size_t normal = buffer.addAccessor(
        buffer.addView(normals.data(), sizeof normals, kGltfArrayBuffer), kGltfFloat, 4, "VEC3");
    const std::size_t texcoord =
        buffer.addAccessor(buffer.addView(uvs.data(), sizeof uvs, kGltfArrayBuffer), kGltfFloat, 4, "VEC2");
    const std::size_t indices = buffer.addAccessor(
        buffer.addView(quad.data(), sizeof quad, kGltfElementArrayBuffer), kGltfUnsignedInt, 6, "SCALAR");
    materials.push_back(
        {{"name", "impostor"},
         {"alphaMode", "MASK"},
         {"alphaCutoff", 0.5},
         {"doubleSided", true},
         {"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", addImage(atlas.image, "impostor atlas", kClampToEdge)}}},
           {"metallicFactor", 0.0},
           {"roughnessFactor", 1.0}}}});
    meshes.push_back(
        {{"name", "tree impostor"},
         {"primitives",
          {{{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", texcoord}}},
            {"indices", indices},
            {"material", materials.size() - 1},
            {"mode", 4}}}}});
    lodIds.push_back(nodes.size());
    nodes.push_back({{"name", "tree impostor"},
                     {"mesh", meshes.size() - 1},
                     {"extras",
                      {{"lod", {{"level", lodCount}}},
                       {"impostor",
                        {{"billboard", "camera-facing"},
                         {"pivot", {cx, b.min.y, cz}},
                         {"layout", atlas.layout},
                         {"viewsPerSide", views},
                         {"atlasSizePx", {atlas.image.width(), atlas.image.height()}},
                         {"viewSizePx", {atlas.image.width() / views, atlas.image.height() / views}},
                         {"quadView", {{"column", bi}, {"row", bj}, {"direction", {dir.x, dir.y, dir.z}}}},
                         {"octahedralConvention",
                          atlas.layout == "hemi-octahedral"
                              ? "cell (column i, row j from the bottom) looks from the direction that "
                                "decodes e = (i, j) / (n - 1) * 2 - 1 as x = (e.x + e.y) / 2, "
                                "z = (e.x - e.y) / 2, y = 1 - |x| - |z|, normalised (the upper hemisphere; "
                                "FarField.hpp hemiOctDecode), y up"
                              : "cell (column i, row j from the top) looks from the direction that decodes "
                                "p = ((i + 0.5) / n, (j + 0.5) / n) * 2 - 1 as (x, z), y = 1 - |x| - |z| "
                                "(folded when negative), y up"},
                         {"boundsMinM", {b.min.x, b.min.y, b.min.z}},
                         {"boundsMaxM", {b.max.x, b.max.y, b.max.z}}}}}}});
    if (atlas.sphere) {
      nodes.back()["extras"]["impostor"]["sphereM"] = {atlas.sphere->x, atlas.sphere->y, atlas.sphere->z,
                                                       atlas.sphere->w};
    }
  }
  if (!lodIds.empty()) {
    nlohmann::json coverage = nlohmann::json::array();
    for (std::size_t l = 0; l <= lodIds.size(); ++l) {
      coverage.push_back(0.5 * std::pow(0.3, static_cast<double>(l)));
    }
    nodes[0]["extensions"] = {{"MSFT_lod", {{"ids", lodIds}}}};
    nodes[0]["extras"]["MSFT_screencoverage"] = coverage;
  }

  const JointWindSettings& w = options.wind;
  nlohmann::json gltf{
      {"asset", {{"version", "2.0"}, {"generator", "Sylva (sylva::trees::exportTreeGltf)"}}},
      {"scene", 0},
      {"scenes",
       {{{"name", tree.species},
         {"nodes", {0, 1}},
         {"extras",
          {{"sylvaTree",
            {{"species", species.name},
             {"seed", tree.seed},
             {"pieces", tree.nodes.size()},
             {"joints", jointCount},
             {"metresPerRimUnit", metresPerRimUnit(species, options)},
             {"levels", options.levels},
             {"boundsMinM", {mesh.bounds.min.x, mesh.bounds.min.y, mesh.bounds.min.z}},
             {"boundsMaxM", {mesh.bounds.max.x, mesh.bounds.max.y, mesh.bounds.max.z}}}},
           {"wind",
            {{"model",
              "damped angular spring per joint (docs/trees.md, Wind on joints); joint node extras hold "
              "each spring"},
             {"youngModulusPa", species.youngModulus},
             {"woodDensityKgPerM3", species.woodDensity},
             {"dampingRatio", species.damping},
             {"airDensityKgPerM3", w.airDensity},
             {"dragCoefficient", w.dragCoefficient},
             {"foliageAreaRimRadii2", w.foliageArea},
             {"maxBendRad", w.maxBend},
             {"referenceFrequencyHz", w.referenceFrequency},
             {"referenceCantileverHz", w.referenceCantilever},
             {"frequencyExponent", w.frequencyExponent}}}}}}}},
      {"nodes", nodes},
      {"meshes", meshes},
      {"materials", materials},
      {"skins",
       {{{"name", "tree skeleton"},
         {"joints", skinJoints},
         {"skeleton", 1},
         {"inverseBindMatrices", ibmAccessor}}}},
      {"accessors", buffer.accessors},
      {"bufferViews", buffer.views}};
  if (!images.empty()) {
    gltf["images"] = images;
    gltf["textures"] = textures;
    gltf["samplers"] = samplers;
  }
  if (!lodIds.empty()) {
    gltf["extensionsUsed"] = {"MSFT_lod"};
  }
  stats.bytes = internal::writeGltf(path, std::move(gltf), buffer.bytes, ext == ".glb");
  return stats;
}

TreeExportStats exportTreeObj(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                              const fs::path& path, const TreeExportOptions& options) {
  const std::string where = path.string();
  if (lowerExtension(path) != ".obj") {
    fail("{}: an OBJ file must end in .obj", where);
  }
  TreeExportOptions first = options;
  first.levels.resize(1);
  first.impostor.reset();
  const TreeMesh mesh = buildTreeMesh(pieces, tree, species, first, where);
  const TreeMeshLod& lod = mesh.lods.front();
  const std::string stem = path.stem().string();
  const fs::path mtl = path.parent_path() / (stem + ".mtl");
  const std::string png = stem + "_bark.png";

  std::string material = fmt::format(
      "# Sylva tree bark (docs/trees.md)\nnewmtl bark\nKd {:.6g} {:.6g} {:.6g}\n"
      "Ka 0 0 0\nKs 0 0 0\nd 1\nillum 1\n",
      options.barkAtlas ? 1.0f : species.barkColour.r, options.barkAtlas ? 1.0f : species.barkColour.g,
      options.barkAtlas ? 1.0f : species.barkColour.b);
  if (options.barkAtlas) {
    material += "map_Kd " + png + "\n";
  }
  std::string text =
      fmt::format("# Sylva tree: species {}, seed {}, {} pieces, {} joints; rest pose, metres, y "
                  "up; tessellation level {} (docs/trees.md)\nmtllib {}.mtl\no tree\n",
                  species.name, tree.seed, tree.nodes.size(), tree.jointCount(), lod.level, stem);
  text.reserve(text.size() + lod.positions.size() * 96 + lod.indices.size() * 12);
  for (const glm::vec3& p : lod.positions) {
    text += fmt::format("v {:.9g} {:.9g} {:.9g}\n", p.x, p.y, p.z);
  }
  for (const glm::vec2& t : lod.uvs) {
    // OBJ's texture space starts at the bottom left.
    text += fmt::format("vt {:.9g} {:.9g}\n", t.x, 1.0f - t.y);
  }
  for (const glm::vec3& n : lod.normals) {
    text += fmt::format("vn {:.9g} {:.9g} {:.9g}\n", n.x, n.y, n.z);
  }
  text += "usemtl bark\n";
  for (std::size_t i = 0; i < lod.indices.size(); i += 3) {
    text += fmt::format("f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}\n", lod.indices[i] + 1, lod.indices[i + 1] + 1,
                        lod.indices[i + 2] + 1);
  }
  if (options.barkAtlas) {
    const Image& atlas = *options.barkAtlas;
    try {
      savePng(path.parent_path() / png,
              atlas.type() == PixelType::F32 ? atlas.converted(PixelType::U16) : atlas);
    } catch (const Error& e) {
      fail("{}: {}", where, e.what());
    }
  }
  writeTextFile(mtl, material);
  writeTextFile(path, text);
  TreeExportStats stats;
  stats.joints = tree.jointCount();
  stats.vertices.push_back(lod.positions.size());
  stats.triangles.push_back(lod.indices.size() / 3);
  stats.bytes = text.size();
  return stats;
}

void useRendererBark(TreeExportOptions& options, const BarkSet& bark, const PieceSet& pieces,
                     const TreeTopology& tree) {
  struct Mapping {
    BarkSet bark;
    BarkAtlas atlas;
    std::vector<PieceTiling> tilings;
  };
  auto mapping = std::make_shared<Mapping>();
  mapping->bark = bark;
  mapping->atlas = barkAtlas(bark);
  for (const Piece& piece : pieces.pieces) {
    mapping->tilings.push_back(pieceTiling(piece));
  }
  options.barkAtlas = mapping->atlas.image;
  options.barkUv = [mapping, &pieces, &tree](std::size_t node, std::size_t quad) {
    const TreeNode& n = tree.nodes[node];
    const Piece& piece = pieces[static_cast<std::size_t>(n.piece)];
    const PieceTiling& tiling = mapping->tilings[static_cast<std::size_t>(n.piece)];
    const std::uint32_t repeat = tileRepeat(tiling, quad, tileStretch(n.stretch));
    const int rotation = tiling.rotation[quad];
    // The tile's y runs along t (rotations 0 and 2) or s (1 and 3), against the strips' order for 1 and 2.
    QuadUvs uvs;
    uvs.alongS = rotation == 1 || rotation == 3;
    const bool reversed = rotation == 1 || rotation == 2;
    for (std::uint32_t strip = 0; strip < repeat; ++strip) {
      const std::uint32_t sub = reversed ? repeat - 1 - strip : strip;
      const std::uint32_t tile =
          barkTile(mapping->bark, piece, tiling, n.rootJoint, static_cast<std::uint32_t>(quad), sub, repeat);
      uvs.strips.push_back(barkAtlasUv(mapping->atlas, tile, rotation));
    }
    return uvs;
  };
}

} // namespace sylva::trees
