#include <sylva/trees/Forest.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/FarField.hpp>
#include <sylva/wind/Wind.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

namespace sylva::trees {
namespace {

ForestTree makeTree(const Forest& forest, int species, std::uint64_t seed, glm::vec3 position, float yaw) {
  const Species& s = forest.species[static_cast<std::size_t>(species)];
  ForestTree t;
  t.species = species;
  t.topology = generateTree(forest.pieces, s, seed);
  Rng rng(hash64(seed ^ 0x5ca1eULL));
  const float radius = s.trunkRadius * (1.0f + s.sizeVariation * rng.uniform(-1.0f, 1.0f));
  // Sink the foot a little so it meets sloping ground.
  t.base = baseFrame(position - glm::vec3(0.0f, 0.15f * radius, 0.0f), yaw, radius);
  t.pose = randomPose(t.topology, s, seed);
  t.phase = rng.uniform(0.0f, 60.0f);
  return t;
}

} // namespace

void Forest::index() {
  jointOffset.resize(trees.size());
  std::size_t next = 0;
  for (std::size_t t = 0; t < trees.size(); ++t) {
    jointOffset[t] = static_cast<std::uint32_t>(next);
    next += trees[t].topology.jointCount();
  }
  jointCount = next;
}

void validate(const ForestSettings& s, const std::string& where) {
  if (s.species.empty()) {
    fail("{}.species: needs at least one species", where);
  }
  if (s.count < 0 || s.count > 1000000) {
    fail("{}.count: {} is out of range [0, 1000000]", where, s.count);
  }
  if (!(std::isfinite(s.spacing) && s.spacing >= 0.0f && s.spacing <= 1000.0f)) {
    fail("{}.spacing: must be a finite number in [0, 1000] metres", where);
  }
  if (!(std::isfinite(s.maxSlope) && s.maxSlope >= 0.0f && s.maxSlope <= 90.0f)) {
    fail("{}.maxSlope: must be in [0, 90] degrees", where);
  }
  if (!(std::isfinite(s.autumn) && s.autumn >= 0.0f && s.autumn <= 1.0f)) {
    fail("{}.autumn: must be in [0, 1] (0 summer, 1 full autumn colour)", where);
  }
  if (!(std::isfinite(s.leafFall) && s.leafFall >= 0.0f && s.leafFall <= 1.0f)) {
    fail("{}.leafFall: must be in [0, 1] (0 every leaf, 1 bare deciduous crowns)", where);
  }
  if (std::isinf(s.minHeight) || std::isinf(s.maxHeight)) {
    fail("{}.minHeight/maxHeight: must be finite", where);
  }
  if (!(std::isfinite(s.regionRadius) && s.regionRadius >= 0.0f && std::isfinite(s.regionCentre.x) &&
        std::isfinite(s.regionCentre.y))) {
    fail("{}.region: centre and radius must be finite, radius ≥ 0 metres", where);
  }
  if (!(std::isfinite(s.verticalScale) && s.verticalScale > 0.0f)) {
    fail("{}.verticalScale: must be a finite number > 0", where);
  }
  if (!(std::isfinite(s.clusterSize) && s.clusterSize > 0.0f) ||
      !(std::isfinite(s.bare) && s.bare >= 0.0f && s.bare < 1.0f)) {
    fail("{}.clusterSize/bare: cluster size must be > 0 metres and bare in [0, 1)", where);
  }
  if (!s.speciesWeights.empty()) {
    if (s.speciesWeights.size() != s.species.size()) {
      fail("{}.speciesWeights: {} weights for {} species", where, s.speciesWeights.size(), s.species.size());
    }
    for (float w : s.speciesWeights) {
      if (!(std::isfinite(w) && w > 0.0f)) {
        fail("{}.speciesWeights: each weight must be a finite number > 0, got {}", where, w);
      }
    }
  }
  if (!s.densityMap.empty() &&
      (s.densityWidth < 1 || s.densityHeight < 1 ||
       s.densityMap.size() != static_cast<std::size_t>(s.densityWidth) * s.densityHeight)) {
    fail("{}.densityMap: {} values for a {}×{} map", where, s.densityMap.size(), s.densityWidth,
         s.densityHeight);
  }
}

namespace {

/** Index i with probability weights[i] / Σ weights, for `u` uniform in [0, 1). */
std::uint32_t weightedPick(const std::vector<float>& weights, float u) {
  float total = 0.0f;
  for (float w : weights) {
    total += w;
  }
  float at = u * total;
  for (std::size_t i = 0; i + 1 < weights.size(); ++i) {
    if (at < weights[i]) {
      return static_cast<std::uint32_t>(i);
    }
    at -= weights[i];
  }
  return static_cast<std::uint32_t>(weights.size() - 1);
}

/** Bilinear value of the density map at normalised footprint coordinates (u, v) in [0, 1]. */
float densityAt(const ForestSettings& s, float u, float v) {
  const float x = std::clamp(u, 0.0f, 1.0f) * static_cast<float>(s.densityWidth - 1);
  const float y = std::clamp(v, 0.0f, 1.0f) * static_cast<float>(s.densityHeight - 1);
  const int x0 = std::min(static_cast<int>(x), s.densityWidth - 1);
  const int y0 = std::min(static_cast<int>(y), s.densityHeight - 1);
  const int x1 = std::min(x0 + 1, s.densityWidth - 1);
  const int y1 = std::min(y0 + 1, s.densityHeight - 1);
  const float fx = x - static_cast<float>(x0);
  const float fy = y - static_cast<float>(y0);
  auto at = [&](int i, int j) { return s.densityMap[static_cast<std::size_t>(j) * s.densityWidth + i]; };
  return (at(x0, y0) * (1.0f - fx) + at(x1, y0) * fx) * (1.0f - fy) +
         (at(x0, y1) * (1.0f - fx) + at(x1, y1) * fx) * fy;
}

} // namespace

Forest placeForest(const terrain::HeightField& terrain, const ForestSettings& settings) {
  validate(settings, "forest");
  Forest forest;
  forest.pieces = standardPieces();
  for (const std::string& name : settings.species) {
    forest.species.push_back(resolveSpecies(name));
    forest.species.back().leafColour = seasonalLeafColour(forest.species.back(), settings.autumn);
    forest.species.back().leafDensity = seasonalLeafDensity(forest.species.back(), settings.leafFall);
  }
  Rng rng(hash64(settings.seed ^ 0xf0e57ULL));
  const float cell = std::max(settings.spacing, 0.5f);
  std::unordered_map<std::int64_t, std::vector<glm::vec2>> grid;
  auto key = [&](int i, int j) {
    return (static_cast<std::int64_t>(i) << 32) ^ static_cast<std::uint32_t>(j);
  };
  const float cosMax = std::cos(settings.maxSlope * std::numbers::pi_v<float> / 180.0f);
  const int attempts = settings.count * 40;
  for (int a = 0; a < attempts && static_cast<int>(forest.trees.size()) < settings.count; ++a) {
    glm::vec2 p(rng.uniform(0.0f, terrain.extentX()), rng.uniform(0.0f, terrain.extentZ()));
    if (settings.regionRadius > 0.0f) {
      // Uniform in the disc, then clamped to the footprint.
      const float r = settings.regionRadius * std::sqrt(rng.uniform());
      const float a = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
      p = glm::clamp(settings.regionCentre + r * glm::vec2(std::cos(a), std::sin(a)), glm::vec2(0.0f),
                     glm::vec2(terrain.extentX(), terrain.extentZ()));
    }
    const float yaw = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
    const std::uint32_t pick = settings.speciesWeights.empty()
                                   ? rng.below(static_cast<std::uint32_t>(forest.species.size()))
                                   : weightedPick(settings.speciesWeights, rng.uniform());
    if (!settings.densityMap.empty() &&
        rng.uniform() >= densityAt(settings, p.x / terrain.extentX(), p.y / terrain.extentZ())) {
      continue;
    }
    const float h = terrain::heightAt(terrain, p.x, p.y) * settings.verticalScale;
    if (std::isnan(h) || (!std::isnan(settings.minHeight) && h < settings.minHeight) ||
        (!std::isnan(settings.maxHeight) && h > settings.maxHeight)) {
      continue;
    }
    const glm::vec3 flat = terrain::normalAt(terrain, p.x, p.y);
    const glm::vec3 n =
        glm::normalize(glm::vec3(flat.x * settings.verticalScale, flat.y, flat.z * settings.verticalScale));
    if (!(n.y >= cosMax)) {
      continue;
    }
    if (settings.bare > 0.0f) {
      const float d = 0.5f + 0.5f * wind::valueNoise(glm::vec3(p / settings.clusterSize, 0.5f),
                                                     static_cast<std::uint32_t>(settings.seed));
      if (d < settings.bare) {
        continue;
      }
    }
    const int ci = static_cast<int>(std::floor(p.x / cell));
    const int cj = static_cast<int>(std::floor(p.y / cell));
    bool free = true;
    for (int dj = -1; dj <= 1 && free; ++dj) {
      for (int di = -1; di <= 1 && free; ++di) {
        const auto it = grid.find(key(ci + di, cj + dj));
        if (it == grid.end()) {
          continue;
        }
        for (const glm::vec2& q : it->second) {
          if (glm::length(q - p) < settings.spacing) {
            free = false;
            break;
          }
        }
      }
    }
    if (!free) {
      continue;
    }
    grid[key(ci, cj)].push_back(p);
    const std::uint64_t seed = hash64(settings.seed * 1000003ULL + forest.trees.size());
    forest.trees.push_back(makeTree(forest, static_cast<int>(pick), seed, glm::vec3(p.x, h, p.y), yaw));
  }
  forest.index();
  return forest;
}

Forest gridForest(const std::vector<std::string>& species, int side, float spacing, std::uint64_t seed) {
  std::vector<Species> resolved;
  for (const std::string& name : species) {
    resolved.push_back(resolveSpecies(name));
  }
  return gridForestOf(resolved, side, spacing, seed);
}

Forest gridForestOf(const std::vector<Species>& species, int side, float spacing, std::uint64_t seed) {
  Forest forest;
  forest.pieces = standardPieces();
  for (const Species& s : species) {
    validate(s, "forest: species '" + s.name + "'");
    forest.species.push_back(s);
  }
  if (forest.species.empty()) {
    fail("forest: needs at least one species");
  }
  const float offset = 0.5f * spacing * static_cast<float>(side - 1);
  for (int j = 0; j < side; ++j) {
    for (int i = 0; i < side; ++i) {
      const std::uint64_t s = hash64(seed * 7919ULL + static_cast<std::uint64_t>(j * side + i));
      const glm::vec3 p(static_cast<float>(i) * spacing - offset, 0.0f,
                        static_cast<float>(j) * spacing - offset);
      const int kind = (j * side + i) % static_cast<int>(forest.species.size());
      forest.trees.push_back(makeTree(forest, kind, s, p, static_cast<float>(s % 6283) * 0.001f));
    }
  }
  forest.index();
  return forest;
}

PackedInstances packInstances(const Forest& forest) {
  PackedInstances out;
  const std::size_t types = forest.pieces.size();
  out.first.assign(types, 0);
  out.count.assign(types, 0);
  for (const ForestTree& t : forest.trees) {
    for (const TreeNode& n : t.topology.nodes) {
      out.count[static_cast<std::size_t>(n.piece)] += 1;
    }
  }
  std::uint32_t total = 0;
  for (std::size_t p = 0; p < types; ++p) {
    out.first[p] = total;
    total += out.count[p];
  }
  out.instances.resize(total);
  std::vector<std::uint32_t> cursor = out.first;
  for (std::size_t ti = 0; ti < forest.trees.size(); ++ti) {
    const ForestTree& t = forest.trees[ti];
    const std::uint32_t offset = forest.jointOffset[ti];
    for (const TreeNode& n : t.topology.nodes) {
      const auto type = static_cast<std::size_t>(n.piece);
      // The stretch's reach along the root axis, model units in 8.8 fixed point rounded up (culling bounds).
      const float reach = std::ceil(stretchReach(forest.pieces[type], n) * 256.0f);
      const auto reachBits = static_cast<std::uint32_t>(std::clamp(reach, 0.0f, 65535.0f));
      out.instances[cursor[type]++].joints = glm::uvec4(
          offset + n.rootJoint, offset + n.jointBase,
          static_cast<std::uint32_t>(n.rotation) | (static_cast<std::uint32_t>(n.piece) << 4) |
              (tileStretch(n.stretch) << 8) | (reachBits << 16),
          static_cast<std::uint32_t>(ti) | (static_cast<std::uint32_t>(std::min(t.species, 255)) << 24));
    }
  }
  return out;
}

gpu::JointFrame packFrame(const glm::mat4& m) {
  return gpu::JointFrame{glm::vec4(m[0][0], m[1][0], m[2][0], m[3][0]),
                         glm::vec4(m[0][1], m[1][1], m[2][1], m[3][1]),
                         glm::vec4(m[0][2], m[1][2], m[2][2], m[3][2])};
}

void forestFrames(const Forest& forest, std::span<const glm::vec2> extraBends,
                  std::vector<gpu::JointFrame>& out) {
  out.resize(forest.jointCount);
  std::vector<glm::mat4> frames;
  std::vector<glm::vec2> bends;
  for (std::size_t ti = 0; ti < forest.trees.size(); ++ti) {
    const ForestTree& t = forest.trees[ti];
    const std::uint32_t offset = forest.jointOffset[ti];
    bends = t.pose;
    bends.resize(t.topology.jointCount(), glm::vec2(0.0f));
    if (!extraBends.empty()) {
      for (std::size_t j = 0; j < bends.size(); ++j) {
        bends[j] += extraBends[offset + j];
      }
    }
    jointFrames(forest.pieces, t.topology, t.base, bends, frames);
    for (std::size_t j = 0; j < frames.size(); ++j) {
      out[offset + j] = packFrame(frames[j]);
    }
  }
}

} // namespace sylva::trees

namespace sylva::trees {
namespace {

glm::mat4 inverseSimilarity(const glm::mat4& m) {
  return glm::inverse(m);
}

glm::vec3 framePoint(const gpu::JointFrame& f, glm::vec3 p) {
  const glm::vec4 p1(p, 1.0f);
  return glm::vec3(glm::dot(f.x, p1), glm::dot(f.y, p1), glm::dot(f.z, p1));
}

} // namespace

gpu::TreePieceGpu pieceTableEntry(const Piece& piece) {
  gpu::TreePieceGpu entry{};
  const Bounds b = pieceBounds(piece);
  const glm::vec3 centre = 0.5f * (b.min + b.max);
  float radius = 0.0f;
  for (const PieceVertex& v : piece.vertices) {
    radius = std::max(radius, glm::length(v.position - centre));
  }
  // Phong tessellation bulges out by at most a fraction of the edge length: a 10 % margin.
  entry.sphere = glm::vec4(centre, radius * 1.1f);
  for (std::size_t j = 0; j < piece.joints.size() && j < SYLVA_TREE_MAX_PIECE_JOINTS; ++j) {
    entry.inverseBind[j] = packFrame(inverseSimilarity(piece.joints[j].bind));
  }
  return entry;
}

JointWindRest forestWindRest(const Forest& forest) {
  std::vector<JointWindTree> list;
  list.reserve(forest.trees.size());
  for (const ForestTree& t : forest.trees) {
    JointWindTree w;
    w.topology = &t.topology;
    w.species = &forest.species[static_cast<std::size_t>(t.species)];
    w.base = t.base;
    w.pose = t.pose;
    w.timeOffset = t.phase;
    list.push_back(w);
  }
  return buildJointWindRest(forest.pieces, list);
}

Aabb forestBounds(const Forest& forest) {
  std::vector<gpu::JointFrame> frames;
  forestFrames(forest, {}, frames);
  Aabb bounds{glm::vec3(0.0f), glm::vec3(0.0f)};
  float tallest = 0.0f;
  for (std::size_t t = 0; t < forest.trees.size(); ++t) {
    const float foot = forest.trees[t].base[3].y;
    const std::size_t first = forest.jointOffset[t];
    for (std::size_t j = first; j < first + forest.trees[t].topology.jointCount(); ++j) {
      const glm::vec3 p(frames[j].x.w, frames[j].y.w, frames[j].z.w);
      bounds.min = j == 0 ? p : glm::min(bounds.min, p);
      bounds.max = j == 0 ? p : glm::max(bounds.max, p);
      tallest = std::max(tallest, p.y - foot);
    }
  }
  if (!frames.empty()) {
    const float margin = 0.5f * tallest + 2.0f;
    bounds.min -= glm::vec3(margin);
    bounds.max += glm::vec3(margin);
  }
  return bounds;
}

glm::vec2 sizeCullTerms(float fovY, float orthoHeight, int height, float minPixels) {
  if (!(minPixels > 0.0f) || height <= 0) {
    return glm::vec2(0.0f);
  }
  if (orthoHeight > 0.0f) {
    return glm::vec2(0.0f, minPixels * 2.0f * orthoHeight / static_cast<float>(height));
  }
  const float focal = static_cast<float>(height) / (2.0f * std::tan(0.5f * fovY));
  return glm::vec2(minPixels / focal, 0.0f);
}

std::vector<std::vector<std::uint32_t>>
cullInstances(const PackedInstances& packed, std::span<const gpu::TreePieceGpu> pieces,
              std::span<const gpu::JointFrame> frames, const std::array<glm::vec4, 6>& planes,
              glm::vec3 camera, float drawDistance, float slack, glm::vec2 sizeCull, glm::vec2 widthCull,
              std::span<const glm::vec4> treeCentres, glm::vec2 farRange) {
  std::vector<std::vector<std::uint32_t>> out(pieces.size());
  const bool far = farRange.y > farRange.x && !treeCentres.empty();
  for (std::size_t i = 0; i < packed.instances.size(); ++i) {
    const glm::uvec4 inst = packed.instances[i].joints;
    if (far) {
      const glm::vec4 c = treeCentres[inst.w & 0xffffffu];
      const float d = glm::length(camera - (glm::vec3(c) + glm::vec3(0.0f, 0.5f * c.w, 0.0f)));
      if (farBlend(d, farRange) >= 1.0f) {
        continue;
      }
    }
    const std::uint32_t type = SYLVA_TREE_INSTANCE_TYPE(inst.z);
    const gpu::TreePieceGpu& piece = pieces[type];
    const gpu::JointFrame& root = frames[inst.x];
    const glm::vec3 c(piece.sphere);
    const float scale = glm::length(glm::vec3(root.x.x, root.y.x, root.z.x));
    // A stretched piece reaches `reach` further up its axis: centre the sphere half-way and widen it by half.
    const float reach = static_cast<float>(SYLVA_TREE_INSTANCE_REACH(inst.z)) / 256.0f;
    const glm::vec3 centre = framePoint(root, glm::vec3(0.0f, c.y + 0.5f * reach, 0.0f));
    const float radius = (piece.sphere.w + glm::length(glm::vec2(c.x, c.z)) + 0.5f * reach) * scale * slack;
    bool inside = true;
    for (const glm::vec4& p : planes) {
      if (glm::dot(glm::vec3(p), centre) + p.w < -radius) {
        inside = false;
        break;
      }
    }
    const float distance = glm::length(centre - camera);
    if (inside && drawDistance > 0.0f && distance - radius > drawDistance) {
      inside = false;
    }
    if (inside && 2.0f * radius < sizeCull.x * distance + sizeCull.y) {
      inside = false;
    }
    if (inside && 2.0f * scale < widthCull.x * distance + widthCull.y) {
      inside = false;
    }
    if (inside) {
      out[type].push_back(static_cast<std::uint32_t>(i));
    }
  }
  return out;
}

} // namespace sylva::trees
