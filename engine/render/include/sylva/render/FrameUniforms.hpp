#pragma once

#include <sylva/gl/Buffer.hpp>
#include <sylva/render/Camera.hpp>

#include <shared/Frame.h>

namespace sylva::render {

/** Lighting and atmosphere of a frame (linear colours). */
struct Environment {
  glm::vec3 sunDirection = glm::normalize(glm::vec3(0.45f, 0.7f, 0.3f)); ///< towards the sun, world space
  float sunIntensity = 1.1f;
  glm::vec3 fogColor{0.62f, 0.72f, 0.85f};
  float fogDensity = 0.0012f; ///< per metre
};

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
