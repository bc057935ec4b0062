// The grass solver's compute shader against the CPU reference: a scripted scene (balls rolling across a small
// field in gusty wind) stepped 120 times by both, blade by blade within 1e-4 m; and simulated tiles drawn
// from the pool in the field's one draw.
#include <sylva/grass/gpu/GrassSimulator.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/Noise.hpp>

#include "GlTest.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::grass {
namespace {

using GrassSimGpu = test::GlTest;

std::shared_ptr<const GrassField> field() {
  terrain::ProceduralSpec spec = terrain::defaultLandscapeSpec(4);
  spec.heightScale = 3.0f;
  FieldSettings fs;
  fs.patch.blades = 4096;
  fs.bladesPerTile = 96;
  fs.density.coverage = 1.0f;
  fs.density.noiseFrequency = 0.0f;
  return std::make_shared<GrassField>(terrain::generate(spec, 0.0, 0.0, 41, 41, 1.0f), proceduralBladeTypes(),
                                      fs);
}

/** Two balls on scripted paths at time t, of mass `mass`: one rolling across, one bouncing on the blades. */
std::vector<SimBody> bodiesAt(const GrassField& f, double t, float mass = 1.0f) {
  std::vector<SimBody> out;
  const auto ball = [&](glm::vec2 xz, float radius, float lift) {
    const float y = terrain::heightAt(f.terrain(), xz.x, xz.y) + radius + lift;
    SimBody b;
    b.shape = {glm::vec3(xz.x, y, xz.y), glm::vec3(xz.x, y, xz.y), radius, mass};
    b.box = {b.shape.a - radius, b.shape.a + radius};
    out.push_back(b);
  };
  const auto s = static_cast<float>(t);
  ball({14.0f + 6.0f * s, 18.0f + 1.5f * s}, 0.45f, 0.0f);
  ball({24.0f - 3.0f * s, 22.0f}, 0.3f, 0.2f * std::abs(std::sin(6.0f * s)));
  return out;
}

/** CPU and GPU runs of the same 120 steps; the largest knot difference of each blade. */
struct Parity {
  std::vector<double> perBlade;
  double moved = 0.0;
};

Parity runBoth(const std::shared_ptr<const GrassField>& f, float mass, const shader::Library& shaders) {
  PoolSettings pool;
  pool.tiles = 64;
  pool.releaseTime = 0.3f;
  SolverSettings solver;
  solver.windDrag = 0.2f;
  wind::WindSettings wind;
  wind.speed = 6.0f;
  wind.direction = {0.6f, 0.8f};
  TileSimulation cpu(f, pool, solver);
  TileSimulation gpuSim(f, pool, solver);
  GrassRenderer renderer(shaders, f);
  GrassSimulator gpu(shaders, renderer, gpuSim);
  gpuSim.setBackend(&gpu);
  for (int i = 1; i <= 120; ++i) {
    const double t = i / 60.0;
    cpu.advance(t, bodiesAt(*f, t, mass), wind);
    gpuSim.advance(t, bodiesAt(*f, t, mass), wind);
  }
  EXPECT_EQ(cpu.stats().activeTiles, gpuSim.stats().activeTiles);
  const std::vector<glm::vec3> positions = gpu.readPositions();
  Parity p;
  for (std::size_t i = 0; i < cpu.blades().count(); ++i) {
    if (!cpu.bladeInUse(i)) {
      continue;
    }
    EXPECT_TRUE(gpuSim.bladeInUse(i));
    double worst = 0.0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(kSimKnots); ++k) {
      const std::size_t at = i * kSimKnots + k;
      worst = std::max<double>(worst, glm::length(positions[at] - cpu.blades().position[at]));
      p.moved = std::max<double>(p.moved, glm::length(cpu.blades().position[at] - cpu.blades().rest[at]));
    }
    p.perBlade.push_back(worst);
  }
  return p;
}

TEST_F(GrassSimGpu, ComputeShaderMatchesTheCpuSolver) {
  // Balls rolling and bouncing through the blades in gusty wind with drag: 120 steps, every knot of every
  // simulated blade within 1e-4 m.
  const Parity p = runBoth(field(), 1.0f, shaders());
  ASSERT_GT(p.perBlade.size(), 500u);
  const double worst = *std::max_element(p.perBlade.begin(), p.perBlade.end());
  std::printf(
      "solver parity after 120 steps: %zu blades, worst %.3g m (largest displacement from rest %.3f m)\n",
      p.perBlade.size(), worst, p.moved);
  RecordProperty("worst_m", std::to_string(worst));
  EXPECT_GT(p.moved, 0.1) << "the balls and the wind moved blades";
  EXPECT_LT(worst, 1e-4);
}

TEST_F(GrassSimGpu, TrampledBladesStayCloseThoughTheyHaveNoRestoringForce) {
  // The same scene with heavy balls: trampled blades lose 97 % of their stiffness, so rounding differences
  // between the two solvers no longer decay (they lie where they were pushed). Nearly all blades still agree
  // within 1e-4 m and none drifts apart.
  const Parity p = runBoth(field(), 40.0f, shaders());
  ASSERT_GT(p.perBlade.size(), 1000u);
  const auto within = static_cast<double>(
      std::count_if(p.perBlade.begin(), p.perBlade.end(), [](double d) { return d < 1e-4; }));
  const double worst = *std::max_element(p.perBlade.begin(), p.perBlade.end());
  std::printf("trampling scene: %.2f %% of %zu blades within 1e-4 m, worst %.3g m\n",
              100.0 * within / static_cast<double>(p.perBlade.size()), p.perBlade.size(), worst);
  EXPECT_GT(within / static_cast<double>(p.perBlade.size()), 0.97);
  EXPECT_LT(worst, 3e-3);
}

TEST_F(GrassSimGpu, SimulatedTilesAreDrawnFromThePoolInTheSameDraw) {
  const auto f = field();
  PoolSettings pool;
  pool.tiles = 32;
  TileSimulation sim(f, pool, SolverSettings{});
  CullSettings cull;
  cull.maxDistance = 60.0f;
  cull.farFade = 10.0f;
  GrassRenderer renderer(shaders(), f, cull);
  GrassSimulator gpu(shaders(), renderer, sim);
  sim.setBackend(&gpu);
  renderer.setSimulation(&gpu);
  const std::vector<SimBody> bodies = bodiesAt(*f, 0.0);
  sim.advance(0.5, bodies, {});
  gpu.syncSlots(sim);
  render::Camera camera;
  camera.position = {8.0f, terrain::heightAt(f->terrain(), 8.0f, 8.0f) + 4.0f, 8.0f};
  camera.target = {16.0f, terrain::heightAt(f->terrain(), 16.0f, 19.0f), 19.0f};
  camera.nearPlane = 0.05f;
  render::RenderTarget target(320, 180);
  target.begin(glm::vec4(0.5f, 0.6f, 0.8f, 1.0f));
  renderer.cull(camera, target.aspect());
  GrassDrawOptions options;
  options.countPrimitives = true;
  renderer.draw(camera, 320, 180, 0.5, nullptr, options);
  const gpu::GrassCounters c = renderer.readCounters();
  // Every blade of every visible simulated tile is drawn from the pool (16 knots), the rest procedurally.
  EXPECT_GT(c.draws[3].y, 100u);
  EXPECT_EQ(c.draws[3].x, 32u);
  EXPECT_EQ(c.overflow.x, 0u);
  std::size_t simulatedBlades = 0;
  for (std::size_t i = 0; i < sim.blades().count(); ++i) {
    simulatedBlades += sim.bladeInUse(i) ? 1 : 0;
  }
  EXPECT_LE(c.draws[3].y, simulatedBlades);
  if (renderer.lastVerticesSubmitted() >= 0) {
    const std::uint64_t expected =
        32ull * c.draws[0].y + 16ull * c.draws[1].y + 8ull * c.draws[2].y + 32ull * c.draws[3].y;
    EXPECT_EQ(static_cast<std::uint64_t>(renderer.lastVerticesSubmitted()), expected);
  }
}

} // namespace
} // namespace sylva::grass
