#include <sylva/trees/FarField.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/trees/Forest.hpp>
#include <sylva/trees/JointWind.hpp>
#include <sylva/trees/Tree.hpp>
#include <sylva/wind/Wind.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::trees {

glm::vec2 hemiOctEncode(glm::vec3 d) {
  d.y = std::max(d.y, 0.0f);
  const float sum = std::abs(d.x) + d.y + std::abs(d.z);
  if (!(sum > 0.0f)) {
    return glm::vec2(0.5f); // degenerate: straight up
  }
  const glm::vec2 p(d.x / sum, d.z / sum);
  return glm::vec2(p.x + p.y, p.x - p.y) * 0.5f + 0.5f;
}

glm::vec3 hemiOctDecode(glm::vec2 uv) {
  const glm::vec2 e = glm::clamp(uv, 0.0f, 1.0f) * 2.0f - 1.0f;
  const glm::vec2 p((e.x + e.y) * 0.5f, (e.x - e.y) * 0.5f);
  const float y = 1.0f - std::abs(p.x) - std::abs(p.y);
  return glm::normalize(glm::vec3(p.x, std::max(y, 0.0f), p.y));
}

glm::vec3 impostorViewDirection(glm::ivec2 cell, int views) {
  return hemiOctDecode(glm::vec2(cell) / static_cast<float>(std::max(views - 1, 1)));
}

ImpostorViews impostorViews(glm::vec3 direction, int views) {
  const int n = std::max(views, 2);
  const glm::vec2 f = hemiOctEncode(direction) * static_cast<float>(n - 1);
  const glm::ivec2 i = glm::clamp(glm::ivec2(glm::floor(f)), glm::ivec2(0), glm::ivec2(n - 2));
  const glm::vec2 t = glm::clamp(f - glm::vec2(i), 0.0f, 1.0f);
  ImpostorViews out;
  if (t.x + t.y <= 1.0f) {
    out.cells = {i, i + glm::ivec2(1, 0), i + glm::ivec2(0, 1)};
    out.weights = glm::vec3(1.0f - t.x - t.y, t.x, t.y);
  } else {
    out.cells = {i + glm::ivec2(1, 1), i + glm::ivec2(0, 1), i + glm::ivec2(1, 0)};
    out.weights = glm::vec3(t.x + t.y - 1.0f, 1.0f - t.x, 1.0f - t.y);
  }
  return out;
}

ImpostorBasis impostorBasis(glm::vec3 forward) {
  // cos(0.1°): only (almost) straight up uses the other hint.
  const glm::vec3 hint = forward.y > 0.9999985f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  ImpostorBasis b;
  b.forward = forward;
  b.right = glm::normalize(glm::cross(hint, forward));
  b.up = glm::cross(forward, b.right);
  return b;
}

glm::vec2 impostorAtlasPixel(glm::ivec2 cell, glm::vec2 local, const ImpostorLayout& layout) {
  return (glm::vec2(cell) + 0.5f + 0.5f * local) * static_cast<float>(layout.cell);
}

glm::vec3 yawRotate(glm::vec3 v, float yaw) {
  const float c = std::cos(yaw);
  const float s = std::sin(yaw);
  return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z};
}

glm::vec4 impostorLeanedSphere(glm::vec4 sphere, float baseY, glm::vec2 lean) {
  const float up = sphere.y - baseY;
  return {sphere.x + lean.x * up, sphere.y, sphere.z + lean.y * up, sphere.w * (1.0f + glm::length(lean))};
}

float impostorWindOffset(std::uint32_t id) {
  return static_cast<float>(lowbias32(id) >> 8) * (600.0f / 16777216.0f);
}

glm::vec2 impostorLean(const FarTree& tree, const ImpostorSway& sway, const gpu::WindUniforms& wind) {
  if (!(sway.perSpeedSquared > 0.0f) || !(wind.flow.z > 0.0f)) {
    return glm::vec2(0.0f);
  }
  gpu::WindUniforms w = wind;
  w.flow.w = w.flow.w + impostorWindOffset(tree.id);
  const glm::vec2 u = wind::windVelocity(w, glm::vec2(tree.position.x, tree.position.z));
  const glm::vec2 lean = sway.perSpeedSquared * glm::length(u) * u;
  const float length = glm::length(lean);
  return length > sway.maxLean ? lean * (sway.maxLean / length) : lean;
}

ImpostorSway calibrateImpostorSway(const Forest& forest, std::size_t tree, float speed, float seconds) {
  if (tree >= forest.trees.size()) {
    fail("impostor sway: tree {} of a forest of {}", tree, forest.trees.size());
  }
  if (!(speed > 0.0f) || !(seconds > 0.0f) || !std::isfinite(speed) || !std::isfinite(seconds)) {
    fail("impostor sway: wind {} m/s for {} s (both must be positive)", speed, seconds);
  }
  const ForestTree& t = forest.trees[tree];
  JointWindTree one;
  one.topology = &t.topology;
  one.species = &forest.species.at(static_cast<std::size_t>(t.species));
  one.base = t.base;
  one.pose = t.pose;
  const JointWindRest rest = buildJointWindRest(forest.pieces, std::span<const JointWindTree>(&one, 1));
  wind::WindSettings steady;
  steady.direction = glm::vec2(1.0f, 0.0f);
  steady.speed = speed;
  steady.gustStrength = 0.0f;
  steady.turbulence = 0.0f;
  JointWindState state(rest.jointCount());
  constexpr float kStep = 1.0f / 60.0f;
  const int steps = static_cast<int>(std::ceil(seconds / kStep));
  for (int i = 0; i < steps; ++i) {
    stepJointWindRange(rest, state, wind::toUniforms(steady, static_cast<float>(i) * kStep), kStep, 0,
                       rest.jointCount());
  }
  std::vector<glm::mat4> bent;
  std::vector<glm::mat4> still;
  forestJointFrames(rest, state, bent);
  forestJointFrames(rest, JointWindState(rest.jointCount()), still);
  const float baseY = still.front()[3].y;
  double dy = 0.0;
  double yy = 0.0;
  for (std::size_t j = 1; j < still.size(); ++j) {
    const double y = static_cast<double>(still[j][3].y - baseY);
    dy += static_cast<double>(bent[j][3].x - still[j][3].x) * y;
    yy += y * y;
  }
  ImpostorSway sway;
  if (yy > 0.0) {
    sway.perSpeedSquared = std::max(static_cast<float>(dy / yy), 0.0f) / (speed * speed);
  }
  return sway;
}

bool impostorVisible(const FarTree& tree, glm::vec4 sphere, const std::array<glm::vec4, 6>& planes,
                     glm::vec3 eye, glm::vec2 farRange, glm::vec2 lean) {
  const float h = tree.height;
  const float d = glm::distance(eye, tree.position + glm::vec3(0.0f, 0.5f * h, 0.0f));
  const float blend = tree.farOnly ? 1.0f : farBlend(d, farRange);
  const glm::vec4 leaned = impostorLeanedSphere(
      glm::vec4(tree.position + yawRotate(glm::vec3(sphere) * h, tree.yaw), sphere.w * h), tree.position.y,
      lean);
  const glm::vec3 centre(leaned);
  const float radius = leaned.w;
  if (blend <= 0.0f || glm::distance(eye, centre) < 2.0f * radius) {
    return false;
  }
  for (const glm::vec4& p : planes) {
    if (glm::dot(glm::vec3(p), centre) + p.w < -radius) {
      return false;
    }
  }
  return true;
}

std::vector<FarTree> farTrees(const Forest& forest) {
  std::vector<FarTree> out;
  out.reserve(forest.trees.size());
  for (std::size_t i = 0; i < forest.trees.size(); ++i) {
    const ForestTree& tree = forest.trees[i];
    // Exactly as TreeRenderer's tree centres, so both passes measure the same distance.
    const float scale = glm::length(glm::vec3(tree.base[0]));
    FarTree f;
    f.position = glm::vec3(tree.base[3]);
    f.height = treeStats(forest.pieces, tree.topology).height * scale;
    f.species = tree.species;
    f.id = static_cast<std::uint32_t>(i);
    f.yaw = std::atan2(-tree.base[0].z, tree.base[0].x);
    out.push_back(f);
  }
  return out;
}

std::vector<FarTree> farTreeField(const FarTreeFieldSettings& s, const terrain::HeightField* terrain) {
  if (s.count < 0 || s.count > 10000000) {
    fail("far trees.count: {} (0 … 10,000,000)", s.count);
  }
  if (!(std::isfinite(s.innerRadius) && std::isfinite(s.outerRadius) && s.innerRadius >= 0.0f &&
        s.outerRadius > s.innerRadius)) {
    fail("far trees: radii must be finite with 0 ≤ inner ({}) < outer ({})", s.innerRadius, s.outerRadius);
  }
  if (s.species < 1 || s.species > SYLVA_TREE_MAX_SPECIES) {
    fail("far trees.species: {} (1 … {})", s.species, SYLVA_TREE_MAX_SPECIES);
  }
  if (!(std::isfinite(s.minHeight) && std::isfinite(s.maxHeight) && s.minHeight > 0.0f &&
        s.maxHeight >= s.minHeight)) {
    fail("far trees: heights must be finite with 0 < min ({}) ≤ max ({})", s.minHeight, s.maxHeight);
  }
  Rng rng(hash64(s.seed ^ 0xfa27ee5ULL));
  std::vector<FarTree> out;
  out.reserve(static_cast<std::size_t>(s.count));
  const float r0 = s.innerRadius * s.innerRadius;
  const float r1 = s.outerRadius * s.outerRadius;
  for (int t = 0; t < s.count; ++t) {
    for (int attempt = 0; attempt < 40; ++attempt) {
      const float r = std::sqrt(rng.uniform(r0, r1));
      const float a = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
      const glm::vec2 p = s.centre + r * glm::vec2(std::cos(a), std::sin(a));
      float y = 0.0f;
      if (terrain != nullptr) {
        if (p.x < 0.0f || p.y < 0.0f || p.x > terrain->extentX() || p.y > terrain->extentZ()) {
          continue;
        }
        y = terrain::heightAt(*terrain, p.x, p.y) * s.verticalScale;
        if (!std::isfinite(y)) {
          continue;
        }
      }
      FarTree f;
      f.position = glm::vec3(p.x, y, p.y);
      f.species = static_cast<int>(rng.below(static_cast<std::uint32_t>(s.species)));
      f.height = rng.uniform(s.minHeight, s.maxHeight);
      f.yaw = rng.uniform(0.0f, 2.0f * std::numbers::pi_v<float>);
      f.id = s.firstId + static_cast<std::uint32_t>(out.size());
      f.farOnly = true;
      out.push_back(f);
      break;
    }
  }
  return out;
}

} // namespace sylva::trees
