#include <sylva/trees/gpu/JointWindGpu.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/gl/ContextInfo.hpp>
#include <sylva/shader/Compiler.hpp>

#include <algorithm>
#include <cmath>
#include <span>

namespace sylva::trees {
namespace {

/** The uniform block of wind.comp and frames.comp (std140: two runs of vec4s). */
struct StepBlock {
  gpu::WindUniforms wind;
  gpu::JointWindStepGpu step;
};
static_assert(sizeof(StepBlock) == 96, "JointWindBlock layout");

GLuint groups(std::size_t joints) {
  return static_cast<GLuint>((joints + SYLVA_TREE_WIND_GROUP - 1) / SYLVA_TREE_WIND_GROUP);
}

} // namespace

JointWindGpu::JointWindGpu(const shader::Library& library, const JointWindRest& rest, JointWindSolve solve)
    : mJoints(rest.jointCount()), mMaxBend(rest.maxBend), mUniforms(sizeof(StepBlock)),
      mRest(std::max<std::size_t>(rest.jointCount(), 1) * sizeof(gpu::TreeJointRest)),
      mMotion(std::max<std::size_t>(rest.jointCount(), 1) * sizeof(glm::vec4)),
      mFrames(std::max<std::size_t>(rest.jointCount(), 1) * sizeof(gpu::JointFrame)) {
  if (mJoints >= 0xffffffffu) {
    fail("joint wind: {} joints do not fit the GPU's indices", mJoints);
  }
  if (solve == JointWindSolve::Cpu ||
      (solve == JointWindSolve::Auto && gl::queryContextInfo().deviceClass() == "llvmpipe")) {
    mCpuRest = std::make_unique<JointWindRest>(rest);
    mCpuState = JointWindState(mJoints);
  }
  if (mJoints > 0) {
    mRest.setSubData(std::span<const gpu::TreeJointRest>(rest.joints));
  }
  mMotion.clear();
  mFrames.clear();
  gl::setLabel(GL_BUFFER, mRest.id(), "tree joint rest");
  gl::setLabel(GL_BUFFER, mMotion.id(), "tree joint motion");
  gl::setLabel(GL_BUFFER, mFrames.id(), "tree joint frames");
  reloadShaders(library);
  uploadStep(gpu::WindUniforms{}, 0.0f);
  updateFrames();
}

void JointWindGpu::reloadShaders(const shader::Library& library) {
  gl::Program wind = shader::compileProgram(library, {"tree joint wind", {"trees/wind.comp"}, {}});
  gl::Program frames = shader::compileProgram(library, {"tree joint frames", {"trees/frames.comp"}, {}});
  mWind = std::move(wind);
  mFramesProgram = std::move(frames);
}

void JointWindGpu::setState(const JointWindState& state) {
  if (state.motion.size() != mJoints) {
    fail("joint wind: the state has {} joints, the GPU buffers {}", state.motion.size(), mJoints);
  }
  if (mJoints > 0) {
    mMotion.setSubData(std::span<const glm::vec4>(state.motion));
  }
  if (mCpuRest) {
    mCpuState = state;
  }
}

void JointWindGpu::uploadStep(const gpu::WindUniforms& wind, float dt) {
  StepBlock block{};
  block.wind = wind;
  block.step.step = glm::vec4(dt, mMaxBend, 0.0f, 0.0f);
  block.step.counts = glm::uvec4(static_cast<std::uint32_t>(mJoints), 0u, 0u, 0u);
  mUniforms.setSubData(0, sizeof(block), &block);
}

void JointWindGpu::bindBuffers() const {
  mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_TREE_WIND_STEP_BINDING);
  mMotion.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_WIND_BINDING);
  mRest.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_WIND_REST_BINDING);
  mFrames.bindBase(GL_SHADER_STORAGE_BUFFER, SYLVA_TREE_JOINT_BINDING);
}

void JointWindGpu::step(const gpu::WindUniforms& wind, float dt) {
  if (!(std::isfinite(dt) && dt > 0.0f)) {
    fail("joint wind: the time step must be a positive number of seconds, got {}", dt);
  }
  if (mJoints == 0) {
    return;
  }
  if (mCpuRest) {
    stepJointWind(*mCpuRest, mCpuState, wind, dt);
    return;
  }
  uploadStep(wind, dt);
  bindBuffers();
  mWind.use();
  glDispatchCompute(groups(mJoints), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void JointWindGpu::updateFrames() {
  if (mJoints == 0) {
    return;
  }
  if (mCpuRest) {
    forestJointFrames(*mCpuRest, mCpuState, mCpuFrames);
    mFrames.setSubData(std::span<const gpu::JointFrame>(mCpuFrames));
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    return;
  }
  bindBuffers();
  mFramesProgram.use();
  glDispatchCompute(groups(mJoints), 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

JointWindState JointWindGpu::readState() const {
  if (mCpuRest) {
    return mCpuState;
  }
  JointWindState state(mJoints);
  if (mJoints > 0) {
    mMotion.getSubData(0, mJoints * sizeof(glm::vec4), state.motion.data());
  }
  return state;
}

std::vector<gpu::JointFrame> JointWindGpu::readFrames() const {
  std::vector<gpu::JointFrame> out(mJoints);
  if (mJoints > 0) {
    mFrames.getSubData(0, mJoints * sizeof(gpu::JointFrame), out.data());
  }
  return out;
}

} // namespace sylva::trees
