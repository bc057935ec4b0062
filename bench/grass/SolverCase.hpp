#pragma once

// The paper's Table 1 workloads of the grass constraint solver (docs/grass-simulation.md, "Benchmarks"),
// shared by the Google Benchmark cases (bench/grass/GrassBench.cpp) and `sylva bench grass-sim`: simulated
// tiles of 64 blades in a square block around the centre of a 96 × 96-tile field of 2 m tiles on gentle
// procedural terrain, and bodies (0.4 m balls) resting on the grass at the centres of their shares of the
// tiles. Header-only so both the benchmark executable and the CLI include it without a library.

#include <sylva/grass/BladeType.hpp>
#include <sylva/grass/GrassField.hpp>
#include <sylva/grass/TileSimulation.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/TerrainSetup.hpp>
#include <sylva/wind/Wind.hpp>

#include <cmath>
#include <memory>
#include <vector>

namespace sylva::grass::bench {

/** The paper's field: 16,384-blade patch, 64 blades per 2 m tile, full density everywhere. */
inline FieldSettings paperFieldSettings() {
  FieldSettings fs;
  fs.patch.blades = 16384;
  fs.bladesPerTile = 64;
  fs.density.noiseFrequency = 0.0f;
  fs.density.coverage = 1.0f;
  fs.density.maxSlopeDegrees = 90.0f;
  return fs;
}

/** The solver benchmarks' field: 96 × 96 tiles of 2 m, room for the 7,813 tiles of the GPU workload. */
inline std::shared_ptr<GrassField> solverField() {
  terrain::ProceduralSpec spec = terrain::TerrainSource::defaultProcedural();
  spec.heightScale = 4.0f;
  spec.frequency = 1.0f / 120.0f;
  return std::make_shared<GrassField>(terrain::generate(spec, 0.0, 0.0, 193, 193, 1.0f),
                                      proceduralBladeTypes(), paperFieldSettings());
}

/** The solver benchmarks' wind: 4 m/s. */
inline wind::WindSettings solverWind() {
  wind::WindSettings wind;
  wind.speed = 4.0f;
  return wind;
}

/**
 * Activates `tiles` tiles of `sim` in a square block around the field's centre and returns each slot's
 * colliders: `bodies` balls of 0.4 m spread over the tiles, each tile getting the balls whose box (inflated
 * by the blade height) touches it.
 */
inline std::vector<std::vector<BladeCollider>> setUpSolverCase(TileSimulation& sim, const GrassField& field,
                                                               int tiles, int bodies,
                                                               const wind::WindSettings& wind) {
  const float top = field.bladeTop();
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tiles))));
  const glm::ivec2 first(48 - side / 2, 48 - side / 2);
  std::vector<glm::ivec2> chosen;
  for (int i = 0; i < tiles; ++i) {
    chosen.push_back(first + glm::ivec2(i % side, i / side));
    sim.activateTile(chosen.back(), wind);
  }
  std::vector<BladeCollider> balls;
  for (int b = 0; b < bodies; ++b) {
    const glm::ivec2 t = chosen[static_cast<std::size_t>((static_cast<double>(b) + 0.5) * tiles / bodies)];
    const glm::vec2 xz = (glm::vec2(t) + 0.5f) * field.layout().tileSize;
    const float y = terrain::heightAt(field.terrain(), xz.x, xz.y) + 0.3f;
    balls.push_back({glm::vec3(xz.x, y, xz.y), glm::vec3(xz.x, y, xz.y), 0.4f, 30.0f});
  }
  std::vector<std::vector<BladeCollider>> colliders(sim.slots().size());
  for (std::size_t s = 0; s < sim.slots().size(); ++s) {
    if (!sim.slots()[s].used) {
      continue;
    }
    const glm::vec2 lo = glm::vec2(sim.slots()[s].tile) * field.layout().tileSize - top;
    const glm::vec2 hi = lo + field.layout().tileSize + 2.0f * top;
    for (const BladeCollider& c : balls) {
      if (c.a.x + c.radius >= lo.x && c.a.x - c.radius <= hi.x && c.a.z + c.radius >= lo.y &&
          c.a.z - c.radius <= hi.y) {
        colliders[s].push_back(c);
      }
    }
  }
  return colliders;
}

} // namespace sylva::grass::bench
