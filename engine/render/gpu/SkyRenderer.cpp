#include <sylva/render/gpu/SkyRenderer.hpp>

#include <sylva/render/Sky.hpp>
#include <sylva/shader/Compiler.hpp>

#include <array>

namespace sylva::render {

SkyRenderer::SkyRenderer(const shader::Library& library) : mFlareState(2 * sizeof(glm::vec4)) {
  mFlareState.clear();
  reloadShaders(library);
}

void SkyRenderer::reloadShaders(const shader::Library& library) {
  gl::Program sky = shader::compileProgram(library, {"sky", {"render/sky.vert", "render/sky.frag"}, {}});
  gl::Program visibility =
      shader::compileProgram(library, {"flare visibility", {"render/flare_visibility.comp"}, {}});
  gl::Program flare =
      shader::compileProgram(library, {"flare", {"render/flare.vert", "render/flare.frag"}, {}});
  mSky = std::move(sky);
  mVisibility = std::move(visibility);
  mFlare = std::move(flare);
}

void SkyRenderer::drawSky() const {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  mSky.use();
  mVao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
}

void SkyRenderer::drawFlare(const gl::Texture& depth, const FlareSettings& settings) const {
  mVisibility.use();
  mVisibility.setUniform("uMinRadiusPixels", settings.minSampleRadiusPixels);
  depth.bind(0);
  mFlareState.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  glDispatchCompute(1, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  if (settings.strength <= 0.0f) {
    return;
  }
  const GLboolean depthTest = glIsEnabled(GL_DEPTH_TEST);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE);
  mFlare.use();
  mFlare.setUniform("uStrength", settings.strength);
  mVao.bind();
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, kFlareGhostCount);
  glDisable(GL_BLEND);
  if (depthTest == GL_TRUE) {
    glEnable(GL_DEPTH_TEST);
  }
}

float SkyRenderer::lastFlareVisibility() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::array<glm::vec4, 2> state{};
  mFlareState.getSubData(0, sizeof(state), state.data());
  return state[1].x;
}

glm::vec4 SkyRenderer::lastSunPixel() const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::array<glm::vec4, 2> state{};
  mFlareState.getSubData(0, sizeof(state), state.data());
  return state[0];
}

} // namespace sylva::render
