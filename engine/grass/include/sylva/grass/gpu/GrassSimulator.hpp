#pragma once
// The grass simulation on the GPU (docs/grass-simulation.md): the pool's blades in storage buffers, stepped
// by shaders/grass/simulate.comp (the twin of the CPU solver), and the slot table the field's culling reads
// so that simulated tiles are drawn from these buffers in the field's one draw. As a SimulationBackend of a
// TileSimulation it runs the steps; with the CPU solver instead, upload() copies the CPU state for drawing.
// Needs a current GL context.

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/grass/gpu/GrassRenderer.hpp>
#include <sylva/grass/TileSimulation.hpp>
#include <sylva/shader/Library.hpp>

#include <shared/GrassSim.h>

#include <vector>

namespace sylva::grass {

/** The blade solver in compute shaders: TileSimulation's steps on the GPU, the same constants as the CPU
 * solver. */
class GrassSimulator : public SimulationBackend {
public:
  /** Buffers for `sim`'s pool; reads the field's patch, types and terrain through `renderer`. */
  GrassSimulator(const shader::Library& library, GrassRenderer& renderer, const TileSimulation& sim);

  /** Recompiles the solver's shaders from `library`; keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);

  void step(const TileSimulation& sim, float seconds, const std::vector<int>& slots,
            const std::vector<std::vector<BladeCollider>>& colliders,
            const wind::WindSettings& wind) override;
  void released(const TileSimulation& sim, int slot) override;
  void activated(const TileSimulation& sim, int slot) override;

  /** CPU solver: copies the used slots' CPU state into the buffers the renderer draws from. */
  void upload(const TileSimulation& sim);
  /** The slot table the culling pass reads (tile, used, release ramp); call after each advance(). */
  void syncSlots(const TileSimulation& sim);
  /** Binds the pool's buffers and slot table for the renderer's cull and draw. */
  void bindForDrawing() const;

  /** The GPU knot positions (pool blade-major, kSimKnots each), for tests. */
  std::vector<glm::vec3> readPositions() const;
  /** Pool slots and blades per tile. */
  int slots() const { return mSlots; }
  /** Blades per tile. */
  int bladesPerTile() const { return mPerTile; }

private:
  void uploadSlotBlades(const TileSimulation& sim, int slot, bool state);

  GrassRenderer& mRenderer;
  const SolverSettings mSolverSettings;
  int mSlots = 0;
  int mPerTile = 0;
  gl::Program mSimulate{gl::NoCreate};
  gl::Buffer mUniforms;
  gl::Buffer mPositions;
  gl::Buffer mPrevious;
  gl::Buffer mBlades;
  gl::Buffer mWork;
  gl::Buffer mRanges;
  gl::Buffer mColliders{gl::NoCreate};
  gl::Buffer mSlotTable;
};

} // namespace sylva::grass
