// Sun visibility from the cascaded shadow map (frame.shadowParams.x cascades; 0 = no shadows: fully lit).
// CPU side: engine/render/include/sylva/render/Shadows.hpp (fitCascades, toFrame, cascadeFor); the depth array
// is render::ShadowMaps. Cascade i covers view depths up to frame.shadowSplits[i]; its matrix maps world
// metres to [0,1]³ (xy texture coordinates, z depth). The receiver is pushed along its normal by
// shadowParams.w texels of its cascade (normal offset) and towards the sun by shadowParams.y depth units
// (depth bias); 3×3 taps one texel apart of the hardware 2×2 PCF soften the edge over about 4 texels.
#pragma once
#include "frame.glsl"

layout(binding = SYLVA_SHADOW_MAP_UNIT) uniform sampler2DArrayShadow sunShadowMap;

/** Index of the cascade covering view depth `depth` (metres), or -1 beyond the last one. */
int shadowCascade(float depth) {
  int n = int(frame.shadowParams.x + 0.5);
  for (int i = 0; i < 4; ++i) {
    if (i < n && depth < frame.shadowSplits[i]) {
      return i;
    }
  }
  return -1;
}

/** 1 = fully lit by the sun, 0 = in shadow, for a surface at `worldPos` with unit normal `normal`. */
float sunVisibility(vec3 worldPos, vec3 normal) {
  if (frame.shadowParams.x < 0.5) {
    return 1.0;
  }
  float depth = -(frame.view * vec4(worldPos, 1.0)).z;
  int cascade = shadowCascade(depth);
  if (cascade < 0) {
    return 1.0;
  }
  mat4 m = frame.shadowMatrices[cascade];
  // World metres per texel of this cascade: 1 / (|d tex.x / d world| · size).
  float texelWorld = frame.shadowParams.z / length(vec3(m[0][0], m[1][0], m[2][0]));
  vec3 p = worldPos + normal * (frame.shadowParams.w * texelWorld);
  vec3 s = (m * vec4(p, 1.0)).xyz;
  float ref = min(s.z - frame.shadowParams.y, 1.0); // below every caster: compare with the far plane
  float texel = frame.shadowParams.z;
  float lit = 0.0;
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i) {
      lit += texture(sunShadowMap, vec4(s.xy + vec2(i, j) * texel, float(cascade), ref));
    }
  }
  lit *= 1.0 / 9.0;
  // Fade out over the last tenth of the last cascade instead of ending in a line.
  int last = int(frame.shadowParams.x + 0.5) - 1;
  if (cascade == last) {
    float end = frame.shadowSplits[last];
    lit = mix(lit, 1.0, smoothstep(0.9 * end, end, depth));
  }
  return lit;
}
