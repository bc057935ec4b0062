#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Texture.hpp>

#include <vector>

namespace sylva::render {

/**
 * The sun's cascaded shadow map on the GPU: a GL_DEPTH_COMPONENT32F 2D array (one layer per cascade,
 * size×size texels) with compare mode LEQUAL and linear filtering (hardware 2×2 PCF through
 * sampler2DArrayShadow), clamped to a border of depth 1 (lit outside the map), and one depth-only framebuffer
 * per layer. Usage per frame: for each cascade begin(i), draw the casters with ShadowCascade::camera at
 * size×size, end(); then bind() before drawing the receivers with Environment::shadows = toFrame(...).
 * Needs a current GL context.
 */
class ShadowMaps {
public:
  /** `size` texels per side (16..16384), `cascades` layers (1..4); throws sylva::Error otherwise. */
  ShadowMaps(int size, int cascades);

  int size() const { return mSize; }         ///< texels per side
  int cascades() const { return mCascades; } ///< layers

  /**
   * Starts rendering cascade `cascade`: remembers the bound draw framebuffer, viewport and the state changed
   * here, binds the layer's framebuffer with a size×size viewport, clears depth to 1, turns colour writes
   * off, enables the depth test (LESS, writes on) and slope-scaled polygon offset (`slopeBias` × max depth
   * slope + `unitsBias` × smallest depth step), and unbinds SYLVA_SHADOW_MAP_UNIT so that no pass samples the
   * array while writing it.
   */
  void begin(int cascade, float slopeBias = 1.5f, float unitsBias = 2.0f);
  /** Restores the framebuffer, viewport and state saved by begin(). */
  void end();
  /** Binds the depth array at SYLVA_SHADOW_MAP_UNIT for the receivers' sunVisibility(). */
  void bind() const;
  /** Unbinds SYLVA_SHADOW_MAP_UNIT (texture 0). */
  static void unbind();

  /** The depth array texture. */
  const gl::Texture& texture() const { return mDepth; }
  /** Depth of layer `cascade` as a 1-channel F32 image (rows bottom-up), for tests and pictures. */
  Image downloadDepth(int cascade) const;

private:
  int mSize = 0;
  int mCascades = 0;
  gl::Texture mDepth{gl::NoCreate};
  std::vector<gl::Framebuffer> mFramebuffers;
  bool mActive = false;
  struct Saved {
    GLint framebuffer = 0;
    GLint viewport[4] = {0, 0, 0, 0};
    GLboolean colorMask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    GLboolean depthMask = GL_TRUE;
    GLint depthFunc = GL_LESS;
    GLboolean depthTest = GL_FALSE;
    GLboolean polygonOffset = GL_FALSE;
    GLfloat offsetFactor = 0.0f;
    GLfloat offsetUnits = 0.0f;
  } mSaved;
};

} // namespace sylva::render
