#include <sylva/scene/BallDrop.hpp>

#include <sylva/terrain/HeightQuery.hpp>

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
  camera.nearPlane = 0.05f;
  return camera;
}

} // namespace sylva::scene
