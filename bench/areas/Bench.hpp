#pragma once

// Sylva's measured benchmarks, `sylva bench <area>` (docs/cli.md, docs/testing.md): one file per area
// (BenchTerrain.cpp, BenchGrass.cpp, BenchTrees.cpp, BenchScene.cpp, BenchFold.cpp, BenchCapture.cpp; the
// demo and the shared frame loop in Bench.cpp), and the target tables: each row is a measured value against a
// target from the specs, printed as a table and returned as JSON. The app (apps/sylva/cmd/CmdBench.cpp) turns
// its options into BenchOptions; the Google Benchmark kernels of the CPU code sit beside this, in
// bench/<module>/.

#include <sylva/platform/GlContext.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/terrain/TerrainSetup.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace sylva::scene {
class SceneWorld;
}

namespace sylva::bench {

/** What a benchmark run measures and how: filled by `sylva bench` from its options. */
struct BenchOptions {
  /** The headless context of areas that make their own (fold's GPU row). */
  platform::ContextOptions context;
  /** The terrain of terrain, soak and grass (default: the demo landscape). */
  terrain::TerrainSetup terrain;
  /** Names a terrain field in errors (the command line names its option: "tess_level" → "--tess"). */
  terrain::TerrainFieldName terrainFieldName;
  /** One line naming the height source, for reports. */
  std::string terrainSource = "the demo landscape";
  /** bench grass: the world `sylva render --grass` draws from the same options, and its first camera. */
  scene::SceneDesc groundWorld;
  std::function<render::Camera(scene::SceneWorld&, float aspect)> groundCamera;
  int frames = 60;  ///< measured frames (per configuration)
  int warmup = 5;   ///< frames run before measuring
  int width = 1280; ///< target size, pixels
  int height = 720;
  /** soak: largest allowed growth of resident memory after warm-up, percent. */
  double maxGrowthPercent = 1.0;
};

/** Host name, CPU model and core count, for benchmark reports. */
struct MachineInfo {
  std::string host;
  std::string cpu;
  unsigned cores = 0;
};
MachineInfo machineInfo();

/** Samples of one measured run: per-pass CPU/GPU milliseconds, wall time per frame, extra per-frame series.
 */
struct Samples {
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> cpu;
  std::map<std::string, std::vector<double>> gpu;
  std::map<std::string, std::vector<double>> wall;
  std::vector<double> frame;
  std::map<std::string, std::vector<double>> extra;
  /** Each pass's work per frame (pipeline statistics; GpuTimers' countWork). */
  std::map<std::string, std::vector<render::PassCounts>> counts;

  /** The median work of `pass` over the frames (fields -1 when it did not run). */
  render::PassCounts countsOf(const std::string& pass) const {
    const auto it = counts.find(pass);
    return it == counts.end() ? render::PassCounts{} : render::medianCounts(it->second);
  }

  nlohmann::json passesJson() const {
    nlohmann::json passes = nlohmann::json::array();
    for (const std::string& pass : order) {
      passes.push_back({{"name", pass},
                        {"cpu_ms", render::Stats::of(cpu.at(pass)).toJson()},
                        {"gpu_ms", render::Stats::of(gpu.at(pass)).toJson()},
                        {"wall_ms", render::Stats::of(wall.at(pass)).toJson()},
                        {"counts", countsOf(pass).toJson()}});
    }
    return passes;
  }
};

/**
 * Runs `frame(timers, index)` warmup + frames times with synchronous GPU timers that also count each pass's
 * work (so a frame must not run pipeline-statistics queries of its own), and collects samples.
 */
Samples measure(const BenchOptions& o, const std::function<void(render::GpuTimers&, int, Samples&)>& frame);

/** The report's common head: area name, renderer, size, frames. */
nlohmann::json header(const BenchOptions& o, const std::string& name, const platform::GlContext& context);

/** One measured metric against its target. */
struct BenchRow {
  std::string metric;
  /** NaN when not measured (the note says why). */
  double value;
  std::string unit;
  double target;
  /** The target is an upper bound (else a lower bound). */
  bool atMost;
  /** Threads the measurement used (0: the GPU). */
  unsigned threads;
  std::string note;
};

/** Resident set size of this process in bytes (Linux /proc/self/statm), 0 if unknown. */
std::uint64_t residentBytes();

/**
 * `bench scene`: the scene file's output camera over `frames` frames after `warmup` (simulations stepping at
 * the file's fps), per-pass CPU, GPU and wall times, frames per second against the llvmpipe target (≥ 5 fps
 * at 1280×720), GPU memory the subsystems report and the process's resident memory; needs a current GL
 * context. `quality`: "default" (real-time shadows), "full" (SceneDrawOptions::fullQuality) or "auto" (the
 * viewer's quality governor keeping frames at `targetFps`, settling over at least 20 warm-up frames; the
 * steps drawn are reported).
 */
void benchScene(const std::string& file, int frames, int warmup, int width, int height,
                const std::string& quality, double targetFps, nlohmann::json& report);

/** Seconds of each of `runs` calls of `fn` after `warmup` unmeasured calls. */
std::vector<double> timeRuns(int warmup, int runs, const std::function<void()>& fn);

/** Prints the rows as a table (measured, target, ok/MISS) and returns them as a JSON array. */
nlohmann::json printBenchRows(const std::vector<BenchRow>& rows);

/** `bench capture`: grass capture targets (docs/capture.md): extraction latency, refining. */
void benchCapture(nlohmann::json& report);

/**
 * `bench trees`: the paper's Fig. 16 workloads (1 … 1,000 trees) instanced and per piece, tessellation levels
 * 1 and 10, generation of 1,000 trees, wind on 100,000 joints; needs a current GL context. `frames` is
 * divided by 10 (at least 3) per configuration: a forest frame on llvmpipe is slow.
 */
void benchTrees(int frames, int width, int height, nlohmann::json& report);

/** `bench demo`: the built-in pipeline scene. */
void benchDemo(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report);
/** `bench terrain`: the paper's Table 8, both crack methods, popping (BenchTerrain.cpp). */
void benchTerrain(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report);
/**
 * `bench terrain-error`: over `o.frames` camera poses on three fields (Jacksboro, the elev.tif GeoTIFF, a
 * ridged procedural field of `proceduralSize`² samples at 2 m), distance LOD and screen-space-error LOD each
 * tuned to the cheapest setting whose measured worst error is ≤ 1 px against the full-depth surface, then
 * their leaves, vertices, triangles, LOD and frame times side by side (BenchTerrainError.cpp).
 */
void benchTerrainError(const BenchOptions& o, const platform::GlContext& context, int proceduralSize,
                       nlohmann::json& report);
/**
 * `bench soak`: memory, GL errors and frame-time drift over a long orbit (BenchTerrain.cpp); report["passed"]
 * is false (and a line on stderr says why) when memory grew more than maxGrowthPercent or a GL error
 * occurred.
 */
/** `sylva bench terrain-stream`: the flight's settings. */
struct StreamBenchOptions {
  double distanceKm = 100.0;                      ///< flight length (clipped to the world)
  double speed = 300.0;                           ///< metres per second
  double simFps = 30.0;                           ///< simulated frames per second (one update and draw each)
  double altitude = 250.0;                        ///< metres above the ground (smoothed terrain following)
  std::uint64_t seed = 7;                         ///< the procedural world's seed
  std::string pyramid;                            ///< a tile pyramid folder instead of the procedural world
  std::size_t gpuBudget = std::size_t{256} << 20; ///< bytes of GPU tile cache
  std::size_t ramBudget = std::size_t{512} << 20; ///< bytes of RAM tile cache
  int checkEvery = 30;                            ///< frames between height-query checks and memory samples
};
/** Flies across a streamed world (docs/terrain-data.md, "Streaming"): memory, loads, waits, query agreement.
 */
void benchTerrainStream(const BenchOptions& o, const platform::GlContext& context,
                        const StreamBenchOptions& s, nlohmann::json& report);
void benchSoak(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report);
/** `bench grass`: the paper's field, memory, popping (BenchGrass.cpp). */
void benchGrass(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report);
/** `bench grass-sim`: the paper's Table 1 solver workloads (BenchGrass.cpp). */
void benchGrassSim(const BenchOptions& o, const platform::GlContext& context, nlohmann::json& report);
/** `bench fold`: the folding targets (BenchFold.cpp; without the folding module, not built). */
void benchFold(const BenchOptions& o, nlohmann::json& report);

} // namespace sylva::bench
