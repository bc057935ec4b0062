#pragma once
// The command line of the grass simulation (docs/grass-simulation.md; the simulation itself is
// scene::GrassSimulation, where balls drop scene::ballDropPoint): `sylva render --grass --physics balls` and
// `sylva view`.

#include <sylva/grass/GrassField.hpp>
#include <sylva/scene/gpu/GrassSimulation.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace sylva::app {

/** --physics and the simulation's settings. */
struct SimulationFlags {
  /** "none" or "balls" (balls dropped ahead of the camera roll downhill through the grass). */
  std::string physics = "none";
  int balls = 10;
  std::uint64_t seed = 7;
  /** "auto", "gpu" (compute shader) or "cpu" (the SIMD solver, bit for bit the reference). */
  std::string solver = "auto";
  int pool = 512;
  float trampleRecovery = 6.0f;
  /** "X,Z" metres: where the balls drop; empty: chosen ahead of the camera (scene::ballDropPoint). */
  std::string ballsAt;

  /** Adds --physics, --balls, --balls-at, --physics-seed, --grass-sim, --grass-pool, --trample-recovery. */
  void add(CLI::App& command);
  bool enabled() const { return physics != "none"; }
  grass::SolverSettings solverSettings() const;
  grass::PoolSettings poolSettings() const;
  /** The engine's description (checked: throws for bad settings). */
  scene::GrassSimSettings settings() const {
    return {poolSettings(), solverSettings(),
            solver == "gpu"   ? scene::GrassSolve::Gpu
            : solver == "cpu" ? scene::GrassSolve::Cpu
                              : scene::GrassSolve::Auto};
  }
};

} // namespace sylva::app
