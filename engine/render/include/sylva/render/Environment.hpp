#pragma once
// A frame's lighting and atmosphere (sun, fog or analytic sky, shadow cascades) as plain data: what the scene
// decides on the CPU and every pass reads through the frame-uniform block (FrameUniforms.hpp, GL). No GL
// here, so shadow fitting and the sky model (Shadows.hpp, Sky.hpp) are CPU code.

#include <glm/glm.hpp>

namespace sylva::render {

class FrameUniformBuffer;

/**
 * Sun shadows of a frame (gpu::FrameUniforms shadow fields): cascades 0 = none. Filled by the scene module
 * from render::ShadowCascades; the depth array itself is bound at SYLVA_SHADOW_MAP_UNIT by whoever owns it.
 */
struct ShadowFrame {
  int cascades = 0;          ///< cascades in use, 0..4
  float depthBias = 0.0f;    ///< receivers move this many metres towards the sun before the compare
  float texel = 0.0f;        ///< 1 / shadow-map size in texels
  float normalOffset = 0.0f; ///< receiver offset along its normal, in texels of its cascade
  glm::vec4 splits{0.0f};    ///< far end of each cascade, metres along the view direction
  glm::mat4 matrices[4]{};   ///< world → cascade shadow-map space [0,1]³
};

/** How distant surfaces fade into the air (gpu::FrameUniforms::atmosphere.x). */
enum class Atmosphere {
  Fog = 0, ///< exponential fog towards `fogColor` (the standalone subsystem views)
  Sky = 1, ///< analytic sky with aerial perspective: haze coloured by the sky in each view direction (scenes)
};

/** Lighting and atmosphere of a frame (linear colours). */
struct Environment {
  glm::vec3 sunDirection = glm::normalize(glm::vec3(0.45f, 0.7f, 0.3f)); ///< towards the sun, world space
  float sunIntensity = 1.1f;                                             ///< sun radiance multiplier
  glm::vec3 fogColor{0.62f, 0.72f, 0.85f};                               ///< linear colour of Atmosphere::Fog
  float fogDensity = 0.0012f;                                            ///< per metre
  Atmosphere atmosphere = Atmosphere::Fog; ///< plain fog or the analytic sky's aerial perspective
  float turbidity = 3.0f;                  ///< sky turbidity (2 clear .. 10 hazy), Atmosphere::Sky only
  float exposure = 1.0f;                   ///< scale on sky radiance, Atmosphere::Sky only
  ShadowFrame shadows;                     ///< no shadows by default
  /**
   * The frame block a frame path (scene::ScenePasses) already uploaded for the camera it is drawing with,
   * from this environment, the pass's target size and time (GL side, FrameUniforms.hpp). Renderers bind it
   * instead of filling a buffer of their own (render::FrameBinding); null outside a frame path.
   */
  const FrameUniformBuffer* frame = nullptr;
};

} // namespace sylva::render
