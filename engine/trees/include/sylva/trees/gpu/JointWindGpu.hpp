#pragma once
// Wind on the joints on the GPU (sylva/trees/JointWind.hpp): the rest data and the springs' state in storage
// buffers, stepped by shaders/trees/wind.comp (one invocation per joint, the twin of stepJointWind) and
// turned into every joint's world frame by shaders/trees/frames.comp (the twin of forestJointFrames) in the
// buffer the tree renderer binds at SYLVA_TREE_JOINT_BINDING: one JointFrame per global joint, a tree's joint
// 0 its base frame. Needs a current GL context; not thread-safe (GL calls).

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/trees/JointWind.hpp>

#include <shared/Trees.h>
#include <shared/Wind.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace sylva::trees {

/** Where the springs are stepped and the frames built. */
enum class JointWindSolve {
  /** The compute shaders. */
  Gpu,
  /**
   * The CPU reference (stepJointWind, forestJointFrames: the same operations, on parallelFor's workers), the
   * frames uploaded each updateFrames(). On a software rasteriser the compute shaders run on the same cores
   * several times slower than this (llvmpipe, 100,000 joints: 39 ms against 8.7 ms a step and frames).
   */
  Cpu,
  /** Cpu on a software rasteriser (gl::ContextInfo::deviceClass() "llvmpipe"), else Gpu. */
  Auto,
};

/** The joint springs of a forest in the wind, stepped in compute shaders or on the CPU, writing the joint
 * frames the trees are drawn with. */
class JointWindGpu {
public:
  /** Uploads `rest` (copied; the object keeps a copy only when it solves on the CPU), starts at rest (θ = ω =
   * 0) and builds the frames. */
  JointWindGpu(const shader::Library& library, const JointWindRest& rest,
               JointWindSolve solve = JointWindSolve::Gpu);
  /** Whether step() and updateFrames() run on the CPU (JointWindSolve::Cpu, or Auto on a software
   * rasteriser). */
  bool solvesOnCpu() const { return mCpuRest != nullptr; }

  /** Recompiles wind.comp and frames.comp (viewer hot reload); keeps the old programs and throws on error. */
  void reloadShaders(const shader::Library& library);

  /** Replaces the springs' state (θ, ω per global joint); throws sylva::Error when the size differs. */
  void setState(const JointWindState& state);
  /**
   * One step of `dt` seconds of every joint in `wind` (flow.w: the time at the step; each tree adds its
   * offset). Frames are not rebuilt: call updateFrames() after the last step of a frame.
   */
  void step(const gpu::WindUniforms& wind, float dt);
  /** Rebuilds every joint's world frame from the current state (frames.comp). */
  void updateFrames();

  /** The frame buffer: JointFrame per global joint (world metres ← joint frame), for
   * SYLVA_TREE_JOINT_BINDING. */
  const gl::Buffer& frames() const { return mFrames; }
  /** The state buffer: vec4 per global joint (xy θ radians, zw ω rad/s), SYLVA_TREE_WIND_BINDING (the
   * compute shaders' state; not kept up to date when solving on the CPU: readState() is). */
  const gl::Buffer& motion() const { return mMotion; }

  /** Reads the state back (synchronous; tests). */
  JointWindState readState() const;
  /** Reads the frames back (synchronous; tests). */
  std::vector<gpu::JointFrame> readFrames() const;

  /** Joints of all trees (entries of every buffer). */
  std::size_t jointCount() const { return mJoints; }

private:
  void uploadStep(const gpu::WindUniforms& wind, float dt);
  void bindBuffers() const;

  std::size_t mJoints = 0;
  float mMaxBend = 0.0f;
  /** Solving on the CPU: the rest data, the state and the frames before upload (null: on the GPU). */
  std::unique_ptr<JointWindRest> mCpuRest;
  JointWindState mCpuState;
  std::vector<gpu::JointFrame> mCpuFrames;
  gl::Program mWind{gl::NoCreate};
  gl::Program mFramesProgram{gl::NoCreate};
  gl::Buffer mUniforms;
  gl::Buffer mRest;
  gl::Buffer mMotion;
  gl::Buffer mFrames;
};

} // namespace sylva::trees
