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
  command.add_option("--balls-at", ballsAt,
                     "Where the balls drop, X,Z metres (default: a grassy spot ahead of the camera; the "
                     "camera line of --log-level info gives the value to render the same view again)");
  command.add_option("--physics-seed", seed, "Seed of the balls' sizes, masses and places")
      ->check(unsignedInteger())
      ->capture_default_str();
  command
      .add_option("--grass-sim", solver,
                  "Grass solver: gpu (compute shader), cpu (SIMD, bit for bit the reference) or auto (cpu on "
                  "a software rasteriser such as llvmpipe, else gpu)")
      ->check(CLI::IsMember({"auto", "gpu", "cpu"}))
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

} // namespace sylva::app
