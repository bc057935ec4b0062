// The wind field (docs/wind.md): mean flow, gusts travelling downwind, turbulence. The twin of
// engine/wind/src/Wind.cpp, operation for operation; WindUniforms is in shared/Wind.h.
#pragma once

#include "../shared/Wind.h"
#include "hash.glsl"

float windLattice(int i, int j, int k, uint seed) {
  uint h = lowbias32(uint(i) * 73856093u ^ uint(j) * 19349663u ^ uint(k) * 83492791u ^ lowbias32(seed));
  return float(h & 0xffffu) * (2.0 / 65535.0) - 1.0;
}

float windSmooth(float t) { return t * t * (3.0 - 2.0 * t); }

float windMix(float a, float b, float t) { return a + (b - a) * t; }

/** 3D value noise in [-1, 1] (valueNoise in C++). */
float windValueNoise(vec3 p, uint seed) {
  vec3 f = floor(p);
  int i = int(f.x);
  int j = int(f.y);
  int k = int(f.z);
  float u = windSmooth(p.x - f.x);
  float v = windSmooth(p.y - f.y);
  float w = windSmooth(p.z - f.z);
  float x00 = windMix(windLattice(i, j, k, seed), windLattice(i + 1, j, k, seed), u);
  float x10 = windMix(windLattice(i, j + 1, k, seed), windLattice(i + 1, j + 1, k, seed), u);
  float x01 = windMix(windLattice(i, j, k + 1, seed), windLattice(i + 1, j, k + 1, seed), u);
  float x11 = windMix(windLattice(i, j + 1, k + 1, seed), windLattice(i + 1, j + 1, k + 1, seed), u);
  return windMix(windMix(x00, x10, v), windMix(x01, x11, v), w);
}

/** Mean flow plus gust along the mean direction, m/s (gustSpeed in C++). */
float windGustSpeed(WindUniforms wind, vec2 position) {
  vec2 dir = wind.flow.xy;
  vec2 across = vec2(-dir.y, dir.x);
  float time = wind.flow.w;
  float along = (dot(position, dir) - wind.gusts.w * time) / wind.gusts.y;
  float side = dot(position, across) / wind.gusts.z;
  float n = windValueNoise(vec3(along, side, time * 0.05), wind.seed.x);
  float gust = clamp(n * 1.6 - 0.2, 0.0, 1.0);
  return wind.flow.z * (1.0 + wind.gusts.x * gust * gust);
}

/** Wind velocity in m/s, world (x, z), at world (x, z) metres (windVelocity in C++). */
vec2 windVelocity(WindUniforms wind, vec2 position) {
  vec2 dir = wind.flow.xy;
  float time = wind.flow.w;
  vec2 mean = dir * windGustSpeed(wind, position);
  vec2 q = position / wind.turbulence.y;
  float t = time * wind.turbulence.z;
  float tx = windValueNoise(vec3(q.x, q.y, t), wind.seed.x + 1u);
  float tz = windValueNoise(vec3(q.x + 31.7, q.y - 17.3, t), wind.seed.x + 2u);
  return mean + vec2(tx, tz) * (wind.flow.z * wind.turbulence.x);
}
