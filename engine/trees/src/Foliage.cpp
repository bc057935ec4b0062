#include <sylva/trees/Foliage.hpp>
#include "internal/Finite.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include "internal/AssimpMath.hpp"
#include "internal/AssimpRead.hpp"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

namespace sylva::trees {
namespace {

using internal::finite;

namespace fs = std::filesystem;

/** A uniformly distributed unit vector. */
glm::vec3 randomUnit(Rng& rng) {
  const float z = rng.uniform(-1.0f, 1.0f);
  const float phi = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
  const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {s * std::cos(phi), z, s * std::sin(phi)};
}

/** Roughly normal in [−1.5, 1.5] (sum of three uniforms), deterministic and cheap. */
float bell(Rng& rng) {
  return rng.uniform() + rng.uniform() + rng.uniform() - 1.5f;
}

/** A unit vector perpendicular to unit `n`. */
glm::vec3 perpendicular(const glm::vec3& n) {
  const glm::vec3 a = std::abs(n.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  return glm::normalize(a - n * glm::dot(n, a));
}

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

} // namespace

void appendCard(LeafCloud& cloud, const LeafCard& card) {
  glm::vec3 n = card.normal;
  n = glm::length(n) > 0.0f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
  glm::vec3 up = card.up - n * glm::dot(n, card.up);
  up = glm::length(up) > 1e-6f ? glm::normalize(up) : perpendicular(n);
  const glm::vec3 right = glm::cross(up, n);
  const glm::vec3 du = right * (0.5f * card.size.x);
  const glm::vec3 dv = up * (0.5f * card.size.y);
  const LeafVertex c00{card.centre - du - dv, n, {0.0f, 0.0f}, card.tint};
  const LeafVertex c10{card.centre + du - dv, n, {1.0f, 0.0f}, card.tint};
  const LeafVertex c11{card.centre + du + dv, n, {1.0f, 1.0f}, card.tint};
  const LeafVertex c01{card.centre - du + dv, n, {0.0f, 1.0f}, card.tint};
  cloud.vertices.insert(cloud.vertices.end(), {c00, c10, c11, c00, c11, c01});
}

LeafCloud leafCloudFromCards(std::span<const LeafCard> cards) {
  LeafCloud cloud;
  cloud.vertices.reserve(cards.size() * 6);
  for (const LeafCard& card : cards) {
    appendCard(cloud, card);
  }
  return cloud;
}

void normaliseLeafCloud(LeafCloud& cloud, const std::string& where) {
  if (cloud.vertices.size() < 3) {
    fail("{}: no triangles", where);
  }
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(std::numeric_limits<float>::lowest());
  for (std::size_t i = 0; i < cloud.vertices.size(); ++i) {
    const glm::vec3& p = cloud.vertices[i].position;
    if (!finite(p)) {
      fail("{}: vertex {} is not finite", where, i);
    }
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // In double: the box of float coordinates near the float limit would overflow.
  const glm::dvec3 centre = 0.5 * (glm::dvec3(lo) + glm::dvec3(hi));
  double radius = 0.0;
  for (const LeafVertex& v : cloud.vertices) {
    radius = std::max(radius, glm::length(glm::dvec3(v.position) - centre));
  }
  if (!(radius > 1e-9 * std::max(1.0, glm::length(centre)))) {
    fail("{}: all vertices at one point", where);
  }
  for (LeafVertex& v : cloud.vertices) {
    glm::vec3 p = glm::vec3((glm::dvec3(v.position) - centre) / radius);
    // Rounding may leave the farthest vertex a hair outside the unit sphere.
    const float length = glm::length(p);
    if (length > 1.0f) {
      p /= length;
    }
    v.position = p;
  }
}

void validate(const LeafCloud& cloud, const std::string& where) {
  if (cloud.vertices.empty() || cloud.vertices.size() % 3 != 0) {
    fail("{}: {} vertices do not make whole triangles (need at least one)", where, cloud.vertices.size());
  }
  if (cloud.triangles() > 1000000) {
    fail("{}: {} triangles (at most 1,000,000)", where, cloud.triangles());
  }
  for (std::size_t i = 0; i < cloud.vertices.size(); ++i) {
    const LeafVertex& v = cloud.vertices[i];
    if (!finite(v.position) || !finite(v.normal) || !finite(v.uv) || !finite(v.tint)) {
      fail("{}: vertex {} is not finite", where, i);
    }
    if (std::abs(glm::length(v.normal) - 1.0f) > 1e-3f) {
      fail("{}: vertex {} has a normal of length {:.4g} (must be 1)", where, i, glm::length(v.normal));
    }
    if (glm::length(v.position) > 1.0f + 1e-4f) {
      fail("{}: vertex {} lies outside the unit sphere (|p| = {:.4g}); normalise the cloud", where, i,
           glm::length(v.position));
    }
  }
}

void validate(const LeafCloudSettings& s, const std::string& where) {
  if (s.leaves < 1 || s.leaves > 100000) {
    fail("{}.leaves: {} is out of range [1, 100000]", where, s.leaves);
  }
  if (!(std::isfinite(s.leafSize) && s.leafSize > 0.0f && s.leafSize <= 1.0f)) {
    fail("{}.leafSize: must be in (0, 1] cloud radii", where);
  }
  if (s.clusters < 1 || s.clusters > 1000) {
    fail("{}.clusters: {} is out of range [1, 1000]", where, s.clusters);
  }
  if (!(std::isfinite(s.shell) && s.shell >= 0.0f && s.shell < 1.0f)) {
    fail("{}.shell: must be in [0, 1)", where);
  }
  if (!(std::isfinite(s.tintVariation) && s.tintVariation >= 0.0f && s.tintVariation <= 1.0f)) {
    fail("{}.tintVariation: must be in [0, 1]", where);
  }
}

LeafCloud makeLeafCloud(const LeafCloudSettings& s) {
  validate(s, "leaf cloud");
  Rng rng(hash64(s.seed ^ 0x1eafc10dULL), hash64(s.seed + 3));
  struct Cluster {
    glm::vec3 centre;
    float spread;
  };
  std::vector<Cluster> clusters(static_cast<std::size_t>(s.clusters));
  for (Cluster& c : clusters) {
    const glm::vec3 d = randomUnit(rng);
    c.centre = d * rng.uniform(s.shell + 0.4f * (1.0f - s.shell), 0.92f);
    c.spread = rng.uniform(0.22f, 0.4f);
  }
  std::vector<LeafCard> cards(static_cast<std::size_t>(s.leaves));
  for (std::size_t i = 0; i < cards.size(); ++i) {
    // Most leaves in clumps (twig ends), one in four anywhere on the shell so the crown has no holes.
    const Cluster& c = clusters[i % clusters.size()];
    glm::vec3 p = i % 4 == 3 ? randomUnit(rng) * rng.uniform(s.shell, 1.0f)
                             : c.centre + glm::vec3(bell(rng), bell(rng), bell(rng)) * c.spread;
    float r = glm::length(p);
    const glm::vec3 radial = r > 1e-4f ? p / r : randomUnit(rng);
    // Keep the leaf on the shell and its corners inside the unit sphere (before normalisation).
    r = std::clamp(r, s.shell, std::max(s.shell, 1.0f - 0.75f * s.leafSize));
    p = radial * r;
    LeafCard& card = cards[i];
    card.centre = p;
    // Leaves face outwards and a little towards the sky, with scatter.
    glm::vec3 n = radial + glm::vec3(0.0f, 0.35f, 0.0f) + randomUnit(rng) * 0.65f;
    card.normal = glm::length(n) > 1e-4f ? glm::normalize(n) : radial;
    card.up = randomUnit(rng);
    const float size = s.leafSize * rng.uniform(0.75f, 1.2f);
    card.size = glm::vec2(size);
    const float brightness = 1.0f + s.tintVariation * rng.uniform(-1.0f, 1.0f);
    const float yellow = s.tintVariation * rng.uniform(-1.0f, 1.0f);
    card.tint = brightness * glm::vec3(1.0f + 0.5f * yellow, 1.0f, 1.0f - 0.6f * yellow);
  }
  LeafCloud cloud = leafCloudFromCards(cards);
  normaliseLeafCloud(cloud, "leaf cloud");
  return cloud;
}

void validate(const NeedleCloudSettings& s, const std::string& where) {
  if (s.shoots < 1 || s.shoots > 1000) {
    fail("{}.shoots: {} is out of range [1, 1000]", where, s.shoots);
  }
  if (s.needles < 1 || s.needles > 1000) {
    fail("{}.needles: {} is out of range [1, 1000]", where, s.needles);
  }
  if (!(std::isfinite(s.shootLength) && s.shootLength > 0.0f && s.shootLength <= 2.0f)) {
    fail("{}.shootLength: must be in (0, 2] cloud radii", where);
  }
  if (!(std::isfinite(s.needleLength) && s.needleLength > 0.0f && s.needleLength <= 1.0f)) {
    fail("{}.needleLength: must be in (0, 1] cloud radii", where);
  }
  if (!(std::isfinite(s.needleWidth) && s.needleWidth > 0.0f && s.needleWidth <= 1.0f)) {
    fail("{}.needleWidth: must be in (0, 1] cloud radii", where);
  }
  if (!(std::isfinite(s.tintVariation) && s.tintVariation >= 0.0f && s.tintVariation <= 1.0f)) {
    fail("{}.tintVariation: must be in [0, 1]", where);
  }
}

LeafCloud makeNeedleCloud(const NeedleCloudSettings& s) {
  validate(s, "needle cloud");
  Rng rng(hash64(s.seed ^ 0x6e656564ULL), hash64(s.seed + 5));
  std::vector<LeafCard> cards;
  cards.reserve(static_cast<std::size_t>(s.shoots) * static_cast<std::size_t>(s.needles));
  for (int shoot = 0; shoot < s.shoots; ++shoot) {
    // A shoot starts inside the sphere and reaches outwards, level or drooping a little.
    const glm::vec3 out = randomUnit(rng);
    const glm::vec3 start = out * rng.uniform(0.05f, 0.45f);
    glm::vec3 axis = out + randomUnit(rng) * 0.35f - glm::vec3(0.0f, 0.25f, 0.0f);
    axis = glm::length(axis) > 1e-4f ? glm::normalize(axis) : out;
    const float length = s.shootLength * rng.uniform(0.7f, 1.1f);
    // Two directions across the shoot.
    const glm::vec3 helper =
        std::abs(axis.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 side = glm::normalize(glm::cross(axis, helper));
    const glm::vec3 other = glm::cross(side, axis);
    const float shootTint = 1.0f + s.tintVariation * rng.uniform(-1.0f, 1.0f);
    for (int n = 0; n < s.needles; ++n) {
      const float along = (static_cast<float>(n) + rng.uniform()) / static_cast<float>(s.needles);
      // All round the shoot (a golden-angle spiral with jitter), leaning towards the shoot's tip.
      const float turn = 2.39996f * static_cast<float>(n) + rng.uniform(-0.3f, 0.3f);
      const glm::vec3 radial = std::cos(turn) * side + std::sin(turn) * other;
      const float lean = rng.uniform(0.35f, 0.85f); // 40–70° from the shoot
      const glm::vec3 dir = glm::normalize(std::sin(lean + 0.35f) * radial + std::cos(lean + 0.35f) * axis);
      const float needle = s.needleLength * rng.uniform(0.8f, 1.15f);
      LeafCard card;
      card.centre = start + axis * (along * length) + dir * (0.5f * needle);
      card.up = dir;
      // The card's face turned to the shoot's sides, so needles read as lines from most directions.
      glm::vec3 normal = glm::cross(dir, axis);
      card.normal = glm::length(normal) > 1e-4f ? glm::normalize(normal) : side;
      card.size = glm::vec2(s.needleWidth, needle);
      const float yellow = s.tintVariation * rng.uniform(-1.0f, 1.0f);
      // Younger needles towards the shoot's tip are lighter.
      const float brightness = shootTint * (0.85f + 0.3f * along);
      card.tint = brightness * glm::vec3(1.0f + 0.4f * yellow, 1.0f, 1.0f - 0.5f * yellow);
      cards.push_back(card);
    }
  }
  LeafCloud cloud = leafCloudFromCards(cards);
  normaliseLeafCloud(cloud, "needle cloud");
  return cloud;
}

LeafCloud loadLeafCloud(const fs::path& file, std::size_t maxTriangles) {
  const std::string name = file.filename().string();
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene =
      internal::readScene(importer, file, name, aiProcess_Triangulate | aiProcess_SortByPType);
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mRootNode == nullptr) {
    fail("{}: no triangles", name);
  }
  LeafCloud cloud;
  // Nodes with their global transforms, walked with an explicit stack (files may nest deeply).
  std::vector<std::pair<const aiNode*, glm::mat4>> stack{{scene->mRootNode, glm::mat4(1.0f)}};
  std::size_t visited = 0;
  while (!stack.empty()) {
    const auto [node, parent] = stack.back();
    stack.pop_back();
    if (++visited > 1000000) {
      fail("{}: more than 1,000,000 nodes", name);
    }
    const glm::mat4 global = parent * internal::toGlm(node->mTransformation);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(global)));
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const unsigned m = node->mMeshes[k];
      if (m >= scene->mNumMeshes || scene->mMeshes[m] == nullptr) {
        fail("{}: node '{}' refers to mesh {} of {}", name, node->mName.C_Str(), m, scene->mNumMeshes);
      }
      const aiMesh& mesh = *scene->mMeshes[m];
      if ((mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) {
        continue;
      }
      if (!mesh.HasTextureCoords(0)) {
        fail("{}: mesh {} has no texture coordinates", name, m);
      }
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) {
          continue;
        }
        if (cloud.triangles() >= maxTriangles) {
          fail("{}: more than {} triangles", name, maxTriangles);
        }
        LeafVertex corners[3];
        for (unsigned c = 0; c < 3; ++c) {
          const unsigned i = face.mIndices[c];
          if (i >= mesh.mNumVertices) {
            fail("{}: mesh {} face {} refers to vertex {} of {}", name, m, f, i, mesh.mNumVertices);
          }
          const aiVector3D& p = mesh.mVertices[i];
          const aiVector3D& t = mesh.mTextureCoords[0][i];
          LeafVertex& v = corners[c];
          v.position = glm::vec3(global * glm::vec4(p.x, p.y, p.z, 1.0f));
          v.uv = glm::vec2(t.x, t.y);
          if (!finite(glm::vec3(p.x, p.y, p.z)) || !finite(v.position) || !finite(v.uv)) {
            fail("{}: vertex {} of mesh {} is not finite", name, i, m);
          }
          v.normal = glm::vec3(0.0f);
          if (mesh.HasNormals()) {
            const aiVector3D& n = mesh.mNormals[i];
            const glm::vec3 world = normalMatrix * glm::vec3(n.x, n.y, n.z);
            const float length = glm::length(world);
            if (std::isfinite(length) && length > 1e-20f) {
              v.normal = world / length;
            }
          }
          if (mesh.HasVertexColors(0)) {
            const aiColor4D& col = mesh.mColors[0][i];
            const glm::vec3 tint(col.r, col.g, col.b);
            v.tint = finite(tint) ? glm::clamp(tint, glm::vec3(0.0f), glm::vec3(4.0f)) : glm::vec3(1.0f);
          }
        }
        const glm::vec3 faceNormal =
            glm::cross(corners[1].position - corners[0].position, corners[2].position - corners[0].position);
        const float area = glm::length(faceNormal);
        for (LeafVertex& v : corners) {
          if (v.normal == glm::vec3(0.0f)) {
            // No usable normal in the file: the triangle's own (any unit vector for a degenerate one).
            v.normal = std::isfinite(area) && area > 0.0f ? faceNormal / area : glm::vec3(0.0f, 0.0f, 1.0f);
          }
        }
        cloud.vertices.insert(cloud.vertices.end(), std::begin(corners), std::end(corners));
      }
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) {
      if (node->mChildren[c] != nullptr) {
        stack.emplace_back(node->mChildren[c], global);
      }
    }
  }
  if (cloud.vertices.empty()) {
    fail("{}: no triangles", name);
  }
  normaliseLeafCloud(cloud, name);
  validate(cloud, name);
  return cloud;
}

Image makeLeafImage(int size) {
  if (size < 8 || size > 4096) {
    fail("leaf image: size {} is out of range [8, 4096]", size);
  }
  Image image(size, size, 4, PixelType::U8);
  const float px = 1.0f / static_cast<float>(size);
  for (int y = 0; y < size; ++y) {
    // v runs up the leaf: row 0 (the top of the image) is the tip.
    const float v = 1.0f - (static_cast<float>(y) + 0.5f) * px;
    for (int x = 0; x < size; ++x) {
      const float u = (static_cast<float>(x) + 0.5f) * px - 0.5f;
      const float au = std::abs(u);
      // Blade from v = 0.1 to 0.97: ovate, widest a third of the way up; a petiole below it.
      const float s = (v - 0.1f) / 0.87f;
      const float half =
          s > 0.0f && s < 1.0f
              ? 0.4f * std::pow(std::sin(std::numbers::pi_v<float> * s), 0.75f) * (1.1f - 0.45f * s)
              : 0.0f;
      const bool blade = au < half;
      const bool petiole = v > 0.02f && v <= 0.12f && au < 0.018f;
      if (!blade && !petiole) {
        continue; // transparent black
      }
      // Base green, lighter midrib and veins (running up and out at 40°), darker towards the rim.
      float shade = 1.0f;
      if (blade) {
        const float edge = au / std::max(half, 1e-3f);
        shade *= 1.0f - 0.25f * edge * edge;
        const float vein = std::abs(std::fmod(v - 0.8f * au + 4.0f, 0.11f) - 0.055f);
        if (au < 0.012f) {
          shade = 1.35f;
        } else if (vein < 0.008f && edge < 0.9f) {
          shade *= 1.18f;
        }
      }
      const glm::vec3 colour = glm::clamp(glm::vec3(0.36f, 0.55f, 0.22f) * shade, 0.0f, 1.0f);
      image.set(x, y, 0, colour.r);
      image.set(x, y, 1, colour.g);
      image.set(x, y, 2, colour.b);
      image.set(x, y, 3, 1.0f);
    }
  }
  return image;
}

Image loadLeafImage(const fs::path& file) {
  const Image raw = loadImage(file);
  if (raw.channels() != 2 && raw.channels() != 4) {
    fail("{}: a leaf texture needs an alpha channel (have {} channels)", file.filename().string(),
         raw.channels());
  }
  const Image image = raw.type() == PixelType::U8 ? raw : raw.converted(PixelType::U8);
  if (image.channels() == 4) {
    return image;
  }
  Image rgba(image.width(), image.height(), 4, PixelType::U8);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        rgba.set(x, y, c, image.get(x, y, 0));
      }
      rgba.set(x, y, 3, image.get(x, y, 1));
    }
  }
  return rgba;
}

glm::vec3 leafImageMean(const Image& image) {
  if (image.empty() || image.channels() != 4 || image.type() != PixelType::U8) {
    fail("leaf texture: needs an 8-bit RGBA image (have {} channels, {})", image.channels(),
         pixelTypeName(image.type()));
  }
  glm::dvec3 sum(0.0);
  std::size_t n = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (image.get(x, y, 3) >= 0.5f) {
        sum += glm::dvec3(srgbToLinear(image.get(x, y, 0)), srgbToLinear(image.get(x, y, 1)),
                          srgbToLinear(image.get(x, y, 2)));
        ++n;
      }
    }
  }
  if (n == 0) {
    return glm::vec3(1.0f);
  }
  return glm::vec3(sum / static_cast<double>(n));
}

float foliageDepthT(float z, float zCentre, float radius) {
  return (z - (zCentre - radius)) / (2.0f * radius);
}

std::uint8_t encodeFoliageDepth(float t) {
  const float c = std::clamp(std::isfinite(t) ? t : 1.0f, 0.0f, 1.0f);
  // floor(x + 0.5), not round(): GLSL's round() may go either way at .5, floor is exact in both languages.
  return static_cast<std::uint8_t>(1.0f + std::floor(kFoliageDepthSteps * c + 0.5f));
}

float decodeFoliageDepth(std::uint8_t alpha) {
  return alpha == 0 ? -1.0f : (static_cast<float>(alpha) - 1.0f) / kFoliageDepthSteps;
}

FoliageBasis foliageBasis(glm::vec3 forward, glm::vec3 up) {
  FoliageBasis b;
  b.forward = glm::normalize(forward);
  glm::vec3 right = glm::cross(b.forward, up);
  if (!(glm::length(right) > 1e-6f)) {
    right = glm::cross(b.forward, std::abs(b.forward.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f)
                                                               : glm::vec3(1.0f, 0.0f, 0.0f));
  }
  b.right = glm::normalize(right);
  b.up = glm::cross(b.right, b.forward);
  return b;
}

glm::mat4 foliageBakeMatrix(const FoliageBasis& b) {
  // Rows: clip x = p·right, clip y = p·up, clip z = p·forward (ndc z = 2t − 1), w = 1.
  glm::mat4 m(0.0f);
  for (int c = 0; c < 3; ++c) {
    m[c][0] = b.right[c];
    m[c][1] = b.up[c];
    m[c][2] = b.forward[c];
  }
  m[3][3] = 1.0f;
  return m;
}

glm::vec3 foliageQuadPoint(const FoliageBasis& b, glm::vec3 centre, float radius, glm::vec2 xy) {
  return centre + radius * (xy.x * b.right + xy.y * b.up - b.forward);
}

glm::vec3 foliageFragmentPoint(glm::vec3 quadPoint, glm::vec3 camera, glm::vec3 forward, float radius,
                               float t) {
  const glm::vec3 r = glm::normalize(quadPoint - camera);
  // dot(r, −n) with n = −forward, the billboard's normal towards the camera.
  return quadPoint + r * (2.0f * radius * t / glm::dot(r, forward));
}

float foliageFragmentDepth(glm::vec3 quadPoint, glm::vec3 camera, glm::vec3 forward, float radius, float t,
                           const glm::mat4& viewProj) {
  const glm::vec4 clip =
      viewProj * glm::vec4(foliageFragmentPoint(quadPoint, camera, forward, radius, t), 1.0f);
  return 0.5f * clip.z / clip.w + 0.5f;
}

void validate(const FoliageSettings& s, const std::string& where) {
  if (s.textureSize < 16 || s.textureSize > 4096) {
    fail("{}.textureSize: {} is out of range [16, 4096] texels", where, s.textureSize);
  }
  auto positive = [&](float v, const char* field) {
    if (!(std::isfinite(v) && v > 0.0f && v <= 1000.0f)) {
      fail("{}.{}: must be a finite number in (0, 1000]", where, field);
    }
  };
  positive(s.radiusScale, "radiusScale");
  positive(s.minRadius, "minRadius");
  positive(s.maxRadius, "maxRadius");
  if (s.maxRadius < s.minRadius) {
    fail("{}.maxRadius: {} is below minRadius {}", where, s.maxRadius, s.minRadius);
  }
  if (!(std::isfinite(s.sizeVariation) && s.sizeVariation >= 0.0f && s.sizeVariation <= 0.9f)) {
    fail("{}.sizeVariation: must be in [0, 0.9]", where);
  }
  if (!(std::isfinite(s.rotationVariation) && s.rotationVariation >= 0.0f &&
        s.rotationVariation <= std::numbers::pi_v<float>)) {
    fail("{}.rotationVariation: must be in [0, pi] radians", where);
  }
  if (!(std::isfinite(s.lift) && s.lift >= -1.0f && s.lift <= 1.0f)) {
    fail("{}.lift: must be in [-1, 1] radii", where);
  }
  validate(s.cloud, where + ".cloud");
  validate(s.needles, where + ".needles");
}

bool carriesLeaves(const Piece& piece, const TreeNode& node, const Species& species) {
  return piece.bearsFoliage || (species.leafOrder > 0 && node.order >= species.leafOrder && node.parent >= 0);
}

std::vector<FoliageAnchor> foliageAnchors(const Forest& forest, const FoliageSettings& settings) {
  validate(settings, "foliage");
  std::vector<gpu::JointFrame> frames;
  forestFrames(forest, {}, frames);
  std::vector<glm::vec4> spheres;
  for (const Piece& piece : forest.pieces.pieces) {
    spheres.push_back(pieceTableEntry(piece).sphere);
  }
  std::vector<FoliageAnchor> out;
  for (std::size_t ti = 0; ti < forest.trees.size(); ++ti) {
    const ForestTree& tree = forest.trees[ti];
    const auto speciesIndex = static_cast<std::size_t>(std::max(tree.species, 0));
    const Species noSpecies;
    const Species& species = speciesIndex < forest.species.size() ? forest.species[speciesIndex] : noSpecies;
    for (const TreeNode& node : tree.topology.nodes) {
      const auto type = static_cast<std::size_t>(node.piece);
      if (!carriesLeaves(forest.pieces[type], node, species)) {
        continue;
      }
      FoliageAnchor a;
      a.joint = forest.jointOffset[ti] + node.rootJoint;
      // The species' leaf density keeps this share of its clusters, the same ones at any season (a cluster
      // stays while its hash is under the density, so thinning only ever removes).
      if (species.leafDensity < 1.0f) {
        const std::uint64_t h =
            hash64(static_cast<std::uint64_t>(a.joint) * 0xd6e8feb86659fd93ULL ^ 0x1eaff411ULL);
        if (static_cast<float>(h >> 40) / 16777216.0f >= species.leafDensity) {
          continue;
        }
      }
      a.tree = static_cast<std::uint32_t>(ti);
      a.species = static_cast<std::uint32_t>(std::max(tree.species, 0));
      const gpu::JointFrame& f = frames[a.joint];
      // Metres per rim unit: the length of the frame's first column (a similarity).
      const float scale = glm::length(glm::vec3(f.x.x, f.y.x, f.z.x));
      const glm::vec4 sphere = spheres[type];
      Rng rng(
          hash64(settings.seed ^ hash64(static_cast<std::uint64_t>(a.joint) * 0x9e3779b97f4a7c15ULL + ti)));
      const float cluster = a.species < forest.species.size() ? forest.species[a.species].leafCluster : 0.0f;
      const float base = cluster > 0.0f ? cluster
                                        : std::clamp(settings.radiusScale * sphere.w * scale,
                                                     settings.minRadius, settings.maxRadius);
      a.radius = base * (1.0f + settings.sizeVariation * rng.uniform(-1.0f, 1.0f));
      a.rotation = settings.rotationVariation * rng.uniform(-1.0f, 1.0f);
      // A stretched piece's middle moves up its axis with it.
      const glm::vec3 middle(sphere.x, sphere.y * node.stretch, sphere.z);
      const glm::vec3 centre = glm::vec3(rimRotation(node.rotation) * glm::vec4(middle, 1.0f));
      a.offset = centre + glm::vec3(0.0f, scale > 0.0f ? settings.lift * a.radius / scale : 0.0f, 0.0f);
      out.push_back(a);
    }
  }
  return out;
}

gpu::FoliageAnchorGpu packAnchor(const FoliageAnchor& a) {
  gpu::FoliageAnchorGpu g{};
  g.place = glm::vec4(a.offset, a.radius);
  g.spin = glm::vec4(std::cos(a.rotation), std::sin(a.rotation), 0.0f, 0.0f);
  g.info = glm::uvec4(a.joint, a.tree, a.species, 0u);
  return g;
}

glm::vec3 anchorCentre(const FoliageAnchor& a, std::span<const gpu::JointFrame> frames) {
  const gpu::JointFrame& f = frames[a.joint];
  const glm::vec4 p(a.offset, 1.0f);
  return {glm::dot(f.x, p), glm::dot(f.y, p), glm::dot(f.z, p)};
}

} // namespace sylva::trees
