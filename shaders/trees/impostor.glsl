// Octahedral impostors of far trees (docs/trees.md "Far field"): GLSL twins of the hemi-octahedral mapping,
// the view selection and the view frames in sylva/trees/FarField.hpp, and the impostor pass's resources.
#pragma once
#include "../shared/Trees.h"
#include "fade.glsl"
#include "../common/wind.glsl"

layout(std430, binding = SYLVA_TREE_IMPOSTOR_BINDING) readonly buffer ImpostorInstances {
  ImpostorInstanceGpu impostors[];
};
layout(std140, binding = SYLVA_TREE_IMPOSTOR_UNIFORM_BINDING) uniform ImpostorBlock {
  ImpostorUniforms impostor;
};

/** Whether far tree `t` is drawn (the cull's rule; impostorVisible in C++): it is dissolving in or beyond (or
 * far-only), the camera is outside twice its bounding sphere, and the sphere meets the frustum. `centre` and
 * `radius` are its bounding sphere (world). */
bool impostorVisible(ImpostorInstanceGpu t, vec3 eye, vec3 centre, float radius) {
  float h = t.placement.w;
  bool farOnly = (t.info.w & SYLVA_TREE_IMPOSTOR_FAR_ONLY) != 0u;
  float d = distance(eye, t.placement.xyz + vec3(0.0, 0.5 * h, 0.0));
  float blend = farOnly ? 1.0 : farBlend(d, impostor.far.xy);
  if (blend <= 0.0 || distance(eye, centre) < 2.0 * radius) {
    return false;
  }
  for (int p = 0; p < 6; ++p) {
    if (dot(impostor.frustum[p].xyz, centre) + impostor.frustum[p].w < -radius) {
      return false;
    }
  }
  return true;
}

/** Seconds added to the wind's clock for far tree `id` (impostorWindOffset in C++). */
float impostorWindOffset(uint id) {
  return float(lowbias32(id) >> 8u) * (600.0 / 16777216.0);
}

/** Far tree `t`'s lean in the wind, world (x, z) metres per metre above its base (impostorLean in C++,
 * sylva/trees/FarField.hpp ImpostorSway): k · |u| u at the base, at most the species' longest lean. */
vec2 impostorLean(ImpostorInstanceGpu t) {
  uint species = min(t.info.y, uint(SYLVA_TREE_MAX_SPECIES - 1));
  vec4 sway = impostor.sway[species];
  if (!(sway.x > 0.0) || !(impostor.wind.flow.z > 0.0)) {
    return vec2(0.0);
  }
  WindUniforms w = impostor.wind;
  w.flow.w = w.flow.w + impostorWindOffset(t.info.x);
  vec2 u = windVelocity(w, t.placement.xz);
  vec2 lean = sway.x * length(u) * u;
  float len = length(lean);
  return len > sway.y ? lean * (sway.y / len) : lean;
}

/** The bounding sphere of a tree sheared by `lean` about its base at height `baseY` (impostorLeanedSphere in
 * C++): centre + lean · (centre.y − baseY), radius · (1 + |lean|). */
vec4 impostorLeanedSphere(vec4 sphere, float baseY, vec2 lean) {
  float up = sphere.y - baseY;
  return vec4(sphere.x + lean.x * up, sphere.y, sphere.z + lean.y * up, sphere.w * (1.0 + length(lean)));
}

/** Unit direction (y up; below the horizon clamped onto it) to hemi-octahedral coordinates in [0, 1]^2. */
vec2 hemiOctEncode(vec3 d) {
  d.y = max(d.y, 0.0);
  float sum = abs(d.x) + d.y + abs(d.z);
  if (!(sum > 0.0)) {
    return vec2(0.5);
  }
  vec2 p = vec2(d.x, d.z) / sum;
  return vec2(p.x + p.y, p.x - p.y) * 0.5 + 0.5;
}

vec3 hemiOctDecode(vec2 uv) {
  vec2 e = clamp(uv, 0.0, 1.0) * 2.0 - 1.0;
  vec2 p = vec2(e.x + e.y, e.x - e.y) * 0.5;
  float y = 1.0 - abs(p.x) - abs(p.y);
  return normalize(vec3(p.x, max(y, 0.0), p.y));
}

/** The three baked views (cells) around `d` and their barycentric weights (sum 1). */
void impostorViews(vec3 d, int views, out ivec2 cells[3], out vec3 weights) {
  int n = max(views, 2);
  vec2 f = hemiOctEncode(d) * float(n - 1);
  ivec2 i = clamp(ivec2(floor(f)), ivec2(0), ivec2(n - 2));
  vec2 t = clamp(f - vec2(i), 0.0, 1.0);
  if (t.x + t.y <= 1.0) {
    cells[0] = i;
    cells[1] = i + ivec2(1, 0);
    cells[2] = i + ivec2(0, 1);
    weights = vec3(1.0 - t.x - t.y, t.x, t.y);
  } else {
    cells[0] = i + ivec2(1, 1);
    cells[1] = i + ivec2(0, 1);
    cells[2] = i + ivec2(1, 0);
    weights = vec3(t.x + t.y - 1.0, 1.0 - t.x, 1.0 - t.y);
  }
}

/** The view frame of direction `forward` (towards the viewer): right, up (impostorBasis in C++). */
void impostorBasis(vec3 forward, out vec3 right, out vec3 up) {
  vec3 hint = forward.y > 0.9999985 ? vec3(0.0, 0.0, -1.0) : vec3(0.0, 1.0, 0.0);
  right = normalize(cross(hint, forward));
  up = cross(forward, right);
}

/** Turn about +y by `yaw` radians (object → world), as baseFrame turns a tree. */
vec3 yawRotate(vec3 v, float yaw) {
  float c = cos(yaw);
  float s = sin(yaw);
  return vec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z);
}
