// Distance haze shared by every pass: applyAtmosphere(colour, worldPos) takes a lit linear colour at a world
// position and returns what the camera sees through the air in front of it.
#pragma once
#include "frame.glsl"

vec3 applyAtmosphere(vec3 lit, vec3 worldPos) {
  float distance = length(worldPos - frame.cameraPos.xyz);
  float fog = clamp(1.0 - exp(-frame.fogColor.a * distance), 0.0, 1.0);
  return mix(lit, frame.fogColor.rgb, fog);
}
