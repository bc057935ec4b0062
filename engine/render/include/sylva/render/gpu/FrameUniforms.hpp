#pragma once
// The frame-uniform block every pass reads (shaders/shared/Frame.h) as a GL buffer; what it holds is
// render::Environment (CPU, Environment.hpp) and the camera.

#include <sylva/gl/Buffer.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/Environment.hpp>

#include <shared/Frame.h>

namespace sylva::render {

/** The per-frame uniform buffer (gpu::FrameUniforms) bound at SYLVA_FRAME_BINDING. */
class FrameUniformBuffer {
public:
  FrameUniformBuffer();
  /** Fills and uploads the block for `camera` on a `width`×`height` pixel target at `time` seconds. */
  void update(const Camera& camera, int width, int height, double time, const Environment& environment = {});
  void bind() const;
  const gpu::FrameUniforms& data() const { return mData; }

private:
  gpu::FrameUniforms mData{};
  gl::Buffer mBuffer;
};

} // namespace sylva::render
