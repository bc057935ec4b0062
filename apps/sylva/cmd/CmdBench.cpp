// `sylva bench <area>` (docs/cli.md): the command line of the benchmarks in bench/areas (sylva::bench), which
// measure; this file only turns options into a bench::BenchOptions and picks the area.
#include "Commands.hpp"
#include "flags/TerrainFlags.hpp"
#include "flags/WorldFlags.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include "Bench.hpp"

#include <cstdio>
#include <memory>

namespace sylva::app {

namespace {

/** The options of `sylva bench`. */
struct BenchFlags {
  std::string area = "demo";
  ContextFlags context;
  TerrainFlags terrain;
  int frames = 60;
  int warmup = 5;
  int width = 1280;
  int height = 720;
  std::string out;
  double maxGrowthPercent = 1.0;
  std::string sceneFile; // empty: the data folder's scenes/meadow.json
  std::string quality = "default";
  double targetFps = 10.0;
  int fieldSize = 4097;             // terrain-error: samples per side of the ridged procedural fields
  bench::StreamBenchOptions stream; // terrain-stream
  double gpuBudgetMb = 256.0;
  double ramBudgetMb = 512.0;

  /** What the area measures; throws naming the option when the terrain options do not go together. */
  bench::BenchOptions options() const {
    bench::BenchOptions b;
    b.context = context.options();
    b.terrain = terrain.setup();
    b.terrainFieldName = terrainOption;
    b.terrainSource = terrain.source.describe();
    b.frames = frames;
    b.warmup = warmup;
    b.width = width;
    b.height = height;
    b.maxGrowthPercent = maxGrowthPercent;
    if (area == "grass") {
      // The demo's ground view: the terrain of the options under a grass layer of the --grass defaults, as
      // `sylva render --grass` draws it.
      auto world = std::make_shared<WorldFlags>();
      world->terrain = terrain;
      world->grass.enabled = true;
      b.groundWorld = world->desc("bench grass", false);
      b.groundCamera = [world](scene::SceneWorld& w, float aspect) { return world->start(w, aspect); };
    }
    return b;
  }
};

/** The benchmarks that draw: each on one headless context. */
void runGlBench(const BenchFlags& o, const bench::BenchOptions& options, nlohmann::json& report) {
  auto context = platform::createHeadlessContext(options.context);
  if (o.area == "terrain") {
    bench::benchTerrain(options, *context, report);
  } else if (o.area == "terrain-error") {
    bench::benchTerrainError(options, *context, o.fieldSize, report);
  } else if (o.area == "terrain-stream") {
    bench::StreamBenchOptions s = o.stream;
    s.gpuBudget = static_cast<std::size_t>(o.gpuBudgetMb * 1.0e6);
    s.ramBudget = static_cast<std::size_t>(o.ramBudgetMb * 1.0e6);
    bench::benchTerrainStream(options, *context, s, report);
  } else if (o.area == "grass") {
    bench::benchGrass(options, *context, report);
  } else if (o.area == "grass-sim") {
    bench::benchGrassSim(options, *context, report);
  } else if (o.area == "trees") {
    report = bench::header(options, "trees", *context);
    bench::benchTrees(o.frames, o.width, o.height, report);
  } else if (o.area == "scene") {
#ifdef SYLVA_HAVE_SCENE
    report = bench::header(options, "scene", *context);
    bench::benchScene(o.sceneFile.empty() ? dataPath("scenes/meadow.json").string() : o.sceneFile, o.frames,
                      o.warmup, o.width, o.height, o.quality, o.targetFps, report);
#else
    fail("bench scene: this sylva was built without the scene module");
#endif
  } else if (o.area == "soak") {
    bench::benchSoak(options, *context, report);
  } else {
    bench::benchDemo(options, *context, report);
  }
}
} // namespace

void registerBench(CLI::App& app) {
  auto* command = app.add_subcommand(
      "bench", "Measure CPU and GPU time per pass over N frames; prints a table and writes JSON");
  auto o = std::make_shared<BenchFlags>();
  command
      ->add_option(
          "area", o->area,
          "demo (pipeline scene), terrain (the paper's Table 8, both crack methods) or terrain-error "
          "(distance LOD against screen-space-error LOD at the same measured worst error of 1 px, "
          "--frames camera poses on each of three fields) or terrain-stream (a flight of --distance km at "
          "--speed m/s across the 2^20 x 2^20-sample procedural world or a --pyramid, streamed within "
          "--gpu-budget and --ram-budget: memory, tiles loaded per second, frames that waited, height "
          "queries against the drawn surface) or soak (long "
          "run of the terrain scene: memory growth, GL errors, frame-time drift; exit 1 on failure) "
          "or fold (folding-texture targets on a generated 1 MP case) or capture (grass capture: "
          "extraction latency per 640x480 frame, refining) or grass (the paper's 955,264-blade field "
          "in one draw, patch memory, culling, LOD popping) or grass-sim (the paper's Table 1 workloads "
          "on the CPU and GPU solvers, and 500,000 blades with 1,024 bodies) or trees (the paper's Fig. 16 "
          "workloads instanced and per piece, tessellation cost, foliage, 1,000 animated + 100,000 impostor "
          "trees, generation, wind on joints, bark tile sets) or scene (a scene file's frames, --scene: "
          "per-pass CPU, GPU and wall times, frames per second, memory)")
      ->check(CLI::IsMember({"demo", "terrain", "terrain-error", "terrain-stream", "soak", "fold", "capture",
                             "grass", "grass-sim", "trees", "scene"}))
      ->capture_default_str();
  o->context.add(*command);
  o->terrain.add(*command);
  command->add_option("--frames", o->frames, "Measured frames (per configuration)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->add_option("--warmup", o->warmup, "Frames run before measuring")
      ->check(CLI::Range(0, 10000))
      ->capture_default_str();
  command->add_option("--width", o->width, "Target width in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  command->add_option("--height", o->height, "Target height in pixels")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "JSON report path (default: out/bench-<area>.json)");
  command
      ->add_option("--scene", o->sceneFile,
                   "scene: the scene file to measure (default: the data folder's scenes/meadow.json, "
                   "wherever sylva runs)")
      ->check(CLI::ExistingFile);
  command
      ->add_option(
          "--quality", o->quality,
          "scene: default, full (every shadow cascade every frame, for comparisons; docs/performance.md) or "
          "auto (the viewer's loop: quality steps chosen to keep --target-fps, scene time moving on by each "
          "frame's wall time)")
      ->check(CLI::IsMember({"default", "full", "auto"}))
      ->capture_default_str();
  command
      ->add_option("--field-size", o->fieldSize,
                   "terrain-error: samples per side of the two ridged procedural fields (2 m spacing; 16384 "
                   "needs a GPU: every pose is also drawn at full depth)")
      ->check(CLI::Range(17, 16384))
      ->capture_default_str();
  command->add_option("--distance", o->stream.distanceKm, "terrain-stream: flight length, km")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  command->add_option("--speed", o->stream.speed, "terrain-stream: metres per second")
      ->check(CLI::Range(1.0, 100000.0))
      ->capture_default_str();
  command->add_option("--sim-fps", o->stream.simFps, "terrain-stream: simulated frames per second")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  command->add_option(
      "--pyramid", o->stream.pyramid,
      "terrain-stream: a tile pyramid folder (sylva terrain pyramid) instead of the procedural "
      "world");
  command
      ->add_option("--gpu-budget", o->gpuBudgetMb,
                   "terrain-stream: MB (10^6 bytes) of GPU tile cache (a texture array; at most "
                   "GL_MAX_ARRAY_TEXTURE_LAYERS tiles)")
      ->check(CLI::Range(1.0, 1.0e6))
      ->capture_default_str();
  command->add_option("--ram-budget", o->ramBudgetMb, "terrain-stream: MB (10^6 bytes) of tiles held in RAM")
      ->check(CLI::Range(1.0, 1.0e6))
      ->capture_default_str();
  command->add_option("--target-fps", o->targetFps, "scene --quality auto: frames per second to keep to")
      ->check(CLI::Range(1.0, 240.0))
      ->capture_default_str();
  command
      ->add_option("--max-growth", o->maxGrowthPercent,
                   "soak: largest allowed growth of resident memory after warm-up, in percent")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  command->callback([o] {
    const bench::BenchOptions options = o->options();
    nlohmann::json report;
    if (o->area == "capture") {
#ifdef SYLVA_HAVE_CAPTURE
      bench::benchCapture(report);
#else
      fail("bench capture: this sylva was built without the capture module");
#endif
    } else if (o->area == "fold") {
#ifdef SYLVA_HAVE_FOLDING
      // CPU rows need no GL; the GPU row makes its own context (and says why when it cannot).
      bench::benchFold(options, report);
#else
      fail("bench fold: this sylva was built without the folding module");
#endif
    } else {
      runGlBench(*o, options, report);
    }
    const std::string out = o->out.empty() ? "out/bench-" + o->area + ".json" : o->out;
    saveJsonFile(out, report);
    std::printf("%s\n", out.c_str());
    if (o->area == "soak" && !report.value("passed", false)) {
      exitCode() = 1; // the report says why
    }
  });
}

} // namespace sylva::app
