// Trees on the CPU: wind on the joints, one fixed step of every joint spring of a forest and every joint's
// world frame (targets: 100,000 joints ≤ 4 ms on 2 cores). Run: SYLVA_THREADS=2 sylva_benchmarks
// --benchmark_filter=JointWind
#include <sylva/trees/JointWind.hpp>
#include <sylva/wind/Wind.hpp>

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace sylva::trees;

/** A grid of trees of four presets, 6 m apart, with at least `joints` joints in all, and its rest data. */
struct WindForest {
  PieceSet pieces = standardPieces();
  std::vector<Species> species;
  std::vector<TreeTopology> topologies;
  std::vector<std::vector<glm::vec2>> poses;
  JointWindRest rest;

  explicit WindForest(std::size_t joints) {
    for (const char* name : {"almond", "quaking-aspen", "apple", "california-black-oak"}) {
      species.push_back(speciesPreset(name));
    }
    std::size_t total = 0;
    for (std::uint64_t seed = 1; total < joints; ++seed) {
      const Species& s = species[seed % species.size()];
      topologies.push_back(generateTree(pieces, s, seed));
      poses.push_back(randomPose(topologies.back(), s, seed));
      total += topologies.back().jointCount();
    }
    std::vector<JointWindTree> trees;
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(topologies.size()))));
    for (std::size_t i = 0; i < topologies.size(); ++i) {
      JointWindTree t;
      t.topology = &topologies[i];
      t.species = &species[(i + 1) % species.size()];
      const glm::vec3 at(static_cast<float>(static_cast<int>(i) % side) * 6.0f, 0.0f,
                         static_cast<float>(static_cast<int>(i) / side) * 6.0f);
      t.base = baseFrame(at, static_cast<float>(i) * 0.7f, t.species->trunkRadius);
      t.pose = poses[i];
      t.timeOffset = windTimeOffset(i);
      trees.push_back(t);
    }
    rest = buildJointWindRest(pieces, trees);
  }
};

const WindForest& windForest(std::size_t joints) {
  static std::map<std::size_t, std::unique_ptr<WindForest>> cache;
  auto& entry = cache[joints];
  if (!entry) {
    entry = std::make_unique<WindForest>(joints);
  }
  return *entry;
}

sylva::wind::WindSettings gusts() {
  sylva::wind::WindSettings w;
  w.speed = 8.0f;
  w.direction = {0.8f, 0.6f};
  return w;
}

/** One 1/60 s step of every joint spring in gusty wind (the CPU reference of shaders/trees/wind.comp). */
void BM_JointWindCpu(benchmark::State& state) {
  const WindForest& forest = windForest(static_cast<std::size_t>(state.range(0)));
  JointWindState springs(forest.rest.jointCount());
  const sylva::wind::WindSettings w = gusts();
  float time = 0.0f;
  for (auto _ : state) {
    time += 1.0f / 60.0f;
    stepJointWind(forest.rest, springs, sylva::wind::toUniforms(w, time), 1.0f / 60.0f);
    benchmark::DoNotOptimize(springs.motion.data());
  }
  const auto joints = static_cast<double>(forest.rest.jointCount());
  state.counters["joints"] = joints;
  state.counters["trees"] = static_cast<double>(forest.rest.treeCount());
  // Seconds per joint (printed with an SI prefix: "24n" is 24 ns).
  state.counters["per_joint"] =
      benchmark::Counter(joints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_JointWindCpu)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();

/** Every joint's world frame from the springs' bends (the CPU reference of shaders/trees/frames.comp). */
void BM_JointWindFramesCpu(benchmark::State& state) {
  const WindForest& forest = windForest(static_cast<std::size_t>(state.range(0)));
  JointWindState springs(forest.rest.jointCount());
  stepJointWind(forest.rest, springs, sylva::wind::toUniforms(gusts(), 1.0f), 1.0f / 60.0f);
  std::vector<sylva::gpu::JointFrame> frames;
  for (auto _ : state) {
    forestJointFrames(forest.rest, springs, frames);
    benchmark::DoNotOptimize(frames.data());
  }
  const auto joints = static_cast<double>(forest.rest.jointCount());
  state.counters["joints"] = joints;
  // Seconds per joint (printed with an SI prefix: "24n" is 24 ns).
  state.counters["per_joint"] =
      benchmark::Counter(joints, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_JointWindFramesCpu)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();

/** Rest data of a forest (springs, levers, frames at rest), once per scene load. */
void BM_JointWindRest(benchmark::State& state) {
  const WindForest& forest = windForest(static_cast<std::size_t>(state.range(0)));
  std::vector<JointWindTree> trees;
  for (std::size_t i = 0; i < forest.topologies.size(); ++i) {
    JointWindTree t;
    t.topology = &forest.topologies[i];
    t.species = &forest.species[(i + 1) % forest.species.size()];
    t.base = baseFrame(glm::vec3(static_cast<float>(i) * 6.0f, 0.0f, 0.0f), 0.0f, t.species->trunkRadius);
    t.pose = forest.poses[i];
    trees.push_back(t);
  }
  for (auto _ : state) {
    JointWindRest rest = buildJointWindRest(forest.pieces, trees);
    benchmark::DoNotOptimize(rest.joints.data());
  }
  state.counters["joints"] = static_cast<double>(forest.rest.jointCount());
}
BENCHMARK(BM_JointWindRest)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
