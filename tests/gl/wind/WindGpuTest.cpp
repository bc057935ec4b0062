// wind.glsl against the C++ wind field: the same velocities at thousands of points and several times.
#include <sylva/core/Random.hpp>
#include <sylva/gl/Buffer.hpp>
#include <sylva/shader/Compiler.hpp>
#include <sylva/wind/Wind.hpp>

#include "GlTest.hpp"

#include <epoxy/gl.h>

#include <glm/geometric.hpp>

#include <vector>

namespace sylva::wind {
namespace {

using WindGpu = test::GlTest;

TEST_F(WindGpu, ShaderMatchesCpu) {
  const gl::Program program = shader::compileProgram(shaders(), {"wind sample", {"wind/sample.comp"}, {}});
  Rng rng(3);
  std::vector<glm::vec2> points(4096);
  for (glm::vec2& p : points) {
    // Hundreds of metres: float positions lose bits there, and both sides must lose the same ones.
    p = {rng.uniform(-400.0f, 400.0f), rng.uniform(-400.0f, 400.0f)};
  }
  const gl::Buffer pointBuffer{std::span<const glm::vec2>(points)};
  const gl::Buffer out(points.size() * sizeof(glm::vec2));
  WindSettings settings;
  settings.direction = {0.6f, -0.8f};
  settings.speed = 6.0f;
  settings.seed = 11;
  double worst = 0.0;
  for (const float time : {0.0f, 1.7f, 93.25f, 1000.5f}) {
    const gpu::WindUniforms u = toUniforms(settings, time);
    const gl::Buffer uniforms(sizeof(u), &u);
    uniforms.bindBase(GL_UNIFORM_BUFFER, SYLVA_WIND_BINDING);
    pointBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    out.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    program.use();
    glDispatchCompute(static_cast<GLuint>((points.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<glm::vec2> gpu = out.read<glm::vec2>();
    ASSERT_EQ(gpu.size(), points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::vec2 cpu = windVelocity(u, points[i]);
      const double d = glm::length(cpu - gpu[i]);
      worst = std::max(worst, d);
      ASSERT_LT(d, 1e-4) << "point " << i << " at t = " << time;
    }
  }
  RecordProperty("worst_mps", std::to_string(worst));
  std::printf("worst CPU/GPU difference %.3g m/s\n", worst);
}

} // namespace
} // namespace sylva::wind
