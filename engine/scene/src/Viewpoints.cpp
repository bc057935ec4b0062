#include <sylva/scene/Viewpoints.hpp>

#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/trees/Tree.hpp>

#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::scene {

glm::vec2 ballDropPoint(const terrain::HeightField& terrain, const grass::GrassField& field,
                        const render::Camera& camera, float radius) {
  const glm::vec2 centre(camera.position.x, camera.position.z);
  glm::vec2 best = centre;
  float bestSlope = -1.0f;
  for (float dz = -radius; dz <= radius; dz += 2.0f) {
    for (float dx = -radius; dx <= radius; dx += 2.0f) {
      const glm::vec2 p = centre + glm::vec2(dx, dz);
      if (glm::length(p - centre) > radius || p.x < 0.0f || p.y < 0.0f || p.x > terrain.extentX() ||
          p.y > terrain.extentZ() || field.density().at(p.x, p.y) < 0.6f) {
        continue;
      }
      const glm::vec3 n = terrain::normalAt(terrain, p.x, p.y);
      const float slope = std::acos(std::clamp(n.y, -1.0f, 1.0f)) * 57.29578f;
      if (slope <= 25.0f && slope > bestSlope) {
        bestSlope = slope;
        best = p;
      }
    }
  }
  return best;
}

render::Camera ballCamera(const terrain::HeightField& t, const Aabb& bounds, glm::vec2 drop, float fovY) {
  const glm::vec3 n = terrain::normalAt(t, drop.x, drop.y);
  glm::vec2 downhill(n.x, n.z);
  downhill = glm::length(downhill) > 1e-3f ? glm::normalize(downhill) : glm::vec2(1.0f, 0.0f);
  // Downhill and a little to the side, so the balls roll past at an angle.
  const glm::vec2 side(-downhill.y, downhill.x);
  const glm::vec2 eye = drop + downhill * 9.0f + side * 2.5f;
  const glm::vec2 look = drop + downhill * 4.0f;
  render::Camera camera;
  camera.position = glm::vec3(eye.x, terrain::heightAt(t, eye.x, eye.y) + 1.8f, eye.y);
  camera.target = glm::vec3(look.x, terrain::heightAt(t, look.x, look.y), look.y);
  camera.fovY = fovY;
  render::fitClipPlanes(camera, bounds);
  camera.nearPlane = kGrassNearPlane;
  return camera;
}

render::Camera grassCamera(const terrain::HeightField& t, const Aabb& bounds, float maxHeight,
                           const grass::GrassField& field, float fovY, float windDirectionDegrees) {
  // The densest grass on a coarse grid over the middle half of the terrain (ties: nearest the centre).
  glm::vec2 best(0.5f * t.extentX(), 0.5f * t.extentZ());
  float bestScore = -1.0f;
  for (int j = 0; j <= 24; ++j) {
    for (int i = 0; i <= 24; ++i) {
      const glm::vec2 p(t.extentX() * (0.25f + 0.5f * i / 24.0f), t.extentZ() * (0.25f + 0.5f * j / 24.0f));
      float d = 0.0f;
      for (int k = 0; k < 9; ++k) {
        d += field.density().at(p.x + 6.0f * static_cast<float>(k % 3 - 1),
                                p.y + 6.0f * static_cast<float>(k / 3 - 1));
      }
      const glm::vec3 n = terrain::normalAt(t, p.x, p.y);
      const float score =
          d -
          0.01f * glm::length(p - 0.5f * glm::vec2(t.extentX(), t.extentZ())) / std::max(t.extentX(), 1.0f) -
          2.0f * (1.0f - n.y);
      if (score > bestScore) {
        bestScore = score;
        best = p;
      }
    }
  }
  const float a = glm::radians(windDirectionDegrees + 35.0f);
  const glm::vec2 dir(std::cos(a), std::sin(a));
  const glm::vec2 ahead = best + dir * 25.0f;
  render::Camera camera;
  camera.position = glm::vec3(best.x, terrain::heightAt(t, best.x, best.y) + 1.7f, best.y);
  camera.target = glm::vec3(ahead.x, terrain::heightAt(t, ahead.x, ahead.y) - 1.0f, ahead.y);
  if (std::isnan(camera.position.y) || std::isnan(camera.target.y)) {
    camera.position.y = maxHeight + 1.7f;
    camera.target.y = maxHeight;
  }
  camera.fovY = fovY;
  render::fitClipPlanes(camera, bounds);
  camera.nearPlane = kGrassNearPlane;
  return camera;
}

render::Camera forestCamera(const terrain::HeightField& field, float exaggeration, const render::Camera& base,
                            const trees::Forest& forest, float fovY) {
  render::Camera camera = base;
  camera.fovY = fovY;
  if (forest.trees.empty()) {
    return camera;
  }
  // The tree nearest the footprint's centre.
  const glm::vec2 centre(field.extentX() * 0.5f, field.extentZ() * 0.5f);
  std::size_t best = 0;
  float bestDistance = 1e30f;
  for (std::size_t i = 0; i < forest.trees.size(); ++i) {
    const glm::vec4& at = forest.trees[i].base[3];
    const float d = glm::length(glm::vec2(at.x, at.z) - centre);
    if (d < bestDistance) {
      bestDistance = d;
      best = i;
    }
  }
  // Its height from the joints at rest (the crown's pieces reach a little past the last joints).
  std::vector<gpu::JointFrame> frames;
  trees::forestFrames(forest, {}, frames);
  const glm::vec3 foot(forest.trees[best].base[3]);
  float top = foot.y;
  const std::size_t first = forest.jointOffset[best];
  for (std::size_t j = first; j < first + forest.trees[best].topology.jointCount(); ++j) {
    top = std::max(top, frames[j].y.w);
  }
  const float height = std::max(top - foot.y, 1.0f) * 1.1f;
  // Seen from a little above eye height, far enough that the whole tree and a few neighbours show.
  const float distance = std::clamp(2.5f * height, 8.0f, 60.0f);
  const glm::vec3 eye = foot + distance * glm::vec3(0.8f, 0.0f, 0.6f);
  const float ground = terrain::heightAt(field, std::clamp(eye.x, 0.0f, field.extentX()),
                                         std::clamp(eye.z, 0.0f, field.extentZ())) *
                       exaggeration;
  camera.position = glm::vec3(eye.x, (std::isnan(ground) ? foot.y : ground) + 2.5f, eye.z);
  camera.target = foot + glm::vec3(0.0f, 0.45f * height, 0.0f);
  camera.nearPlane = kForestNearPlane;
  return camera;
}

} // namespace sylva::scene
