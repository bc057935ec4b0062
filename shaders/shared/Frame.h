// Per-frame uniforms shared by every pass (std140, binding kFrameBinding).
#ifndef SYLVA_SHARED_FRAME_H
#define SYLVA_SHARED_FRAME_H

#include "Prelude.h"

SYLVA_GPU_BEGIN

#define SYLVA_FRAME_BINDING 0

struct FrameUniforms {
  mat4 viewProj;     // world → clip (OpenGL conventions)
  mat4 view;         // world → view
  vec4 cameraPos;    // xyz: camera position in world metres; w: frame time in seconds (fixed clock in tests)
  vec4 sunDirection; // xyz: unit vector towards the sun, world space; w: sun intensity
  vec4 fogColor;     // rgb: fog/sky colour (linear); a: fog density per metre
  vec4 viewport;     // width, height in pixels; 1/width, 1/height
  // x: 0 = flat exponential fog towards fogColor (the standalone subsystems), 1 = analytic sky and aerial
  // perspective (scenes, shaders/common/atmosphere.glsl); y: sky turbidity (2..10); z: exposure; w: reserved
  vec4 atmosphere;
  // x: sun shadow cascades in use (0 = no shadows); y: depth bias (metres towards the sun); z: 1 / shadow-map
  // size in texels; w: normal offset in texels of the receiver's cascade (shaders/common/shadows.glsl)
  vec4 shadowParams;
  vec4 shadowSplits;        // far end of cascade i, metres along the view direction
  mat4 shadowMatrices[4];   // world → cascade i's shadow-map space [0,1]³
};
SYLVA_ASSERT_SIZE(FrameUniforms, 496);

// Texture unit of the sun's cascaded shadow map (sampler2DArrayShadow, one layer per cascade); bound by the scene
// module for every pass, sampled only while shadowParams.x > 0.
#define SYLVA_SHADOW_MAP_UNIT 16

SYLVA_GPU_END

#endif
