// Distance haze shared by every pass: applyAtmosphere(colour, worldPos) takes a lit linear colour at a world
// position and returns what the camera sees through the air in front of it.
//   frame.atmosphere.x == 0: exponential fog towards frame.fogColor.rgb (density frame.fogColor.a per metre).
//   frame.atmosphere.x == 1: aerial perspective: lit · T + inscatter · (1 − T), T = exp(−density · distance),
//   inscatter = the sky in the view direction (towards the horizon below it) + the sun's forward Mie glow
//   (sky.glsl; CPU twin render::aerial).
#pragma once
#include "frame.glsl"
#include "sky.glsl"

/** Aerial perspective of `lit` seen `distance` metres away along unit `viewDir` (mode 1). */
vec3 aerialPerspective(vec3 lit, vec3 viewDir, float distance) {
  float transmittance = exp(-frame.fogColor.a * distance);
  vec3 inscatter = skyInscatter(viewDir, normalize(frame.sunDirection.xyz), frame.atmosphere.y,
                                frame.atmosphere.z, frame.sunDirection.w);
  return lit * transmittance + inscatter * (1.0 - transmittance);
}

vec3 applyAtmosphere(vec3 lit, vec3 worldPos) {
  if (frame.atmosphere.x > 0.5) {
    vec3 toSurface = worldPos - frame.cameraPos.xyz;
    float range = length(toSurface);
    return aerialPerspective(lit, range > 0.0 ? toSurface / range : vec3(0.0, 0.0, -1.0), range);
  }
  float distance = length(worldPos - frame.cameraPos.xyz);
  float fog = clamp(1.0 - exp(-frame.fogColor.a * distance), 0.0, 1.0);
  return mix(lit, frame.fogColor.rgb, fog);
}
