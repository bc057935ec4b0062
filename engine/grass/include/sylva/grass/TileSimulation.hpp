#pragma once
// Tile management (Fan et al. 2015, docs/grass-simulation.md): a tile gets per-blade simulation state from a
// fixed pool only while a body is near it. On activation the state is the tile's current procedural pose (no
// pop); a tile no body is near any more (and whose blades have stood up again) ramps back to the procedural
// pose over releaseTime and returns its slot. When the pool is full, the tiles nearest a body win; the rest
// stay procedural and are counted. The solver runs at its fixed rate whatever the frame rate.

#include <sylva/core/Geometry.hpp>
#include <sylva/grass/GrassField.hpp>
#include <sylva/grass/Simulation.hpp>
#include <sylva/wind/Wind.hpp>

#include <glm/vec2.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace sylva::grass {

/** The pool. */
struct PoolSettings {
  /** Tiles that can be simulated at once (slots). */
  int tiles = 512;
  /** Seconds over which a released tile returns to the procedural pose. */
  float releaseTime = 1.0f;
  /** Throws sylva::Error naming the field for a pool of 0 or absurd size, or a non-finite ramp. */
  void validate() const;
};

/** A body as the tile manager sees it: its collision shape and bounding box (world metres). */
struct SimBody {
  /** Collision shape. */
  BladeCollider shape;
  /** Bounding box, world metres. */
  Aabb box;
};

/** One slot of the pool. */
struct SimSlot {
  /** Whether the slot holds a tile. */
  bool used = false;
  /** The tile it holds (column, row). */
  glm::ivec2 tile{0};
  /** 0 while simulated; rises to 1 over the release ramp, then the slot is freed. */
  float release = 0.0f;
  /** True while the slot is being released. */
  bool releasing = false;
  /** Simulation time until which the tile counts as trampled (a heavy body was near): it is not released
   * before, so bent blades stay bent and stand up again under simulation. */
  double trampledUntil = 0.0;
  /** Beyond the focus, not stepped (TileSimulation::setFocus); its clocks wait. */
  bool held = false;
  /** While held: the seconds of trampling it had left when it was held. */
  double trampleLeft = 0.0;
};

/**
 * Where the simulated blades can be seen (real time): the eye's ground position and the distance beyond which
 * the grass is not drawn, world metres. Tiles wholly beyond it are held (TileSimulation::setFocus).
 */
struct SimFocus {
  glm::vec2 centre{0.0f}; ///< eye, world xz
  float radius = 0.0f;    ///< drawn grass distance, metres (horizontal; ≥ 0)
};

/** What the last advance() did. */
struct SimStats {
  /** Tiles simulated in the last step. */
  std::size_t activeTiles = 0;
  /** Blades simulated in the last step. */
  std::size_t simulatedBlades = 0;
  /** Tiles in the pool not stepped in the last step: beyond the focus, held as they were (setFocus). */
  std::size_t heldTiles = 0;
  /** Tiles near a body that got no slot (pool exhausted) in the last step. */
  std::size_t refusedTiles = 0;
  /** Tiles that got a slot in the last advance(). */
  std::size_t activations = 0;
  /** Tiles released in the last advance(). */
  std::size_t releases = 0;
  /** Fixed steps run by the last advance(). */
  int steps = 0;
};

class TileSimulation;

/**
 * Where the solver steps run when not on the CPU (the GPU simulator). The tile manager stays on the CPU and
 * calls these once per fixed step, in this order: step (the slots in use before this step's activations),
 * released, activated. With a backend the CPU blade arrays only hold each slot's state at activation.
 */
class SimulationBackend {
public:
  virtual ~SimulationBackend() = default;
  /** One step at `seconds` of the blades of `slots`, each with `colliders[slot]`, in `wind`. */
  virtual void step(const TileSimulation& sim, float seconds, const std::vector<int>& slots,
                    const std::vector<std::vector<BladeCollider>>& colliders,
                    const wind::WindSettings& wind) = 0;
  /** `slot` was freed. */
  virtual void released(const TileSimulation& sim, int slot) = 0;
  /** `slot` was filled: its blades are in the CPU arrays at their procedural pose. */
  virtual void activated(const TileSimulation& sim, int slot) = 0;
};

/** The tile manager and its blades. */
class TileSimulation {
public:
  /** A manager for `field` with a pool of `pool.tiles` slots, stepped with `solver`. */
  TileSimulation(std::shared_ptr<const GrassField> field, const PoolSettings& pool,
                 const SolverSettings& solver);

  /**
   * Runs the fixed steps up to `seconds` (simulation time): each step updates which tiles are simulated from
   * the bodies' boxes (inflated by the tallest blade), sets every simulated blade's rest pose to its
   * procedural pose under `wind` at that moment, and runs the solver on each tile with the bodies whose boxes
   * touch it. `bodies` are the state at `seconds` (they are not interpolated between steps).
   */
  void advance(double seconds, const std::vector<SimBody>& bodies, const wind::WindSettings& wind);
  /**
   * Puts tile (tx, tz) in the pool now (at its procedural pose at time()), as a body coming near would: for
   * benchmarks and tests that need a given set of simulated tiles. False when the pool is full or the tile is
   * in already. The next advance() releases it unless a body is near.
   */
  bool activateTile(glm::ivec2 tile, const wind::WindSettings& wind);
  /**
   * One solver step of every simulated tile with `colliders[slot]` (sized like slots()), without tile
   * management: the solver part of a step, for benchmarks. Runs on the backend when there is one.
   */
  void stepSolver(const std::vector<std::vector<BladeCollider>>& colliders, const wind::WindSettings& wind);
  /**
   * Real time: steps only the tiles the frame can draw. A tile whose nearest point lies farther than
   * `focus->radius` (plus the tallest blade) from `focus->centre` is held: not stepped, its trample clock and
   * release ramp paused, so it resumes as it was when it comes back into view; a held tile no body touches
   * and with no trampled blades is released at once (nobody sees it go back to the procedural pose), and
   * tiles beyond the focus are not activated (they start at the procedural pose of the moment they come into
   * view). Null (the default): every tile is stepped, and a sequence's state depends only on its times.
   */
  void setFocus(std::optional<SimFocus> focus);
  /** The focus set by setFocus(). */
  const std::optional<SimFocus>& focus() const { return mFocus; }
  /** Runs the steps on `backend` instead of the CPU (null: the CPU reference). Not owned. */
  void setBackend(SimulationBackend* backend) { mBackend = backend; }

  /** The field simulated. */
  const GrassField& field() const { return *mField; }
  /** The pool's settings. */
  const PoolSettings& pool() const { return mPool; }
  /** The solver's settings. */
  const SolverSettings& solver() const { return mSolver; }
  /** The pool's slots. */
  const std::vector<SimSlot>& slots() const { return mSlots; }
  /** The pool's blades, slot-major: slot s holds blades [s·bladesPerTile, (s + 1)·bladesPerTile). */
  const SimBlades& blades() const { return mBlades; }
  /** Whether pool blade i is a blade of its tile (the density keeps it); others are never drawn. */
  bool bladeInUse(std::size_t i) const { return mPatchIndex[i] != kUnused; }
  /** Patch index of pool blade i (kUnused when not in use). */
  std::uint32_t patchIndex(std::size_t i) const { return mPatchIndex[i]; }
  /** Root of pool blade i, world metres. */
  glm::vec3 root(std::size_t i) const { return mRoot[i]; }
  /** Slot of tile (tx, tz), or −1. */
  int slotOf(glm::ivec2 tile) const;
  /** What the last advance() did. */
  const SimStats& stats() const { return mStats; }
  /** Simulation time reached, seconds. */
  double time() const { return mTime; }
  /** Blades per tile in the pool. */
  int bladesPerTile() const { return mPerTile; }

  /** patchIndex() of a pool blade not in use. */
  static constexpr std::uint32_t kUnused = 0xffffffffu;

private:
  void step(const std::vector<SimBody>& bodies, const wind::WindSettings& wind);
  void stepOnCpu(const std::vector<int>& used, const std::vector<std::vector<BladeCollider>>& colliders,
                 const wind::WindSettings& wind);
  void finishStep(const std::map<std::pair<int, int>, float>& wanted, const std::vector<std::uint8_t>& held,
                  const wind::WindSettings& wind);
  /** Whether tile (tx, tz) lies within the focus (always without one). */
  bool inFocus(glm::ivec2 tile) const;
  void activate(int slot, glm::ivec2 tile, float seconds, const wind::WindSettings& wind);
  /** Sets blade `blade`'s rest pose for `wind`; returns the wind velocity at its root. */
  glm::vec2 restPose(std::size_t blade, const gpu::WindUniforms& wind);

  std::shared_ptr<const GrassField> mField;
  PoolSettings mPool;
  SolverSettings mSolver;
  int mPerTile = 0;
  std::vector<SimSlot> mSlots;
  SimBlades mBlades;
  std::vector<std::uint32_t> mPatchIndex;
  std::vector<glm::vec3> mRoot;
  SimStats mStats;
  double mTime = 0.0;
  long long mStepIndex = 0;
  SimulationBackend* mBackend = nullptr;
  std::optional<SimFocus> mFocus;
};

} // namespace sylva::grass
