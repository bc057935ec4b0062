#pragma once
// The frame-uniform block every pass reads (shaders/shared/Frame.h) as a GL buffer; what it holds is
// render::Environment (CPU, Environment.hpp) and the camera.

#include <sylva/gl/Buffer.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/Environment.hpp>

#include <shared/Frame.h>

#include <cstddef>
#include <cstdint>
#include <memory>

namespace sylva::render {

/** The per-frame uniform buffer (gpu::FrameUniforms) bound at SYLVA_FRAME_BINDING. */
class FrameUniformBuffer {
public:
  FrameUniformBuffer();
  ~FrameUniformBuffer();
  FrameUniformBuffer(const FrameUniformBuffer&) = delete;
  FrameUniformBuffer& operator=(const FrameUniformBuffer&) = delete;
  /** Fills and uploads the block for `camera` on a `width`×`height` pixel target at `time` seconds. */
  void update(const Camera& camera, int width, int height, double time, const Environment& environment = {});
  /** Binds the block at its binding point (shared/Frame.h) for the passes that follow. */
  void bind() const;
  /** The values last uploaded. */
  const gpu::FrameUniforms& data() const { return mData; }

  /** Whether the block was last filled for `camera` (same view matrix and position). */
  bool isFor(const Camera& camera) const;

  /** Frame-uniform buffers alive in the process (a scene frame needs one: ScenePasses'). */
  static std::size_t liveBuffers();
  /** Uploads (update() calls) since the process started; a scene frame makes one per camera it draws with. */
  static std::uint64_t uploads();

private:
  gpu::FrameUniforms mData{};
  gl::Buffer mBuffer;
};

/**
 * How a renderer binds the frame block: the frame path's (Environment::frame) when it was filled for the
 * camera the renderer draws with, otherwise a buffer of the renderer's own, created on first use (renderers
 * used alone: tests, bakes, the demo). In a scene frame no renderer creates one.
 */
class FrameBinding {
public:
  /** Binds the block for `camera` on a `width`×`height` target at `time` seconds in `environment`. */
  void bind(const Camera& camera, int width, int height, double time, const Environment& environment);
  /** Whether this renderer had to create its own buffer. */
  bool ownsBuffer() const { return mOwn != nullptr; }

private:
  std::unique_ptr<FrameUniformBuffer> mOwn;
};

} // namespace sylva::render
