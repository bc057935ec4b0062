#version 450 core
// Streamed terrain: height and slope colours (meadow, rock, snow), Lambert sun, sky ambient and haze; debug views:
// LOD colours by tile level; world position (relative to the render origin) and the normal (alpha: level + 1)
// for tests.
#include "stream.glsl"
#include "../common/lighting.glsl"

in vec3 teWorldPos;
in vec3 teNormal;
in float teAbsent;
flat in int teLevel;
layout(location = 0) out vec4 outColor;

vec3 levelColour(int level) {
  const vec3 colours[8] = vec3[8](vec3(0.90, 0.30, 0.25), vec3(0.95, 0.65, 0.20), vec3(0.90, 0.90, 0.30),
                                  vec3(0.40, 0.80, 0.35), vec3(0.30, 0.75, 0.85), vec3(0.35, 0.45, 0.90),
                                  vec3(0.65, 0.40, 0.90), vec3(0.90, 0.45, 0.75));
  return colours[level % 8];
}

void main() {
  if (teAbsent > 0.0) {
    discard;
  }
  int view = stream.shape.w;
  if (view == 4) {
    outColor = vec4(teWorldPos, 1.0);
    return;
  }
  vec3 n = normalize(teNormal);
  if (view == 5) {
    outColor = vec4(n, float(teLevel + 1));
    return;
  }
  float slope = 1.0 - n.y;
  // Meadow drying with altitude, rock on steep slopes, snow above 2,400 m on gentle ones (absolute metres:
  // no snow on hills, whatever their range).
  float t = clamp(teWorldPos.y / 2000.0, 0.0, 1.0);
  vec3 meadow = mix(vec3(0.20, 0.30, 0.10), vec3(0.34, 0.36, 0.16), t);
  vec3 rock = vec3(0.32, 0.29, 0.26);
  vec3 snow = vec3(0.85, 0.87, 0.90);
  vec3 albedo = mix(meadow, rock, smoothstep(0.12, 0.30, slope));
  albedo = mix(albedo, snow, smoothstep(2300.0, 2500.0, teWorldPos.y) * (1.0 - smoothstep(0.35, 0.55, slope)));
  if (view == 1) {
    albedo = mix(albedo, levelColour(teLevel), 0.7);
  }
  outColor = vec4(toSrgb(shadeOutdoor(albedo, n, teWorldPos)), 1.0);
}
