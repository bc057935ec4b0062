#pragma once

#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/gl/VertexArray.hpp>
#include <sylva/shader/Library.hpp>

#include <glm/glm.hpp>

namespace sylva::render {

/** How the lens flare is drawn. */
struct FlareSettings {
  float strength = 1.0f; ///< scale on the ghosts' colours (0 = no flare)
  float minSampleRadiusPixels =
      4.0f; ///< smallest radius of the visibility test's disc around the sun, pixels
};

/**
 * The sky pass and the sun's lens flare (render::Sky.hpp holds their CPU references). Both read the frame
 * uniforms (FrameUniformBuffer::bind() first): sun direction and intensity, atmosphere.y turbidity, .z
 * exposure. Needs a current GL context; move-only.
 *
 * Scene use, after the opaque passes into a RenderTarget:
 *   sky.drawSky();                      // fills the pixels nothing covered (depth still 1)
 *   ... transparent passes ...
 *   sky.drawFlare(target.depth());      // last: additive ghosts scaled by the sun's visibility
 */
class SkyRenderer {
public:
  /** Compiles the sky and flare programs from `library`; needs a current context. */
  explicit SkyRenderer(const shader::Library& library);

  /** Recompiles the programs from `library` (viewer hot reload); keeps the old ones and throws on error. */
  void reloadShaders(const shader::Library& library);

  /**
   * Draws the Preetham sky and the sun's disc into the bound framebuffer: one full-screen triangle at the far
   * plane with depth test LEQUAL and no depth writes, so only pixels still at depth 1 change; writes sRGB.
   * Leaves depth test on with GL_LESS and depth writes on (RenderTarget::begin's state).
   */
  void drawSky() const;

  /**
   * Tests the sun's visibility against `depth` (the bound target's depth attachment, e.g.
   * RenderTarget::depth(): window depth, 1 = nothing drawn) with a one-work-group compute pass over
   * kFlareSamples texels around the sun, then adds the ghosts to the bound framebuffer scaled by that
   * fraction (no CPU readback, no depth test, blending GL_ONE/GL_ONE; blending is left off and the depth test
   * as it was).
   */
  void drawFlare(const gl::Texture& depth, const FlareSettings& settings = {}) const;

  /** The visibility the last drawFlare measured (0..1); reads the GPU buffer back (stalls): tests and tools.
   */
  float lastFlareVisibility() const;
  /** The sun's window pixel (xy), in-front flag (z) and sample radius in pixels (w) of the last drawFlare. */
  glm::vec4 lastSunPixel() const;

private:
  gl::Program mSky{gl::NoCreate};
  gl::Program mVisibility{gl::NoCreate};
  gl::Program mFlare{gl::NoCreate};
  gl::Buffer mFlareState;
  gl::VertexArray mVao;
};

} // namespace sylva::render
