#include <sylva/grass/gpu/GrassSimulator.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/shader/Compiler.hpp>

#include <algorithm>
#include <bit>

namespace sylva::grass {
namespace {

constexpr std::size_t kKnots = static_cast<std::size_t>(kSimKnots);

} // namespace

GrassSimulator::GrassSimulator(const shader::Library& library, GrassRenderer& renderer,
                               const TileSimulation& sim)
    : mRenderer(renderer), mSolverSettings(sim.solver()), mSlots(sim.pool().tiles),
      mPerTile(sim.bladesPerTile()), mUniforms(sizeof(gpu::GrassSimUniforms)),
      mPositions(static_cast<std::size_t>(mSlots) * static_cast<std::size_t>(mPerTile) * kKnots *
                 sizeof(glm::vec4)),
      mPrevious(mPositions.size()), mBlades(static_cast<std::size_t>(mSlots) *
                                            static_cast<std::size_t>(mPerTile) * sizeof(gpu::GrassSimBlade)),
      mWork(static_cast<std::size_t>(mSlots) * sizeof(std::uint32_t)),
      mRanges(static_cast<std::size_t>(mSlots) * sizeof(glm::uvec4)),
      mSlotTable(static_cast<std::size_t>(mSlots) * sizeof(glm::ivec4)) {
  std::vector<gpu::GrassSimBlade> unused(static_cast<std::size_t>(mSlots) *
                                         static_cast<std::size_t>(mPerTile));
  for (gpu::GrassSimBlade& b : unused) {
    b.info = glm::uvec4(SYLVA_GRASS_SIM_UNUSED, 0u, 0u, 0u);
  }
  mBlades.setSubData(std::span<const gpu::GrassSimBlade>(unused));
  mSlotTable.clear();
  mRanges.clear();
  gl::setLabel(GL_BUFFER, mPositions.id(), "grass pool knots");
  reloadShaders(library);
}

void GrassSimulator::reloadShaders(const shader::Library& library) {
  mSimulate = shader::compileProgram(library, {"grass simulate", {"grass/simulate.comp"}, {}});
}

void GrassSimulator::uploadSlotBlades(const TileSimulation& sim, int slot, bool state) {
  const std::size_t first = static_cast<std::size_t>(slot) * static_cast<std::size_t>(mPerTile);
  const auto count = static_cast<std::size_t>(mPerTile);
  std::vector<gpu::GrassSimBlade> blades(count);
  std::vector<glm::vec4> knots(state ? count * kKnots : 0);
  std::vector<glm::vec4> previous(state ? count * kKnots : 0);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t b = first + i;
    const bool inUse = state && sim.bladeInUse(b);
    blades[i].root = glm::vec4(inUse ? sim.root(b) : glm::vec3(0.0f), inUse ? sim.blades().trample[b] : 0.0f);
    blades[i].info = glm::uvec4(inUse ? sim.patchIndex(b) : SYLVA_GRASS_SIM_UNUSED, 0u, 0u, 0u);
    for (std::size_t k = 0; state && k < kKnots; ++k) {
      knots[i * kKnots + k] = glm::vec4(sim.blades().position[b * kKnots + k], 0.0f);
      previous[i * kKnots + k] = glm::vec4(sim.blades().previous[b * kKnots + k], 0.0f);
    }
  }
  mBlades.setSubData(first * sizeof(gpu::GrassSimBlade), count * sizeof(gpu::GrassSimBlade), blades.data());
  if (state) {
    mPositions.setSubData(first * kKnots * sizeof(glm::vec4), knots.size() * sizeof(glm::vec4), knots.data());
    mPrevious.setSubData(first * kKnots * sizeof(glm::vec4), previous.size() * sizeof(glm::vec4),
                         previous.data());
  }
}

void GrassSimulator::activated(const TileSimulation& sim, int slot) {
  uploadSlotBlades(sim, slot, true);
}

void GrassSimulator::released(const TileSimulation& sim, int slot) {
  uploadSlotBlades(sim, slot, false);
}

void GrassSimulator::upload(const TileSimulation& sim) {
  for (std::size_t s = 0; s < sim.slots().size(); ++s) {
    if (sim.slots()[s].used) {
      uploadSlotBlades(sim, static_cast<int>(s), true);
    }
  }
}

void GrassSimulator::step(const TileSimulation& sim, float seconds, const std::vector<int>& slots,
                          const std::vector<std::vector<BladeCollider>>& colliders,
                          const wind::WindSettings& wind) {
  if (slots.empty()) {
    return;
  }
  const SolverConstants c = solverConstants(sim.solver());
  gpu::GrassSimUniforms u{};
  u.step = glm::vec4(c.dt, c.keep, c.gravityStep, c.maxStep);
  u.shape = glm::vec4(c.global, c.globalKnots, c.localShare, c.windDrag);
  u.trample = glm::vec4(c.trampleMass, c.softening, c.recoveryStep, 0.0f);
  u.counts = glm::ivec4(static_cast<int>(slots.size()), mPerTile, c.localPasses, c.lengthPasses);
  u.wind = wind::toUniforms(wind, seconds);
  mUniforms.setSubData(0, sizeof(u), &u);
  // The bodies near each used slot, one after another.
  std::vector<glm::uvec4> ranges(static_cast<std::size_t>(mSlots), glm::uvec4(0u));
  std::vector<gpu::GrassCollider> flat;
  for (const int s : slots) {
    const auto& list = colliders[static_cast<std::size_t>(s)];
    ranges[static_cast<std::size_t>(s)] =
        glm::uvec4(static_cast<unsigned>(flat.size()), static_cast<unsigned>(list.size()), 0u, 0u);
    for (const BladeCollider& b : list) {
      flat.push_back({glm::vec4(b.a, b.radius), glm::vec4(b.b, b.mass)});
    }
  }
  mRanges.setSubData(std::span<const glm::uvec4>(ranges));
  const std::size_t bytes = std::max<std::size_t>(flat.size(), 1) * sizeof(gpu::GrassCollider);
  if (!mColliders || mColliders.size() < bytes) {
    mColliders = gl::Buffer(std::bit_ceil(bytes));
  }
  if (!flat.empty()) {
    mColliders.setSubData(std::span<const gpu::GrassCollider>(flat));
  }
  std::vector<std::uint32_t> work(slots.begin(), slots.end());
  mWork.setSubData(std::span<const std::uint32_t>(work));
  mRenderer.bindFieldResources();
  mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_GRASS_SIM_BINDING);
  mPositions.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_POSITION_BINDING);
  mPrevious.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_PREVIOUS_BINDING);
  mBlades.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_BLADE_BINDING);
  mWork.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_WORK_BINDING);
  mColliders.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_COLLIDER_BINDING);
  mRanges.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_RANGE_BINDING);
  mSimulate.use();
  const std::size_t invocations = slots.size() * static_cast<std::size_t>(mPerTile);
  glDispatchCompute(static_cast<GLuint>((invocations + 63) / 64), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void GrassSimulator::syncSlots(const TileSimulation& sim) {
  std::vector<glm::ivec4> table(static_cast<std::size_t>(mSlots), glm::ivec4(0));
  for (std::size_t s = 0; s < sim.slots().size(); ++s) {
    const SimSlot& slot = sim.slots()[s];
    table[s] =
        glm::ivec4(slot.tile, slot.used ? 1 : 0, std::bit_cast<int>(slot.releasing ? slot.release : 0.0f));
  }
  mSlotTable.setSubData(std::span<const glm::ivec4>(table));
}

void GrassSimulator::bindForDrawing() const {
  mSlotTable.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_SLOT_BINDING);
  mPositions.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_GRASS_SIM_POSITION_BINDING);
}

std::vector<glm::vec3> GrassSimulator::readPositions() const {
  const std::vector<glm::vec4> raw = mPositions.read<glm::vec4>();
  std::vector<glm::vec3> out(raw.size());
  std::transform(raw.begin(), raw.end(), out.begin(), [](const glm::vec4& v) { return glm::vec3(v); });
  return out;
}

} // namespace sylva::grass
