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
#include <array>
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

/** A field drawn with its simulation on the GPU: a pool of `tiles`, culled to `distance` (far fade `fade`).
 */
struct SimulatedField {
  SimulatedField(const shader::Library& shaders, const std::shared_ptr<const GrassField>& f, int tiles,
                 float distance, float fade)
      : sim(f, PoolSettings{.tiles = tiles}, SolverSettings{}),
        renderer(shaders, f, CullSettings{.maxDistance = distance, .farFade = fade}),
        gpu(shaders, renderer, sim) {
    sim.setBackend(&gpu);
    renderer.setSimulation(&gpu);
  }
  TileSimulation sim;
  GrassRenderer renderer;
  GrassSimulator gpu;
};

TEST_F(GrassSimGpu, SimulatedTilesAreDrawnFromThePoolInTheSameDraw) {
  const auto f = field();
  SimulatedField simulated(shaders(), f, 32, 60.0f, 10.0f);
  TileSimulation& sim = simulated.sim;
  GrassRenderer& renderer = simulated.renderer;
  GrassSimulator& gpu = simulated.gpu;
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
  // Every blade of every visible simulated tile (and its near tufts) is drawn from the pool (16 knots), the
  // rest procedurally.
  EXPECT_GT(c.draws[3].y, 100u);
  EXPECT_EQ(c.draws[3].x, 32u);
  EXPECT_EQ(c.overflow.x, 0u);
  std::size_t simulatedBlades = 0;
  for (std::size_t i = 0; i < sim.blades().count(); ++i) {
    simulatedBlades += sim.bladeInUse(i) ? 1 : 0;
  }
  EXPECT_LE(c.draws[3].y, simulatedBlades + c.overflow.w); // and the near tufts that follow them
  if (renderer.lastVerticesSubmitted() >= 0) {
    const std::uint64_t expected =
        32ull * c.draws[0].y + 16ull * c.draws[1].y + 8ull * c.draws[2].y + 32ull * c.draws[3].y;
    EXPECT_EQ(static_cast<std::uint64_t>(renderer.lastVerticesSubmitted()), expected);
  }
}

/** Share of the pixels of two images that differ by more than 8 levels in some channel. */
double changedShare(const Image& a, const Image& b) {
  int changed = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      for (int c = 0; c < 3; ++c) {
        if (std::abs(a.get(x, y, c) - b.get(x, y, c)) > 8.0f / 255.0f) {
          ++changed;
          break;
        }
      }
    }
  }
  return static_cast<double>(changed) / static_cast<double>(a.width() * a.height());
}

TEST_F(GrassSimGpu, TuftBladesFollowTheirSimulatedBlades) {
  const auto f = field();
  SimulatedField simulated(shaders(), f, 160, 45.0f, 6.0f);
  TileSimulation& sim = simulated.sim;
  GrassRenderer& withSim = simulated.renderer;
  GrassSimulator& gpu = simulated.gpu;
  const CullSettings cull = withSim.cullSettings();
  GrassRenderer plain(shaders(), f, cull);
  // Over the grass, looking down at the path a heavy ball rolls along x at z = 20 (4 m ahead).
  const float ground = terrain::heightAt(f->terrain(), 20.0f, 16.0f);
  render::Camera camera;
  camera.position = {20.0f, ground + 1.6f, 16.0f};
  camera.target = {20.0f, terrain::heightAt(f->terrain(), 20.0f, 20.0f), 20.0f};
  camera.nearPlane = 0.05f;
  const int width = 320;
  const int height = 180;
  const wind::WindSettings calm{.speed = 0.0f};
  const auto frame = [&](GrassRenderer& renderer, double time) {
    const render::Camera& c = camera;
    render::RenderTarget target(width, height);
    target.begin(glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    renderer.cull(c, target.aspect());
    GrassDrawOptions options;
    options.wind = calm;
    renderer.draw(c, width, height, time, nullptr, options);
    return std::pair(target.readColor(), renderer.readCounters());
  };
  // Every tile within 10 m simulated at its procedural pose: tufts and blades drawn where they were.
  for (int tz = 0; tz < f->layout().tilesZ; ++tz) {
    for (int tx = 0; tx < f->layout().tilesX; ++tx) {
      const glm::vec2 centre = (glm::vec2(tx, tz) + 0.5f) * f->layout().tileSize;
      if (glm::length(centre - glm::vec2(camera.position.x, camera.position.z)) < 10.0f) {
        ASSERT_TRUE(sim.activateTile({tx, tz}, calm));
      }
    }
  }
  gpu.syncSlots(sim);
  const auto [activated, activatedCounts] = frame(withSim, sim.time());
  const auto [procedural, proceduralCounts] = frame(plain, sim.time());
  EXPECT_GT(activatedCounts.draws[3].y, 3000u) << "blades and tufts drawn from the pool";
  EXPECT_GT(activatedCounts.overflow.w, 2000u) << "tuft blades";
  EXPECT_EQ(activatedCounts.overflow.x, 0u);
  const double popped = changedShare(activated, procedural);
  std::printf("activation: %.3f %% of pixels change by more than 8 levels\n", 100.0 * popped);
  EXPECT_LT(popped, 0.002) << "simulated tiles must start where the procedural field was drawn";
  // A 5 kg ball rolls across; a second later the path's blades lie flat, and the tufts beside them with them:
  // the trampled frame differs from the standing one by several times what it does without tufts (tufts
  // drawn standing would hide the flattened blades instead).
  for (int i = 1; i <= 90; ++i) {
    const double t = sim.time() + 1.0 / 60.0;
    const float x = 16.0f + 8.0f * static_cast<float>(std::min(t, 1.0));
    const float y = terrain::heightAt(f->terrain(), x, 20.0f) + 0.4f;
    SimBody ball;
    ball.shape = {glm::vec3(x, y, 20.0f), glm::vec3(x, y, 20.0f), 0.4f, 5.0f};
    ball.box = {ball.shape.a - 0.4f, ball.shape.a + 0.4f};
    sim.advance(t, {ball}, calm);
  }
  gpu.syncSlots(sim);
  const Image trampled = frame(withSim, sim.time()).first;
  const Image standing = frame(plain, sim.time()).first;
  const double withTufts = changedShare(trampled, standing);
  // Flattened blades catch the sky (a paler, glossier path, as trampled grass looks): over the pixels the
  // trampling changed, the grass of the trampled frame is brighter than the grass of the standing one.
  const auto luminance = [](const Image& image, int x, int y) {
    return 0.2126 * image.get(x, y, 0) + 0.7152 * image.get(x, y, 1) + 0.0722 * image.get(x, y, 2);
  };
  const auto isGrass = [](const Image& image, int x, int y) {
    return std::abs(image.get(x, y, 2) - 1.0f) > 0.02f;
  };
  std::array<double, 2> light{0.0, 0.0};
  std::array<int, 2> grassPixels{0, 0};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (std::abs(luminance(trampled, x, y) - luminance(standing, x, y)) <= 8.0 / 255.0) {
        continue;
      }
      for (int k = 0; k < 2; ++k) {
        const Image& image = k == 0 ? trampled : standing;
        if (isGrass(image, x, y)) {
          light[static_cast<std::size_t>(k)] += luminance(image, x, y);
          ++grassPixels[static_cast<std::size_t>(k)];
        }
      }
    }
  }
  ASSERT_GT(grassPixels[0], 100);
  ASSERT_GT(grassPixels[1], 100);
  const double paler = light[0] / grassPixels[0];
  const double before = light[1] / grassPixels[1];
  std::printf("trampled path: grass luminance %.3f trampled (%d px), %.3f standing (%d px)\n", paler,
              grassPixels[0], before, grassPixels[1]);
  EXPECT_GT(paler, 1.03 * before); // 1.000 with the flattened shading off
  CullSettings noTufts = cull;
  noTufts.nearLayers = 1;
  withSim.setCullSettings(noTufts);
  plain.setCullSettings(noTufts);
  const double fieldOnly = changedShare(frame(withSim, sim.time()).first, frame(plain, sim.time()).first);
  std::printf("trampled path: %.2f %% of pixels change with tufts, %.2f %% without\n", 100.0 * withTufts,
              100.0 * fieldOnly);
  EXPECT_GT(fieldOnly, 0.002);
  EXPECT_GT(withTufts, 2.5 * fieldOnly);
}

} // namespace
} // namespace sylva::grass
