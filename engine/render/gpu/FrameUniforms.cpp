#include <sylva/render/gpu/FrameUniforms.hpp>

#include <atomic>

namespace sylva::render {

namespace {
std::atomic<std::size_t> gLive{0};
std::atomic<std::uint64_t> gUploads{0};
} // namespace

FrameUniformBuffer::FrameUniformBuffer() : mBuffer(sizeof(gpu::FrameUniforms)) {
  ++gLive;
}

FrameUniformBuffer::~FrameUniformBuffer() {
  --gLive;
}

std::size_t FrameUniformBuffer::liveBuffers() {
  return gLive.load();
}

std::uint64_t FrameUniformBuffer::uploads() {
  return gUploads.load();
}

bool FrameUniformBuffer::isFor(const Camera& camera) const {
  return mData.view == camera.view() && glm::vec3(mData.cameraPos) == camera.position;
}

void FrameBinding::bind(const Camera& camera, int width, int height, double time,
                        const Environment& environment) {
  if (environment.frame != nullptr && environment.frame->isFor(camera)) {
    environment.frame->bind();
    return;
  }
  if (!mOwn) {
    mOwn = std::make_unique<FrameUniformBuffer>();
  }
  mOwn->update(camera, width, height, time, environment);
  mOwn->bind();
}

void FrameUniformBuffer::update(const Camera& camera, int width, int height, double time,
                                const Environment& environment) {
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  mData.viewProj = camera.viewProjection(aspect);
  mData.view = camera.view();
  mData.cameraPos = glm::vec4(camera.position, static_cast<float>(time));
  mData.sunDirection = glm::vec4(glm::normalize(environment.sunDirection), environment.sunIntensity);
  mData.fogColor = glm::vec4(environment.fogColor, environment.fogDensity);
  mData.viewport = glm::vec4(static_cast<float>(width), static_cast<float>(height),
                             1.0f / static_cast<float>(width), 1.0f / static_cast<float>(height));
  mData.atmosphere = glm::vec4(static_cast<float>(environment.atmosphere), environment.turbidity,
                               environment.exposure, 0.0f);
  const ShadowFrame& shadows = environment.shadows;
  mData.shadowParams =
      glm::vec4(static_cast<float>(shadows.cascades), shadows.depthBias, shadows.texel, shadows.normalOffset);
  mData.shadowSplits = shadows.splits;
  for (int i = 0; i < 4; ++i) {
    mData.shadowMatrices[i] = shadows.matrices[i];
  }
  mBuffer.setSubData(0, sizeof(mData), &mData);
  ++gUploads;
}

void FrameUniformBuffer::bind() const {
  mBuffer.bindBase(GL_UNIFORM_BUFFER, SYLVA_FRAME_BINDING);
}

} // namespace sylva::render
