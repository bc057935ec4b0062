// Wind on the joints on the GPU: wind.comp and frames.comp against the CPU reference (stepJointWind,
// forestJointFrames, jointFrames): a small forest stepped 120 times in gusty wind by both, every joint's θ
// and ω and every frame compared; a state set from the CPU gives the CPU's frames; and the time both passes
// take for a forest of 100,000 joints (20,000 on llvmpipe).
#include <sylva/core/Error.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/trees/gpu/JointWindGpu.hpp>
#include <sylva/wind/Wind.hpp>

#include "GlTest.hpp"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

namespace sylva::trees {
namespace {

using JointWindGpuTest = test::GlTest;

constexpr float kDt = 1.0f / 60.0f;

/** A forest for the wind (owns what JointWindTree points to). */
struct WindForest {
  PieceSet pieces = standardPieces();
  std::vector<Species> species;
  std::vector<TreeTopology> topologies;
  std::vector<std::vector<glm::vec2>> poses;
  std::vector<JointWindTree> trees;
  JointWindRest rest;

  /** Trees of the presets in turn on a grid 7 m apart until there are at least `joints` joints. */
  explicit WindForest(std::size_t joints) {
    for (const char* name : {"almond", "quaking-aspen", "weeping-willow", "california-black-oak", "apple"}) {
      species.push_back(speciesPreset(name));
    }
    std::size_t total = 0;
    for (std::uint64_t seed = 1; total < joints; ++seed) {
      const Species& s = species[seed % species.size()];
      topologies.push_back(generateTree(pieces, s, seed));
      poses.push_back(randomPose(topologies.back(), s, seed));
      total += topologies.back().jointCount();
    }
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(topologies.size()))));
    for (std::size_t i = 0; i < topologies.size(); ++i) {
      JointWindTree t;
      t.topology = &topologies[i];
      t.species = &species[(i + 1) % species.size()];
      const glm::vec3 at(static_cast<float>(static_cast<int>(i) % side) * 7.0f - 20.0f,
                         0.3f * static_cast<float>(i),
                         static_cast<float>(static_cast<int>(i) / side) * 7.0f - 10.0f);
      t.base = baseFrame(at, static_cast<float>(i) * 1.3f, t.species->trunkRadius);
      t.pose = poses[i];
      t.timeOffset = windTimeOffset(i);
      trees.push_back(t);
    }
    rest = buildJointWindRest(pieces, trees);
  }
};

wind::WindSettings gusts() {
  wind::WindSettings w;
  w.direction = {0.8f, -0.6f};
  w.speed = 9.0f;
  w.gustStrength = 1.2f;
  w.turbulence = 0.4f;
  w.seed = 9;
  return w;
}

/** Largest difference of translations (metres) and of linear parts between two sets of frames. */
double worstFrameDifference(const std::vector<gpu::JointFrame>& a, const std::vector<gpu::JointFrame>& b) {
  double worst = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    worst = std::max<double>(worst, glm::length(a[j].x - b[j].x));
    worst = std::max<double>(worst, glm::length(a[j].y - b[j].y));
    worst = std::max<double>(worst, glm::length(a[j].z - b[j].z));
  }
  return worst;
}

TEST_F(JointWindGpuTest, ComputeShadersMatchTheCpuReference) {
  const WindForest forest(900);
  const JointWindRest& rest = forest.rest;
  JointWindGpu gpu(shaders(), rest);
  ASSERT_EQ(gpu.jointCount(), rest.jointCount());
  ASSERT_EQ(gpu.frames().size(), rest.jointCount() * sizeof(gpu::JointFrame))
      << "one frame per global joint: a node's root joint is its parent's terminal joint";
  JointWindState cpu(rest.jointCount());
  const wind::WindSettings w = gusts();
  for (int i = 1; i <= 120; ++i) {
    const gpu::WindUniforms u = wind::toUniforms(w, static_cast<float>(i) * kDt);
    stepJointWind(rest, cpu, u, kDt);
    gpu.step(u, kDt);
  }
  gpu.updateFrames();
  const JointWindState onGpu = gpu.readState();
  double thetaScale = 0.0;
  double omegaScale = 0.0;
  for (std::size_t j = 0; j < rest.jointCount(); ++j) {
    thetaScale = std::max<double>(thetaScale, glm::length(cpu.theta(j)));
    omegaScale = std::max<double>(omegaScale, glm::length(cpu.omega(j)));
  }
  double thetaWorst = 0.0;
  double omegaWorst = 0.0;
  for (std::size_t j = 0; j < rest.jointCount(); ++j) {
    thetaWorst = std::max<double>(thetaWorst, glm::length(cpu.theta(j) - onGpu.theta(j)));
    omegaWorst = std::max<double>(omegaWorst, glm::length(cpu.omega(j) - onGpu.omega(j)));
  }
  std::vector<gpu::JointFrame> cpuFrames;
  forestJointFrames(rest, cpu, cpuFrames);
  const std::vector<gpu::JointFrame> gpuFrames = gpu.readFrames();
  ASSERT_EQ(gpuFrames.size(), rest.jointCount());
  // The GPU's frames against the CPU's from the GPU's own state (the frames pass alone) and from the CPU's
  // state (both passes), and against jointFrames() of every tree.
  std::vector<gpu::JointFrame> fromGpuState;
  forestJointFrames(rest, onGpu, fromGpuState);
  const double framesPass = worstFrameDifference(gpuFrames, fromGpuState);
  const double framesBoth = worstFrameDifference(gpuFrames, cpuFrames);
  double framesSkeleton = 0.0;
  for (std::size_t t = 0; t < rest.treeCount(); ++t) {
    std::vector<glm::mat4> reference;
    jointFrames(forest.pieces, forest.topologies[t], forest.trees[t].base, treeBends(rest, onGpu, t),
                reference);
    const std::uint32_t offset = rest.jointOffset[t];
    EXPECT_EQ(std::memcmp(&gpuFrames[offset], &rest.joints[offset].local, sizeof(gpu::JointFrame)), 0)
        << "frames[0] of tree " << t << " is its base frame";
    for (std::size_t j = 0; j < reference.size(); ++j) {
      const glm::mat4 m = jointFrameMatrix(gpuFrames[offset + j]);
      for (int c = 0; c < 4; ++c) {
        framesSkeleton = std::max<double>(framesSkeleton, glm::length(m[c] - reference[j][c]));
      }
    }
  }
  std::printf("%zu joints of %zu trees after 120 steps: |θ| up to %.3f rad, |ω| up to %.3f rad/s\n"
              "  GPU − CPU: θ %.3g rad (%.3g relative), ω %.3g rad/s (%.3g relative)\n"
              "  frames: %.3g (frames pass), %.3g (both passes), %.3g (against jointFrames) m\n",
              rest.jointCount(), rest.treeCount(), thetaScale, omegaScale, thetaWorst,
              thetaWorst / thetaScale, omegaWorst, omegaWorst / omegaScale, framesPass, framesBoth,
              framesSkeleton);
  RecordProperty("theta_relative", std::to_string(thetaWorst / thetaScale));
  RecordProperty("omega_relative", std::to_string(omegaWorst / omegaScale));
  RecordProperty("frames_m", std::to_string(framesBoth));
  EXPECT_GT(thetaScale, 0.05) << "the wind bent the trees";
  EXPECT_LT(thetaWorst / thetaScale, 1e-4);
  EXPECT_LT(omegaWorst / omegaScale, 1e-4);
  EXPECT_LT(framesPass, 2e-5);
  EXPECT_LT(framesBoth, 1e-4);
  EXPECT_LT(framesSkeleton, 1e-4);
}

TEST_F(JointWindGpuTest, FramesOfAStateSetFromTheCpu) {
  // Large bends set from the CPU (up to 0.45 rad per joint): the frames pass alone, chains up to the deepest
  // joint, against forestJointFrames.
  const WindForest forest(1500);
  const JointWindRest& rest = forest.rest;
  JointWindState state(rest.jointCount());
  for (std::size_t j = 0; j < rest.jointCount(); ++j) {
    const float a = static_cast<float>(j) * 2.399f;
    state.motion[j] = glm::vec4(0.45f * std::cos(a) * std::sin(0.37f * static_cast<float>(j)),
                                0.45f * std::sin(a) * std::cos(0.11f * static_cast<float>(j)), 0.0f, 0.0f);
    if (rest.joints[j].info.x == SYLVA_TREE_NO_PARENT) {
      state.motion[j] = glm::vec4(0.0f);
    }
  }
  std::uint32_t deepest = 0;
  for (const gpu::TreeJointRest& r : rest.joints) {
    deepest = std::max(deepest, r.info.z);
  }
  JointWindGpu gpu(shaders(), rest);
  gpu.setState(state);
  gpu.updateFrames();
  std::vector<gpu::JointFrame> cpuFrames;
  forestJointFrames(rest, state, cpuFrames);
  const double worst = worstFrameDifference(gpu.readFrames(), cpuFrames);
  std::printf("set state: %zu joints, chains up to %u joints, worst frame difference %.3g m\n",
              rest.jointCount(), deepest + 1, worst);
  EXPECT_GT(deepest, 10u);
  EXPECT_LT(worst, 2e-5);
  JointWindState wrong(rest.jointCount() + 1);
  EXPECT_THROW(gpu.setState(wrong), Error);
}

TEST_F(JointWindGpuTest, SolvingOnTheCpuGivesTheComputeShadersFrames) {
  // The CPU solve (what a forest uses on llvmpipe) steps the reference and uploads its frames: the renderer's
  // buffer then holds forestJointFrames of the reference state, within float rounding of the shaders'.
  const WindForest forest(900);
  const JointWindRest& rest = forest.rest;
  JointWindGpu onGpu(shaders(), rest, JointWindSolve::Gpu);
  JointWindGpu onCpu(shaders(), rest, JointWindSolve::Cpu);
  const JointWindGpu automatic(shaders(), rest, JointWindSolve::Auto);
  EXPECT_FALSE(onGpu.solvesOnCpu());
  EXPECT_TRUE(onCpu.solvesOnCpu());
  EXPECT_EQ(automatic.solvesOnCpu(), onLlvmpipe());
  JointWindState reference(rest.jointCount());
  const wind::WindSettings w = gusts();
  for (int i = 1; i <= 60; ++i) {
    const gpu::WindUniforms u = wind::toUniforms(w, static_cast<float>(i) * kDt);
    stepJointWind(rest, reference, u, kDt);
    onGpu.step(u, kDt);
    onCpu.step(u, kDt);
  }
  onGpu.updateFrames();
  onCpu.updateFrames();
  EXPECT_EQ(onCpu.readState().motion, reference.motion) << "the CPU solve is the reference, bit for bit";
  std::vector<gpu::JointFrame> frames;
  forestJointFrames(rest, reference, frames);
  const std::vector<gpu::JointFrame> uploaded = onCpu.readFrames();
  ASSERT_EQ(uploaded.size(), frames.size());
  EXPECT_EQ(std::memcmp(uploaded.data(), frames.data(), frames.size() * sizeof(gpu::JointFrame)), 0);
  EXPECT_LT(worstFrameDifference(uploaded, onGpu.readFrames()), 1e-4);
  // A state set from outside is what the next step starts from.
  JointWindState rest0(rest.jointCount());
  onCpu.setState(rest0);
  EXPECT_EQ(onCpu.readState().motion, rest0.motion);
}

TEST_F(JointWindGpuTest, TimesBothPassesForAForest) {
  // The target is 100,000 joints in 0.25 ms on a desktop GPU; llvmpipe runs a fifth of that to keep the test
  // short. Timings are printed (not asserted); the result is checked against the CPU after one step.
  const std::size_t joints = onLlvmpipe() ? 20000 : 100000;
  const WindForest forest(joints);
  const JointWindRest& rest = forest.rest;
  JointWindGpu gpu(shaders(), rest);
  const wind::WindSettings w = gusts();
  render::GpuTimers timers(1, true);
  std::vector<double> windMs;
  std::vector<double> framesMs;
  for (int frame = 1; frame <= 12; ++frame) {
    const gpu::WindUniforms u = wind::toUniforms(w, static_cast<float>(frame) * kDt);
    timers.beginFrame();
    timers.begin("wind");
    gpu.step(u, kDt);
    timers.end();
    timers.begin("frames");
    gpu.updateFrames();
    timers.end();
    timers.endFrame();
    if (frame > 2) {
      windMs.push_back(timers.lastFrame()[0].gpuMs);
      framesMs.push_back(timers.lastFrame()[1].gpuMs);
    }
  }
  const render::Stats wind = render::Stats::of(windMs);
  const render::Stats frames = render::Stats::of(framesMs);
  std::printf("%zu joints (%zu trees): wind.comp %.4f ms, frames.comp %.4f ms (GPU time, median of %zu)\n",
              rest.jointCount(), rest.treeCount(), wind.median, frames.median, windMs.size());
  RecordProperty("wind_ms", std::to_string(wind.median));
  RecordProperty("frames_ms", std::to_string(frames.median));
  // One more step on both from the GPU's state: the same result.
  JointWindState cpu = gpu.readState();
  const gpu::WindUniforms u = wind::toUniforms(w, 13.0f * kDt);
  stepJointWind(rest, cpu, u, kDt);
  gpu.step(u, kDt);
  const JointWindState onGpu = gpu.readState();
  double worst = 0.0;
  for (std::size_t j = 0; j < rest.jointCount(); ++j) {
    worst = std::max<double>(worst, glm::length(cpu.theta(j) - onGpu.theta(j)));
  }
  EXPECT_LT(worst, 1e-5);
}

} // namespace
} // namespace sylva::trees
