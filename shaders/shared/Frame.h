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
};
SYLVA_ASSERT_SIZE(FrameUniforms, 192);

SYLVA_GPU_END

#endif
