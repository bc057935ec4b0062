#pragma once
// Grass simulation in the apps (docs/grass-simulation.md): a Bullet world on the terrain, the tile manager
// and its solver (GPU or CPU reference), the bodies drawn: `sylva render --grass --physics balls`, `sylva
// view`.

#include <sylva/grass/GrassSimulator.hpp>
#include <sylva/physics/BodyRenderer.hpp>
#include <sylva/physics/World.hpp>
#include <sylva/terrain/TerrainScene.hpp>

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
  /** "gpu" (compute shader) or "cpu" (the reference solver). */
  std::string solver = "gpu";
  int pool = 512;
  float trampleRecovery = 6.0f;

  /** Adds --physics, --balls, --physics-seed, --grass-sim, --grass-pool, --trample-recovery. */
  void add(CLI::App& command);
  bool enabled() const { return physics != "none"; }
  grass::SolverSettings solverSettings() const;
  grass::PoolSettings poolSettings() const;
};

/** The world, the simulated tiles and the drawing of bodies. */
class GrassSimScene {
public:
  GrassSimScene(const shader::Library& library, const terrain::TerrainScene& scene,
                grass::GrassRenderer& grass, std::shared_ptr<const grass::GrassField> field,
                const SimulationFlags& flags);
  ~GrassSimScene();

  /** Drops `count` seeded balls over a disc of `radius` metres around world (x, z) `centre`. */
  void spawnBalls(glm::vec2 centre, float radius, int count, std::uint64_t seed, float drop = 1.0f);
  /** Adds a body (`where` names it in errors). */
  void addBody(const physics::BodySpec& spec, const std::string& where);
  /** Adds one ball (world metres, m/s, kg). */
  void spawnBall(const glm::vec3& position, const glm::vec3& velocity, float radius = 0.35f,
                 float mass = 30.0f);
  /** Advances the bodies and the grass to `seconds` (fixed steps; the grass draws the result). */
  void advance(double seconds, const wind::WindSettings& wind);
  /** Draws the bodies into the bound framebuffer. */
  void drawBodies(const render::Camera& camera, int width, int height, double time,
                  const render::Environment& environment);
  void reloadShaders(const shader::Library& library);

  const grass::SimStats& stats() const { return mTiles->stats(); }
  std::size_t bodies() const { return mWorld->bodyCount(); }
  double time() const { return mTime; }
  bool onGpu() const { return mGpu; }

private:
  grass::GrassRenderer& mGrass;
  std::unique_ptr<physics::World> mWorld;
  std::unique_ptr<grass::TileSimulation> mTiles;
  std::unique_ptr<grass::GrassSimulator> mSimulator;
  physics::BodyRenderer mBodies;
  bool mGpu = true;
  double mTime = 0.0;
};

/**
 * Where the demo drops its balls: the steepest grassy slope (at most 25°) within `radius` metres of `camera`,
 * so they roll down through the grass.
 */
glm::vec2 ballDropPoint(const terrain::HeightField& terrain, const grass::GrassField& field,
                        const render::Camera& camera, float radius = 40.0f);

/**
 * A camera that watches balls dropped at `drop` roll down towards it: downhill of the drop point and a little
 * to the side, 1.8 m above the ground, looking back up the slope.
 */
render::Camera ballCamera(const terrain::TerrainScene& scene, glm::vec2 drop, float fovY);

} // namespace sylva::app
