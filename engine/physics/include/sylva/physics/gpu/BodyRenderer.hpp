#pragma once
// Draws a world's bodies (instanced spheres with a checker pattern that shows them roll; capsules and boxes
// as their bounding spheres) with the scene's sun and fog. Needs a current GL context.

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/physics/World.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/shader/Library.hpp>

namespace sylva::physics {

/** Draws a World's bodies (spheres, capsules, boxes) lit by the frame's environment. Needs a current context.
 */
class BodyRenderer {
public:
  /** Compiles the body shaders from `library`. */
  explicit BodyRenderer(const shader::Library& library);
  /** Recompiles from `library`; keeps the old programs when compiling fails (and throws). */
  void reloadShaders(const shader::Library& library);
  /** Draws every body of `world` into the bound framebuffer. */
  void draw(const World& world, const render::Camera& camera, int width, int height, double time,
            const render::Environment& environment = {});

private:
  gl::Program mProgram{gl::NoCreate};
  gl::Buffer mInstances{gl::NoCreate};
  gl::VertexArray mVao;
  render::FrameBinding mFrame; ///< the frame path's block, or its own when drawn alone
};

} // namespace sylva::physics
