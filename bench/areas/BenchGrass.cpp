#include "Bench.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/gl/Debug.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/grass/gpu/GrassSimulator.hpp>
#include <sylva/scene/gpu/GrassSimulation.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <grass/SolverCase.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/gpu/TerrainPopping.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <numeric>
#include <unistd.h>

namespace sylva::bench {

namespace {

using grass::bench::paperFieldSettings;

} // namespace

/**
 * `bench grass`: the paper's field (14,926 tiles of 2 m, 64 blades each: 955,264 blades in one draw, seen
 * whole), the demo's ground view, memory against the paper's 24 MB patch, and LOD popping: pixels that change
 * when the LOD boundary moves past blades (camera still), with dithered cross-fades and with hard switches.
 */
void benchGrass(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  shader::Library library;
  render::RenderTarget target(o.width, o.height);
  const std::string rendererName = gl::queryContextInfo().renderer;
  std::vector<BenchRow> rows;
  report = header(o, "grass", context);

  // 1. The paper's field: 34 x 439 tiles = 14,926, full density, every blade drawn: a 69 x 879 m terrain of
  // 1 m samples under one grass layer of one density everywhere (no density noise, no splat layer). The
  // paper's frame is terrain and grass: no shadows, sky or flare.
  scene::SceneDesc paperDesc;
  paperDesc.path = "bench grass";
  paperDesc.name = "paper field";
  terrain::TerrainSetup& setup = paperDesc.terrain.setup.emplace();
  setup.source.procedural = terrain::TerrainSource::defaultProcedural();
  setup.source.procedural.heightScale = 6.0f;
  setup.source.procedural.frequency = 1.0f / 150.0f;
  setup.source.proceduralSize = 69;
  setup.source.proceduralRows = 879;
  setup.source.proceduralSpacing = 1.0f;
  setup.seaLevel.kind = terrain::SeaLevelRule::Kind::None;
  setup.quadtree.rootSize = 128.0f;
  setup.maxDepth = 4;
  scene::GrassLayer& paperLayer = paperDesc.grass.emplace_back();
  paperLayer.layer = "none";
  paperLayer.noiseFrequency = 0.0f;
  paperLayer.maxSlope = 90.0f;
  paperLayer.patchBlades = 16384;
  paperLayer.bladesPerTile = 64;
  grass::CullSettings& all = paperLayer.cull.emplace();
  all.maxDistance = 5000.0f;
  all.orientationCos = 0.0f;
  paperDesc.wind.speed = 3.0f;
  paperDesc.shadows.cascades = 0;
  paperDesc.sky.flare = false;
  scene::SceneWorld paperWorld(library, paperDesc);
  paperWorld.passes().setEnabled(scene::Pass::Sky, false);
  grass::GrassRenderer& paperGrass = paperWorld.grass(0);
  const grass::GrassField& paperField = paperGrass.field();
  const std::size_t fieldBlades = paperField.countBlades();
  const std::size_t tiles = static_cast<std::size_t>(paperField.layout().tilesX) *
                            static_cast<std::size_t>(paperField.layout().tilesZ);
  const render::Camera camera =
      paperWorld.terrain().frameCamera(render::ViewFrom::SouthWest, glm::radians(50.0f), target.aspect());
  const auto frame = [&](scene::SceneWorld& world, const render::Camera& view, double time,
                         render::GpuTimers* timers) {
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    world.draw(view, o.width, o.height, time, &target.depth(), timers);
  };
  const Samples paper = measure(o, [&](render::GpuTimers& timers, int i, Samples&) {
    frame(paperWorld, camera, 1.0 + i / 60.0, &timers);
  });
  const gpu::GrassCounters counters = paperGrass.readCounters();
  const double drawnBlades = counters.blades.x;
  const auto wallOf = [](const Samples& s, const std::string& pass) {
    return s.wall.count(pass) != 0 ? render::Stats::of(s.wall.at(pass)).median : std::nan("");
  };
  const double cullMs = wallOf(paper, "grass cull");
  const double drawMs = wallOf(paper, "grass");
  const double frameMs = render::Stats::of(paper.frame).median;
  const std::int64_t triangles =
      paper.countsOf("grass").primitivesSubmitted; // the pass's pipeline statistics
  std::printf("grass: the paper's field, %zu tiles, %zu blades, %dx%d, %s\n", tiles, fieldBlades, o.width,
              o.height, rendererName.c_str());
  const std::string paperNote = "paper: 20 ms on a Radeon R9 270";
  rows.push_back({"paper field: tiles", static_cast<double>(tiles), "tiles", 14926.0, false, 0, ""});
  rows.push_back({"paper field: blades drawn in one draw", drawnBlades, "blades", 955264.0, false, 0,
                  fmt::format("{} triangles", triangles)});
  rows.push_back({"paper field: grass cull + draw", cullMs + drawMs, "ms", 20.0, true, 0, paperNote});
  rows.push_back({"paper field: culling passes", cullMs, "ms", std::nan(""), true, 0, "3 compute passes"});
  rows.push_back(
      {"paper field: whole frame (terrain + grass, wall)", frameMs, "ms", std::nan(""), true, 0, ""});
  rows.push_back({"paper field: blades drawn per second", drawnBlades / ((cullMs + drawMs) * 1e-3) / 1e6,
                  "M blades/s", 955264.0 / 0.020 / 1e6, false, 0, "target: the paper's rate"});
  rows.push_back({"patch memory (16,384 blades + 3 types)",
                  static_cast<double>(grass::patchBytes(16384, 3)) / 1e6, "MB", 24.0, true, 0,
                  "paper: about 24 MB"});
  rows.push_back({"storing every blade of the paper field instead",
                  static_cast<double>(grass::perBladeFieldBytes(fieldBlades)) / 1e6, "MB", std::nan(""), true,
                  0, "16 knots + widths per blade"});
  rows.push_back({"grass GPU memory (paper field, all buffers)",
                  static_cast<double>(paperGrass.gpuBytes()) / 1e6, "MB", std::nan(""), true, 0,
                  "instance lists sized for the draw distance"});

  // 2. The demo's ground view: the terrain of the command line (default: the demo landscape) under a grass
  // layer of the --grass defaults, as `sylva render --grass` draws it (shadows, sky, flare).
  scene::SceneWorld demoWorld(library, o.groundWorld);
  grass::GrassRenderer& demoGrass = demoWorld.grass(0);
  const render::Camera ground = o.groundCamera(demoWorld, target.aspect());
  const Samples demoSamples = measure(o, [&](render::GpuTimers& timers, int i, Samples&) {
    frame(demoWorld, ground, 1.0 + i / 60.0, &timers);
  });
  const gpu::GrassCounters demoCounters = demoGrass.readCounters();
  rows.push_back({"demo ground view: blades drawn", static_cast<double>(demoCounters.blades.x), "blades",
                  std::nan(""), false, 0,
                  fmt::format("{} visible tiles of {} blades", demoCounters.dispatch.x,
                              demoGrass.field().layout().bladesPerTile)});
  rows.push_back({"demo ground view: grass cull + draw",
                  wallOf(demoSamples, "grass cull") + wallOf(demoSamples, "grass"), "ms", std::nan(""), true,
                  0, ""});
  rows.push_back({"demo ground view: whole frame (wall)", render::Stats::of(demoSamples.frame).median, "ms",
                  std::nan(""), true, 0, "with sun shadows, sky and flare"});
  // What the near tufts cost: the same view with them off.
  rows.push_back({"demo ground view: of which near tufts", static_cast<double>(demoCounters.overflow.w),
                  "blades", std::nan(""), false, 0,
                  fmt::format("{} layers within {} m", demoGrass.cullSettings().nearLayers,
                              grass::nearReach(demoGrass.cullSettings()))});
  {
    const grass::CullSettings withTufts = demoGrass.cullSettings();
    grass::CullSettings noTufts = withTufts;
    noTufts.nearLayers = 1;
    demoGrass.setCullSettings(noTufts);
    const Samples plainSamples = measure(o, [&](render::GpuTimers& timers, int i, Samples&) {
      frame(demoWorld, ground, 1.0 + i / 60.0, &timers);
    });
    demoGrass.setCullSettings(withTufts);
    rows.push_back({"demo ground view without near tufts: grass cull + draw",
                    wallOf(plainSamples, "grass cull") + wallOf(plainSamples, "grass"), "ms", std::nan(""),
                    true, 0, "--grass-near-layers 1"});
  }

  // 3. Popping: the camera stays; the LOD boundaries move by 0.25 m (what a 0.25 m step of the camera does
  // to the blades near them, without the parallax). Pixels changing by more than 5 % in any channel.
  const auto still = [&](const grass::CullSettings& settings) {
    demoGrass.setCullSettings(settings);
    frame(demoWorld, ground, 1.0, nullptr);
    return target.readColor();
  };
  const grass::CullSettings base = demoGrass.cullSettings();
  const auto shifted = [](grass::CullSettings s, float by) {
    s.lodDistances = {s.lodDistances[0] - by, s.lodDistances[1] - by};
    return s;
  };
  grass::CullSettings hard = base;
  hard.lodFade = 0.0f;
  const double faded = terrain::changedPixelFraction(still(base), still(shifted(base, 0.25f)), 0.05f);
  const double popped = terrain::changedPixelFraction(still(hard), still(shifted(hard, 0.25f)), 0.05f);
  // The draw distance moved by 1 m: blades dissolving into the ground tint over the far fade, or cut.
  const auto nearer = [](grass::CullSettings s) {
    s.maxDistance -= 1.0f;
    return s;
  };
  // The near tufts' reach moved by 0.25 m: each layer dissolves over the last quarter of its reach.
  const auto nearerTufts = [](grass::CullSettings s) {
    s.nearDistance -= 0.25f;
    return s;
  };
  const double tuftsFaded = terrain::changedPixelFraction(still(base), still(nearerTufts(base)), 0.05f);
  grass::CullSettings cut = base;
  cut.farFade = 0.0f;
  const double farFaded = terrain::changedPixelFraction(still(base), still(nearer(base)), 0.05f);
  const double farCut = terrain::changedPixelFraction(still(cut), still(nearer(cut)), 0.05f);
  // The same 0.25 m step of the camera, across the boundaries and with one level everywhere (no boundary).
  const auto step = [&](const grass::CullSettings& settings) {
    demoGrass.setCullSettings(settings);
    render::Camera moved = ground;
    const glm::vec3 forward = glm::normalize(
        glm::vec3(ground.target.x - ground.position.x, 0.0f, ground.target.z - ground.position.z));
    moved.position += forward * 0.25f;
    moved.target += forward * 0.25f;
    frame(demoWorld, ground, 1.0, nullptr);
    const Image a = target.readColor();
    frame(demoWorld, moved, 1.0, nullptr);
    return terrain::changedPixelFraction(a, target.readColor(), 0.05f);
  };
  grass::CullSettings single = base;
  single.lodDistances = {base.maxDistance - base.farFade - 2.0f * base.lodFade,
                         base.maxDistance - base.farFade - base.lodFade};
  const double acrossFaded = step(base);
  const double acrossHard = step(hard);
  const double inside = step(single);
  demoGrass.setCullSettings(base);
  rows.push_back({"popping: boundary moved 0.25 m, dithered cross-fade", faded * 100.0, "% pixels",
                  std::nan(""), true, 0, "changed > 5 %, camera still"});
  rows.push_back({"popping: boundary moved 0.25 m, hard switch", popped * 100.0, "% pixels", std::nan(""),
                  true, 0, "the same without cross-fade"});
  rows.push_back({"popping: near tufts' reach moved 0.25 m (dithered)", tuftsFaded * 100.0, "% pixels",
                  std::nan(""), true, 0, "changed > 5 %, camera still"});
  rows.push_back({"draw distance moved 1 m, far fade into the ground tint", farFaded * 100.0, "% pixels",
                  std::nan(""), true, 0, "changed > 5 %, camera still"});
  rows.push_back(
      {"draw distance moved 1 m, hard cut", farCut * 100.0, "% pixels", std::nan(""), true, 0, ""});
  rows.push_back({"camera step 0.25 m across LOD boundaries (cross-fade)", acrossFaded * 100.0, "% pixels",
                  inside * 100.0 * 1.1, true, 0, "target: within 10 % of the same step inside one band"});
  rows.push_back({"camera step 0.25 m across LOD boundaries (hard switch)", acrossHard * 100.0, "% pixels",
                  std::nan(""), true, 0, ""});
  rows.push_back({"camera step 0.25 m inside one LOD band", inside * 100.0, "% pixels", std::nan(""), true, 0,
                  "parallax alone"});
  report["rows"] = printBenchRows(rows);
  report["paper_field"] = {
      {"tiles", tiles}, {"blades", fieldBlades}, {"triangles", triangles}, {"passes", paper.passesJson()}};
  report["demo_passes"] = demoSamples.passesJson();
}

/**
 * `bench grass-sim`: the paper's Table 1 workloads (6/14/150/709 simulated tiles of 64 blades with
 * 1/2/20/128 bodies) stepped by the CPU reference (all cores) and the compute shader, and the GPU target
 * workload (500,000 blades, 1,024 bodies). Solver steps only (rest poses, constraints, collisions), medians.
 */
void benchGrassSim(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report) {
  shader::Library library;
  const std::string rendererName = gl::queryContextInfo().renderer;
  report = header(o, "grass-sim", context);
  const std::shared_ptr<grass::GrassField> field = grass::bench::solverField();
  grass::GrassRenderer renderer(library, field);
  const wind::WindSettings wind = grass::bench::solverWind();
  struct Workload {
    int tiles;
    int bodies;
    double paperMs;
  };
  const Workload table1[] = {{6, 1, 0.176}, {14, 2, 0.183}, {150, 20, 0.952}, {709, 128, 4.67}};
  constexpr int kRuns = 15;
  constexpr int kWarmup = 3;
  const auto cpuMs = [&](int tiles, int bodies, std::size_t& blades) {
    grass::PoolSettings pool;
    pool.tiles = tiles;
    grass::TileSimulation sim(field, pool, grass::SolverSettings{});
    const std::vector<std::vector<grass::BladeCollider>> colliders =
        grass::bench::setUpSolverCase(sim, *field, tiles, bodies, wind);
    blades = 0;
    for (std::size_t i = 0; i < sim.blades().count(); ++i) {
      blades += sim.bladeInUse(i) ? 1 : 0;
    }
    return render::Stats::of(timeRuns(kWarmup, kRuns, [&] { sim.stepSolver(colliders, wind); })).median * 1e3;
  };
  const auto gpuMs = [&](int tiles, int bodies) {
    grass::PoolSettings pool;
    pool.tiles = tiles;
    grass::TileSimulation sim(field, pool, grass::SolverSettings{});
    grass::GrassSimulator gpu(library, renderer, sim);
    sim.setBackend(&gpu);
    const std::vector<std::vector<grass::BladeCollider>> colliders =
        grass::bench::setUpSolverCase(sim, *field, tiles, bodies, wind);
    gl::finish();
    return render::Stats::of(timeRuns(kWarmup, kRuns,
                                      [&] {
                                        sim.stepSolver(colliders, wind);
                                        gl::finish();
                                      }))
               .median *
           1e3;
  };
  const MachineInfo machine = machineInfo();
  std::printf(
      "grass-sim: solver steps (16 knots, 2 local and 2 length passes), CPU %s (%u threads), GPU %s\n",
      machine.cpu.c_str(), workerCount(), rendererName.c_str());
  std::vector<BenchRow> rows;
  nlohmann::json table = nlohmann::json::array();
  for (const Workload& w : table1) {
    std::size_t blades = 0;
    const double cpu = cpuMs(w.tiles, w.bodies, blades);
    const double gpu = gpuMs(w.tiles, w.bodies);
    const bool largest = w.tiles == 709;
    const std::string what =
        fmt::format("Table 1: {} tiles, {} bodies, {} blades", w.tiles, w.bodies, blades);
    rows.push_back({what + ", CPU", cpu, "ms/step", largest ? 10.0 : std::nan(""), true, workerCount(),
                    fmt::format("paper (GPU): {} ms; {:.0f} ns/blade", w.paperMs, cpu * 1e6 / blades)});
    rows.push_back({what + ", GPU", gpu, "ms/step", std::nan(""), true, 0,
                    fmt::format("{}; {:.0f} ns/blade", rendererName.substr(0, 24), gpu * 1e6 / blades)});
    table.push_back({{"tiles", w.tiles},
                     {"bodies", w.bodies},
                     {"blades", blades},
                     {"cpu_ms", cpu},
                     {"gpu_ms", gpu},
                     {"paper_ms", w.paperMs}});
  }
  // The GPU target: 500,000 simulated blades (7,813 tiles of 64) with 1,024 bodies in 3 ms.
  const double big = gpuMs(7813, 1024);
  rows.push_back({"500,000 blades, 1,024 bodies, GPU", big, "ms/step", 3.0, true, 0,
                  fmt::format("{}; target for an NVIDIA GPU", rendererName.substr(0, 24))});
  report["rows"] = printBenchRows(rows);
  report["table1"] = table;
}

} // namespace sylva::bench
