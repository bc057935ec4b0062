#include <sylva/render/gpu/DemoScene.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/shader/Compiler.hpp>

#include <shared/Demo.h>

#include <algorithm>
#include <cmath>

namespace sylva::render {

namespace {

void validate(const DemoSettings& s) {
  if (s.patches < 1 || s.patches > 1024) {
    fail("demo: patches {} out of range (1..1024)", s.patches);
  }
  if (!(s.worldSize > 0.0f) || !(s.heightScale >= 0.0f) || !(s.tessLevel >= 1.0f && s.tessLevel <= 64.0f)) {
    fail("demo: world size, height scale or tessellation level out of range");
  }
  if (s.fieldSize < 2 || s.fieldSize > 8192) {
    fail("demo: field size {} out of range (2..8192)", s.fieldSize);
  }
}

} // namespace

DemoScene::DemoScene(const shader::Library& library, const DemoSettings& settings)
    : mSettings((validate(settings), settings)),
      mHeights(gl::Texture::create2D(GL_R32F, settings.fieldSize, settings.fieldSize)),
      mUniforms(sizeof(gpu::DemoUniforms)) {
  mHeights.setSampler({GL_LINEAR, GL_LINEAR, GL_CLAMP_TO_EDGE});
  gl::setLabel(GL_TEXTURE, mHeights.id(), "demo heights");
  reloadShaders(library);
}

void DemoScene::reloadShaders(const shader::Library& library) {
  gl::Program compute = shader::compileProgram(library, {"demo heights", {"demo/heights.comp"}, {}});
  gl::Program surface = shader::compileProgram(
      library,
      {"demo surface", {"demo/patch.vert", "demo/patch.tesc", "demo/patch.tese", "demo/patch.frag"}, {}});
  mCompute = std::move(compute);
  mSurface = std::move(surface);
}

float demoHeightReference(const DemoSettings& s, double time, int i, int j) {
  // Same expression, order and float precision as heights.comp.
  const float size = static_cast<float>(s.fieldSize);
  const glm::vec2 uv = (glm::vec2(static_cast<float>(i), static_cast<float>(j)) + 0.5f) / size;
  const glm::vec2 xz = (uv - 0.5f) * s.worldSize;
  const float hills = 0.55f * std::sin(xz.x * 0.045f) * std::cos(xz.y * 0.035f) +
                      0.25f * std::sin(xz.x * 0.11f + xz.y * 0.07f) +
                      0.12f * std::cos(glm::length(xz) * 0.09f);
  const glm::vec2 centre(0.15f * s.worldSize, -0.1f * s.worldSize);
  const float r = glm::length(xz - centre);
  const float ripple = 0.18f * std::sin(r * 0.12f - static_cast<float>(time) * 2.0f) * std::exp(-r * 0.02f);
  return (hills + ripple) * s.heightScale;
}

Camera DemoScene::defaultCamera() const {
  Camera camera;
  const float s = mSettings.worldSize;
  camera.position = {0.42f * s, 0.16f * s, 0.42f * s};
  camera.target = {-0.05f * s, 0.0f, -0.08f * s};
  camera.farPlane = 4.0f * s;
  camera.nearPlane = 0.5f;
  return camera;
}

void DemoScene::render(const Camera& camera, int width, int height, double time, GpuTimers* timers,
                       bool wireframe) {
  gpu::DemoUniforms u{};
  u.grid = glm::vec4(static_cast<float>(mSettings.patches), mSettings.worldSize, mSettings.heightScale,
                     mSettings.tessLevel);
  u.wave =
      glm::vec4(static_cast<float>(time), 0.12f, 0.15f * mSettings.worldSize, -0.1f * mSettings.worldSize);
  u.field = glm::ivec4(mSettings.fieldSize, mSettings.fieldSize, 0, 0);
  mUniforms.setSubData(0, sizeof(u), &u);
  mUniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_DEMO_BINDING);
  mFrame.update(camera, width, height, time);
  mFrame.bind();

  {
    const GpuTimerScope timed(timers, "heights");
    mCompute.use();
    mHeights.bindImage(0, GL_WRITE_ONLY);
    const GLuint groups =
        static_cast<GLuint>((mSettings.fieldSize + SYLVA_DEMO_GROUP_SIZE - 1) / SYLVA_DEMO_GROUP_SIZE);
    glDispatchCompute(groups, groups, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  const GpuTimerScope timed(timers, "surface");
  mSurface.use();
  mHeights.bind(0);
  mVao.bind();
  glPatchParameteri(GL_PATCH_VERTICES, 4);
  glPolygonMode(GL_FRONT_AND_BACK, wireframe ? GL_LINE : GL_FILL);
  glDrawArraysInstanced(GL_PATCHES, 0, 4, mSettings.patches * mSettings.patches);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

} // namespace sylva::render
