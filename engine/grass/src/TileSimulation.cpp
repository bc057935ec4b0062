#include <sylva/grass/TileSimulation.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/grass/Expand.hpp>

#include "SimulationSimd.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace sylva::grass {

void PoolSettings::validate() const {
  if (tiles < 1 || tiles > 65536) {
    fail("grass simulation: pool tiles must be in 1..65536, got {}", tiles);
  }
  if (!std::isfinite(releaseTime) || releaseTime <= 0.0f || releaseTime > 600.0f) {
    fail("grass simulation: releaseTime must be in (0, 600] seconds, got {}", releaseTime);
  }
}

TileSimulation::TileSimulation(std::shared_ptr<const GrassField> field, const PoolSettings& pool,
                               const SolverSettings& solver)
    : mField(std::move(field)), mPool(pool), mSolver(solver) {
  mPool.validate();
  mSolver.validate();
  mPerTile = std::min(mField->layout().bladesPerTile, static_cast<int>(mField->patch().size()));
  const std::size_t blades = static_cast<std::size_t>(mPool.tiles) * static_cast<std::size_t>(mPerTile);
  if (blades > (std::size_t{1} << 24)) {
    fail("grass simulation: a pool of {} tiles of {} blades is more than 2^24 blades", mPool.tiles, mPerTile);
  }
  mSlots.resize(static_cast<std::size_t>(mPool.tiles));
  mBlades.position.assign(blades * kSimKnots, glm::vec3(0.0f));
  mBlades.previous.assign(blades * kSimKnots, glm::vec3(0.0f));
  mBlades.rest.assign(blades * kSimKnots, glm::vec3(0.0f));
  mBlades.trample.assign(blades, 0.0f);
  mPatchIndex.assign(blades, kUnused);
  mRoot.assign(blades, glm::vec3(0.0f));
}

int TileSimulation::slotOf(glm::ivec2 tile) const {
  for (std::size_t s = 0; s < mSlots.size(); ++s) {
    if (mSlots[s].used && mSlots[s].tile == tile) {
      return static_cast<int>(s);
    }
  }
  return -1;
}

glm::vec2 TileSimulation::restPose(std::size_t blade, const gpu::WindUniforms& wind) {
  const gpu::GrassBlade& b = mField->patch()[mPatchIndex[blade]];
  const BladeType& type = mField->types()[std::min<std::size_t>(b.info.x, mField->types().size() - 1)];
  const glm::vec3 root = mRoot[blade];
  const glm::vec2 velocity = wind::windVelocity(wind, glm::vec2(root.x, root.z));
  bladeCentreLine(type, b, root, velocity,
                  std::span<glm::vec3, kSimKnots>(mBlades.rest.data() + blade * kSimKnots, kSimKnots));
  return velocity;
}

void TileSimulation::activate(int slot, glm::ivec2 tile, float seconds, const wind::WindSettings& wind) {
  SimSlot& s = mSlots[static_cast<std::size_t>(slot)];
  s = SimSlot{true, tile, 0.0f, false, 0.0};
  const std::size_t base = static_cast<std::size_t>(slot) * static_cast<std::size_t>(mPerTile);
  std::fill(mPatchIndex.begin() + static_cast<std::ptrdiff_t>(base),
            mPatchIndex.begin() + static_cast<std::ptrdiff_t>(base + static_cast<std::size_t>(mPerTile)),
            kUnused);
  const gpu::WindUniforms u = wind::toUniforms(wind, seconds);
  mField->forEachTileBlade(tile.x, tile.y, [&](const FieldBlade& fb) {
    const std::size_t i = base + static_cast<std::size_t>(fb.rangeIndex);
    mPatchIndex[i] = fb.patchIndex;
    mRoot[i] = fb.root;
    restPose(i, u);
    // The state starts as the pose drawn this frame: no pop.
    const auto first = mBlades.rest.begin() + static_cast<std::ptrdiff_t>(i * kSimKnots);
    std::copy(first, first + kSimKnots,
              mBlades.position.begin() + static_cast<std::ptrdiff_t>(i * kSimKnots));
    std::copy(first, first + kSimKnots,
              mBlades.previous.begin() + static_cast<std::ptrdiff_t>(i * kSimKnots));
    mBlades.trample[i] = 0.0f;
  });
  ++mStats.activations;
}

void TileSimulation::advance(double seconds, const std::vector<SimBody>& bodies,
                             const wind::WindSettings& wind) {
  wind::validate(wind);
  for (const SimBody& b : bodies) {
    const glm::vec3 values[] = {b.shape.a, b.shape.b, b.box.min, b.box.max};
    for (const glm::vec3& v : values) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        fail("grass simulation: a body's shape or box is not finite");
      }
    }
    if (!std::isfinite(b.shape.radius) || b.shape.radius < 0.0f) {
      fail("grass simulation: a body's radius must be finite and ≥ 0, got {}", b.shape.radius);
    }
  }
  mStats.steps = 0;
  mStats.activations = 0;
  mStats.releases = 0;
  const double dt = 1.0 / static_cast<double>(mSolver.rate);
  // At most one second of steps per call: after a long pause the simulation skips ahead instead of stalling.
  const long long target = static_cast<long long>(std::floor(seconds / dt + 1e-6));
  if (target - mStepIndex > static_cast<long long>(mSolver.rate)) {
    mStepIndex = target - static_cast<long long>(mSolver.rate);
  }
  while (mStepIndex < target) {
    ++mStepIndex;
    mTime = static_cast<double>(mStepIndex) * dt;
    step(bodies, wind);
    ++mStats.steps;
  }
}

void TileSimulation::step(const std::vector<SimBody>& bodies, const wind::WindSettings& wind) {
  const FieldLayout& layout = mField->layout();
  const float top = mField->bladeTop();
  const auto seconds = static_cast<float>(mTime);
  // Tiles near a body: its box inflated by the tallest blade against each tile's box; key = distance to the
  // nearest body (nearest tiles first when the pool is short).
  std::map<std::pair<int, int>, float> wanted;
  std::vector<std::vector<int>> near(mSlots.size());
  for (std::size_t bi = 0; bi < bodies.size(); ++bi) {
    const Aabb& box = bodies[bi].box;
    const glm::vec2 lo = (glm::vec2(box.min.x, box.min.z) - top - layout.origin) / layout.tileSize;
    const glm::vec2 hi = (glm::vec2(box.max.x, box.max.z) + top - layout.origin) / layout.tileSize;
    const int x0 = std::max(0, static_cast<int>(std::floor(lo.x)));
    const int z0 = std::max(0, static_cast<int>(std::floor(lo.y)));
    const int x1 = std::min(layout.tilesX - 1, static_cast<int>(std::floor(hi.x)));
    const int z1 = std::min(layout.tilesZ - 1, static_cast<int>(std::floor(hi.y)));
    const glm::vec2 centre(0.5f * (box.min.x + box.max.x), 0.5f * (box.min.z + box.max.z));
    for (int tz = z0; tz <= z1; ++tz) {
      for (int tx = x0; tx <= x1; ++tx) {
        const glm::vec2 range = mField->tileRange(tx, tz);
        if (!(range.x <= range.y) || box.max.y < range.x - top || box.min.y > range.y + top ||
            !inFocus({tx, tz})) {
          continue;
        }
        const glm::vec2 c = layout.origin + (glm::vec2(tx, tz) + 0.5f) * layout.tileSize;
        const float d = glm::length(c - centre);
        auto [it, inserted] = wanted.try_emplace({tx, tz}, d);
        if (!inserted) {
          it->second = std::min(it->second, d);
        }
      }
    }
  }
  // Simulate the tiles already in the pool (releasing ones too, with no bodies: they keep moving while they
  // ramp back), each with the bodies near it; tiles beyond the focus are held, their clocks paused.
  std::vector<std::vector<BladeCollider>> colliders(mSlots.size());
  std::vector<int> used;
  // held[s]: 0 stepped, 1 held, 2 held with a body touching it.
  std::vector<std::uint8_t> held(mSlots.size(), 0);
  for (std::size_t s = 0; s < mSlots.size(); ++s) {
    if (!mSlots[s].used) {
      continue;
    }
    SimSlot& slot = mSlots[s];
    const bool seen = inFocus(slot.tile);
    if (seen) {
      used.push_back(static_cast<int>(s));
      if (slot.held) {
        slot.held = false;
        slot.trampledUntil = mTime + slot.trampleLeft;
      }
    } else {
      held[s] = 1;
      if (!slot.held) {
        slot.held = true;
        slot.trampleLeft = std::max(0.0, slot.trampledUntil - mTime);
      }
    }
    const glm::vec2 lo = layout.origin + glm::vec2(slot.tile) * layout.tileSize - top;
    const glm::vec2 hi = lo + layout.tileSize + 2.0f * top;
    for (const SimBody& b : bodies) {
      if (b.box.max.x >= lo.x && b.box.min.x <= hi.x && b.box.max.z >= lo.y && b.box.min.z <= hi.y) {
        if (!seen) {
          held[s] = 2;
          break;
        }
        colliders[s].push_back(b.shape);
        if (b.shape.mass >= mSolver.trampleMass) {
          slot.trampledUntil = mTime + static_cast<double>(mSolver.trampleRecovery);
        }
      }
    }
  }
  if (mBackend != nullptr) {
    mBackend->step(*this, seconds, used, colliders, wind);
  } else {
    stepOnCpu(used, colliders, wind);
  }
  finishStep(wanted, held, wind);
}

bool TileSimulation::inFocus(glm::ivec2 tile) const {
  if (!mFocus) {
    return true;
  }
  const FieldLayout& layout = mField->layout();
  const glm::vec2 lo = layout.origin + glm::vec2(tile) * layout.tileSize;
  const glm::vec2 nearest = glm::clamp(mFocus->centre, lo, lo + layout.tileSize);
  return glm::length(nearest - mFocus->centre) <= mFocus->radius + mField->bladeTop();
}

void TileSimulation::setFocus(std::optional<SimFocus> focus) {
  if (focus && (!std::isfinite(focus->centre.x) || !std::isfinite(focus->centre.y) ||
                !std::isfinite(focus->radius) || focus->radius < 0.0f)) {
    fail("grass simulation: the focus needs a finite centre and a radius ≥ 0 m, got ({}, {}) and {}",
         focus->centre.x, focus->centre.y, focus->radius);
  }
  mFocus = focus;
}

void TileSimulation::stepOnCpu(const std::vector<int>& used,
                               const std::vector<std::vector<BladeCollider>>& colliders,
                               const wind::WindSettings& wind) {
  const auto seconds = static_cast<float>(mTime);
  const gpu::WindUniforms u = wind::toUniforms(wind, seconds);
  const terrain::HeightField& terrain = mField->terrain();
  const GroundFunction ground = [&terrain](float x, float z) { return rootHeight(terrain, x, z); };
  const SolverConstants constants = solverConstants(mSolver);
  const bool simd = constants.kernel == SolverKernel::Simd;
  std::vector<RestShape> shapes;
  if (simd) {
    for (const BladeType& type : mField->types()) {
      shapes.push_back(restShape(type));
    }
  }
  // The highest ground a tile's knots can reach: every knot is within a blade length of its root (the edge
  // lengths hold it there), and the ground between samples is bilinear, so no higher than the samples around
  // it. Knots outside the bound are looked up as before.
  const float reach = 2.0f * mField->bladeTop() + 1.0f;
  const auto groundBound = [&](const std::vector<std::uint32_t>& blades) {
    GroundShortcuts bound;
    if (blades.empty() || terrain.width() < 2 || terrain.height() < 2) {
      return bound;
    }
    bound.grid = &terrain;
    glm::vec2 lo(std::numeric_limits<float>::max());
    glm::vec2 hi(std::numeric_limits<float>::lowest());
    for (const std::uint32_t i : blades) {
      lo = glm::min(lo, glm::vec2(mRoot[i].x, mRoot[i].z));
      hi = glm::max(hi, glm::vec2(mRoot[i].x, mRoot[i].z));
    }
    bound.lo = lo - reach;
    bound.hi = hi + reach;
    const auto sample = [](float at, float spacing, int count, bool up) {
      const float g = std::clamp(at / spacing, 0.0f, static_cast<float>(count - 1));
      return std::clamp(static_cast<int>(up ? std::ceil(g) : std::floor(g)), 0, count - 1);
    };
    const int i0 = sample(bound.lo.x, terrain.spacingX(), terrain.width(), false);
    const int i1 = sample(bound.hi.x, terrain.spacingX(), terrain.width(), true);
    const int j0 = sample(bound.lo.y, terrain.spacingZ(), terrain.height(), false);
    const int j1 = sample(bound.hi.y, terrain.spacingZ(), terrain.height(), true);
    bound.ceiling = std::numeric_limits<float>::lowest();
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        if (terrain.valid(i, j)) {
          bound.ceiling = std::max(bound.ceiling, terrain.at(i, j));
        }
      }
    }
    // The bilinear blend may round a few ulps above its highest sample.
    bound.ceiling += std::abs(bound.ceiling) * 1e-6f + 1e-6f;
    return bound;
  };
  parallelFor(
      used.size(),
      [&](std::size_t begin, std::size_t end) {
        std::vector<std::uint32_t> blades;
        std::vector<glm::vec2> velocities;
        std::vector<glm::vec2> roots;
        std::vector<RestInput> rest;
        for (std::size_t k = begin; k < end; ++k) {
          const auto s = static_cast<std::size_t>(used[k]);
          const std::size_t base = s * static_cast<std::size_t>(mPerTile);
          blades.clear();
          velocities.clear();
          roots.clear();
          rest.clear();
          for (std::size_t i = base; i < base + static_cast<std::size_t>(mPerTile); ++i) {
            if (mPatchIndex[i] == kUnused) {
              continue;
            }
            blades.push_back(static_cast<std::uint32_t>(i));
            if (!simd) {
              velocities.push_back(restPose(i, u));
              continue;
            }
            // The reference's restPose on lanes: the wind at every root of the tile at once (bit for bit
            // windVelocity), then the bent knot lines.
            const gpu::GrassBlade& b = mField->patch()[mPatchIndex[i]];
            roots.emplace_back(mRoot[i].x, mRoot[i].z);
            rest.push_back({static_cast<std::uint32_t>(i),
                            std::min<std::uint32_t>(b.info.x, static_cast<std::uint32_t>(shapes.size() - 1)),
                            b.placement.z, b.placement.w, mRoot[i], glm::vec2(0.0f)});
          }
          if (simd) {
            velocities.resize(roots.size());
            wind::windVelocities(u, roots, {}, velocities);
            for (std::size_t r = 0; r < rest.size(); ++r) {
              rest[r].wind = velocities[r];
            }
            restPosesSimd(shapes, rest.data(), rest.size(), mBlades);
          }
          simulateBlades(mBlades, blades, velocities, colliders[s], ground, constants, groundBound(blades));
        }
      },
      1);
}

void TileSimulation::finishStep(const std::map<std::pair<int, int>, float>& wanted,
                                const std::vector<std::uint8_t>& held, const wind::WindSettings& wind) {
  const float dt = mSolver.step();
  const auto seconds = static_cast<float>(mTime);
  // Release bookkeeping: a tile no body is near starts ramping back once its blades stand (none trampled);
  // a body coming back stops the ramp. A held tile (not drawn) goes back at once or waits as it is.
  mStats.heldTiles = 0;
  for (std::size_t s = 0; s < mSlots.size(); ++s) {
    SimSlot& slot = mSlots[s];
    if (!slot.used) {
      continue;
    }
    const bool near = wanted.count({slot.tile.x, slot.tile.y}) != 0;
    if (held[s] != 0) {
      // Not drawn: it waits as it is while a body touches it or its blades are trampled, else goes back now.
      if (held[s] == 2 || slot.trampleLeft > 0.0) {
        ++mStats.heldTiles;
        continue;
      }
    } else if (near) {
      slot.releasing = false;
      slot.release = 0.0f;
      continue;
    } else if (!slot.releasing) {
      slot.releasing = mTime >= slot.trampledUntil;
      continue;
    }
    slot.release = held[s] != 0 ? 1.0f : slot.release + dt / mPool.releaseTime;
    if (slot.release >= 1.0f) {
      slot = SimSlot{};
      const std::size_t base = s * static_cast<std::size_t>(mPerTile);
      std::fill(mPatchIndex.begin() + static_cast<std::ptrdiff_t>(base),
                mPatchIndex.begin() + static_cast<std::ptrdiff_t>(base + static_cast<std::size_t>(mPerTile)),
                kUnused);
      ++mStats.releases;
      if (mBackend != nullptr) {
        mBackend->released(*this, static_cast<int>(s));
      }
    }
  }
  // New tiles, nearest first, while slots last.
  std::vector<std::pair<float, glm::ivec2>> fresh;
  for (const auto& [tile, d] : wanted) {
    if (slotOf({tile.first, tile.second}) < 0) {
      fresh.push_back({d, glm::ivec2(tile.first, tile.second)});
    }
  }
  std::sort(fresh.begin(), fresh.end(), [](const auto& a, const auto& b) {
    return a.first != b.first
               ? a.first < b.first
               : (a.second.y != b.second.y ? a.second.y < b.second.y : a.second.x < b.second.x);
  });
  mStats.refusedTiles = 0;
  std::size_t free = 0;
  for (const auto& [d, tile] : fresh) {
    while (free < mSlots.size() && mSlots[free].used) {
      ++free;
    }
    if (free == mSlots.size()) {
      ++mStats.refusedTiles;
      continue;
    }
    activate(static_cast<int>(free), tile, seconds, wind);
    if (mBackend != nullptr) {
      mBackend->activated(*this, static_cast<int>(free));
    }
  }
  mStats.activeTiles = 0;
  mStats.simulatedBlades = 0;
  for (std::size_t s = 0; s < mSlots.size(); ++s) {
    if (mSlots[s].used) {
      ++mStats.activeTiles;
      const std::size_t base = s * static_cast<std::size_t>(mPerTile);
      for (std::size_t i = base; i < base + static_cast<std::size_t>(mPerTile); ++i) {
        mStats.simulatedBlades += mPatchIndex[i] != kUnused ? 1 : 0;
      }
    }
  }
}

} // namespace sylva::grass

namespace sylva::grass {

bool TileSimulation::activateTile(glm::ivec2 tile, const wind::WindSettings& wind) {
  const FieldLayout& layout = mField->layout();
  if (tile.x < 0 || tile.y < 0 || tile.x >= layout.tilesX || tile.y >= layout.tilesZ || slotOf(tile) >= 0) {
    return false;
  }
  for (std::size_t s = 0; s < mSlots.size(); ++s) {
    if (!mSlots[s].used) {
      activate(static_cast<int>(s), tile, static_cast<float>(mTime), wind);
      if (mBackend != nullptr) {
        mBackend->activated(*this, static_cast<int>(s));
      }
      return true;
    }
  }
  return false;
}

void TileSimulation::stepSolver(const std::vector<std::vector<BladeCollider>>& colliders,
                                const wind::WindSettings& wind) {
  if (colliders.size() != mSlots.size()) {
    fail("grass simulation: {} collider lists for {} slots", colliders.size(), mSlots.size());
  }
  std::vector<int> used;
  for (std::size_t s = 0; s < mSlots.size(); ++s) {
    if (mSlots[s].used) {
      used.push_back(static_cast<int>(s));
    }
  }
  if (mBackend != nullptr) {
    mBackend->step(*this, static_cast<float>(mTime), used, colliders, wind);
  } else {
    stepOnCpu(used, colliders, wind);
  }
}

} // namespace sylva::grass
