#pragma once
// Simulated grass (docs/grass-simulation.md): a Bullet world on the terrain, the tile manager and its solver
// (GPU, or the CPU reference) moving one grass layer, and the bodies drawn. Scene files ("simulate": true,
// "bodies", "drops"), `sylva render --grass --physics balls` and `sylva view` use it. GL side.

#include <sylva/grass/gpu/GrassRenderer.hpp>
#include <sylva/grass/gpu/GrassSimulator.hpp>
#include <sylva/grass/TileSimulation.hpp>
#include <sylva/physics/gpu/BodyRenderer.hpp>
#include <sylva/physics/World.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/wind/Wind.hpp>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace sylva::scene {

/**
 * The physics world on a terrain, the simulated tiles of one grass renderer's field and the drawing of the
 * bodies. The renderer draws the simulated blades while this object lives (GrassRenderer::setSimulation).
 * Needs a current GL context; not thread-safe.
 */
class GrassSimulation {
public:
  /** A world on `ground` (drawn heights, world metres; not owned, must outlive this) moving `grass`'s field.
   * Throws sylva::Error for bad settings. */
  GrassSimulation(const shader::Library& library, const terrain::HeightField& ground,
                  grass::GrassRenderer& grass, std::shared_ptr<const grass::GrassField> field,
                  const GrassSimSettings& settings);
  ~GrassSimulation();
  GrassSimulation(const GrassSimulation&) = delete;
  GrassSimulation& operator=(const GrassSimulation&) = delete;

  /** Drops `count` seeded balls over a disc of `radius` metres around world (x, z) `centre`, `drop` metres
   * up. */
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
  /** Recompiles the solver and body shaders from `library`; keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);

  /** Real time: the grass steps only the tiles within `focus` (grass::TileSimulation::setFocus); null: all.
   */
  void setFocus(std::optional<grass::SimFocus> focus) { mTiles->setFocus(focus); }
  /** Counts of the last step: active, held and refused tiles, simulated blades. */
  const grass::SimStats& stats() const { return mTiles->stats(); }
  /** Bodies in the world. */
  std::size_t bodies() const { return mWorld->bodyCount(); }
  /** Simulated time, seconds. */
  double time() const { return mTime; }
  /** Whether the solver runs in compute shaders (else on the CPU). */
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

} // namespace sylva::scene
