#include <sylva/physics/gpu/BodyRenderer.hpp>

#include <sylva/shader/Compiler.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <bit>

namespace sylva::physics {
namespace {

/** Segments of the sphere mesh generated in body.vert (around, and pole to pole). */
constexpr int kAround = 32;
constexpr int kRings = 16;

} // namespace

BodyRenderer::BodyRenderer(const shader::Library& library) {
  reloadShaders(library);
}

void BodyRenderer::reloadShaders(const shader::Library& library) {
  mProgram = shader::compileProgram(library, {"bodies", {"physics/body.vert", "physics/body.frag"}, {}});
}

void BodyRenderer::draw(const World& world, const render::Camera& camera, int width, int height, double time,
                        const render::Environment& environment) {
  if (world.bodyCount() == 0) {
    return;
  }
  std::vector<glm::mat4> models;
  const std::vector<ShapeExport> shapes = world.shapes();
  for (std::size_t i = 0; i < world.bodyCount(); ++i) {
    const BodyState s = world.body(static_cast<int>(i));
    const ShapeExport& e = shapes[i];
    const float radius = e.radius + 0.5f * glm::length(e.b - e.a);
    models.push_back(glm::translate(glm::mat4(1.0f), s.position) * glm::mat4_cast(s.orientation) *
                     glm::scale(glm::mat4(1.0f), glm::vec3(radius)));
  }
  const std::size_t bytes = models.size() * sizeof(glm::mat4);
  if (!mInstances || mInstances.size() < bytes) {
    mInstances = gl::Buffer(std::bit_ceil(bytes));
  }
  mInstances.setSubData(0, bytes, models.data());
  mInstances.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  mFrame.bind(camera, width, height, time, environment);
  mProgram.use();
  mProgram.setUniform("uAround", kAround);
  mProgram.setUniform("uRings", kRings);
  mVao.bind();
  glDrawArraysInstanced(GL_TRIANGLES, 0, kAround * kRings * 6, static_cast<GLsizei>(models.size()));
}

} // namespace sylva::physics
