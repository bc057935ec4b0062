#include "flags/GrassSim.hpp"

#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::app {

void SimulationFlags::add(CLI::App& command) {
  command
      .add_option(
          "--physics", physics,
          "Bodies in the grass: none, or balls (dropped ahead of the camera, rolling downhill through "
          "the field; needs --grass)")
      ->check(CLI::IsMember({"none", "balls"}))
      ->capture_default_str();
  command.add_option("--balls", balls, "Balls of --physics balls")
      ->check(CLI::Range(1, 4096))
      ->capture_default_str();
  command.add_option("--physics-seed", seed, "Seed of the balls' sizes, masses and places")
      ->check(unsignedInteger())
      ->capture_default_str();
  command.add_option("--grass-sim", solver, "Grass solver: gpu (compute shader) or cpu (the reference)")
      ->check(CLI::IsMember({"gpu", "cpu"}))
      ->capture_default_str();
  command.add_option("--grass-pool", pool, "Tiles that can be simulated at once")
      ->check(CLI::Range(1, 65536))
      ->capture_default_str();
  command
      .add_option("--trample-recovery", trampleRecovery, "Seconds a trampled blade takes to stand up again")
      ->check(finiteRange(0.1, 600.0))
      ->capture_default_str();
}

grass::SolverSettings SimulationFlags::solverSettings() const {
  grass::SolverSettings s;
  s.trampleRecovery = trampleRecovery;
  s.validate();
  return s;
}

grass::PoolSettings SimulationFlags::poolSettings() const {
  grass::PoolSettings p;
  p.tiles = pool;
  p.validate();
  return p;
}

glm::vec2 ballDropPoint(const terrain::HeightField& terrain, const grass::GrassField& field,
                        const render::Camera& camera, float radius) {
  // The steepest grassy slope (up to 25°, where balls roll without bouncing away) within `radius` of the
  // camera: the balls roll down it through the grass.
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

} // namespace sylva::app

namespace sylva::app {

render::Camera ballCamera(const terrain::TerrainScene& scene, glm::vec2 drop, float fovY) {
  const terrain::HeightField& t = scene.field();
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
  render::fitClipPlanes(camera, scene.bounds());
  camera.nearPlane = 0.05f;
  return camera;
}

} // namespace sylva::app
