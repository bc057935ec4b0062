#version 450
// One solver step of every blade of the used pool slots (docs/grass-simulation.md): the twin of stepBlade in
// engine/grass/src/Simulation.cpp, operation for operation, with the rest pose of grassCentreLine.
#include "grass.glsl"
#include "../shared/GrassSim.h"
#include "../common/wind.glsl"

layout(local_size_x = 64) in;

layout(std140, binding = SYLVA_GRASS_SIM_BINDING) uniform SimBlock {
  GrassSimUniforms sim;
};
layout(std430, binding = SYLVA_GRASS_SIM_POSITION_BINDING) buffer Positions {
  vec4 knots[];
};
layout(std430, binding = SYLVA_GRASS_SIM_PREVIOUS_BINDING) buffer Previous {
  vec4 previousKnots[];
};
layout(std430, binding = SYLVA_GRASS_SIM_BLADE_BINDING) buffer SimBlades {
  GrassSimBlade simBlades[];
};
layout(std430, binding = SYLVA_GRASS_SIM_WORK_BINDING) readonly buffer Work {
  uint usedSlots[];
};
layout(std430, binding = SYLVA_GRASS_SIM_COLLIDER_BINDING) readonly buffer Colliders {
  GrassCollider colliders[];
};
layout(std430, binding = SYLVA_GRASS_SIM_RANGE_BINDING) readonly buffer Ranges {
  uvec4 colliderRanges[];
};

const int N = SYLVA_GRASS_SIM_KNOTS;
const float CONTACT_DEPTH = 0.01; // kContactDepth in Simulation.cpp

vec3 qrotate(vec4 q, vec3 v) { return v + 2.0 * cross(q.xyz, cross(q.xyz, v) + q.w * v); }
vec4 qconj(vec4 q) { return vec4(-q.xyz, q.w); }
vec4 qmul(vec4 a, vec4 b) { return vec4(a.w * b.xyz + b.w * a.xyz + cross(a.xyz, b.xyz), a.w * b.w - dot(a.xyz, b.xyz)); }
vec4 fromX(vec3 to) {
  if (to.x < -0.99999) {
    return vec4(0.0, 0.0, 1.0, 0.0);
  }
  vec4 q = vec4(0.0, -to.z, to.y, 1.0 + to.x);
  return q / length(q);
}
vec3 safeNormalize(vec3 v) {
  float l = length(v);
  return l > 1e-12 ? v / l : vec3(1.0, 0.0, 0.0);
}

void main() {
  uint perTile = uint(sim.counts.y);
  uint i = gl_GlobalInvocationID.x;
  if (i >= uint(sim.counts.x) * perTile) {
    return;
  }
  uint blade = usedSlots[i / perTile] * perTile + i % perTile;
  uint slot = usedSlots[i / perTile];
  GrassSimBlade sb = simBlades[blade];
  if (sb.info.x == SYLVA_GRASS_SIM_UNUSED) {
    return;
  }
  GrassBlade b = patchBlades[sb.info.x];
  uint type = min(b.info.x, grass.options.z - 1u);
  vec3 root = sb.root.xyz;
  vec2 wind = windVelocity(sim.wind, root.xz);
  vec3 rest[N];
  grassCentreLine(type, b, root, wind, rest);
  vec3 x[N];
  vec3 xp[N];
  for (int k = 0; k < N; ++k) {
    x[k] = knots[blade * uint(N) + uint(k)].xyz;
    xp[k] = previousKnots[blade * uint(N) + uint(k)].xyz;
  }
  float trample = max(0.0, sb.root.w - sim.trample.z);
  float soft = 1.0 - sim.trample.y * trample;
  // 1. Verlet.
  for (int k = 0; k < N; ++k) {
    if (k < 2) {
      x[k] = rest[k];
      xp[k] = rest[k];
      continue;
    }
    vec3 v = x[k] - xp[k];
    xp[k] = x[k];
    x[k] = x[k] + sim.step.y * v + vec3(0.0, -sim.step.z, 0.0);
  }
  // 2. Global shape.
  float global = sim.shape.x * soft;
  for (int k = 2; k < N; ++k) {
    if (float(k) < sim.shape.y) {
      x[k] = x[k] + global * (rest[k] - x[k]);
    }
  }
  // 3. Local shape with propagated frames.
  float share = sim.shape.z * soft;
  vec3 restLocal[N];
  vec4 frame = fromX(safeNormalize(rest[1] - rest[0]));
  for (int k = 1; k < N - 1; ++k) {
    restLocal[k] = qrotate(qconj(frame), rest[k + 1] - rest[k]);
    frame = qmul(frame, fromX(safeNormalize(restLocal[k])));
  }
  frame = fromX(safeNormalize(x[1] - x[0]));
  for (int k = 1; k < N - 1; ++k) {
    for (int pass = 0; pass < sim.counts.z; ++pass) {
      vec3 goal = x[k] + qrotate(frame, restLocal[k]);
      vec3 delta = share * (goal - x[k + 1]);
      if (k >= 2) {
        x[k] = x[k] - delta;
      }
      x[k + 1] = x[k + 1] + delta;
    }
    frame = qmul(frame, fromX(safeNormalize(qrotate(qconj(frame), x[k + 1] - x[k]))));
  }
  // 4. Wind.
  if (sim.shape.w > 0.0) {
    vec3 w = vec3(wind.x, 0.0, wind.y);
    for (int k = 2; k < N; ++k) {
      vec3 e = x[k] - x[k - 1];
      float ee = max(dot(e, e), 1e-12);
      vec3 across = w - e * (dot(w, e) / ee);
      x[k] = x[k] + sim.shape.w * length(across) * across * (sim.step.x * sim.step.x);
    }
  }
  // 5. Lengths.
  for (int pass = 0; pass < sim.counts.w; ++pass) {
    for (int parity = 0; parity < 2; ++parity) {
      for (int j = parity; j < N - 1; j += 2) {
        if (j == 0) {
          continue;
        }
        float restLength = length(rest[j + 1] - rest[j]);
        vec3 d = x[j + 1] - x[j];
        vec3 delta = (1.0 - restLength / max(length(d), 1e-7)) * d;
        if (j == 1) {
          x[j + 1] = x[j + 1] - delta;
        } else {
          x[j] = x[j] + 0.5 * delta;
          x[j + 1] = x[j + 1] - 0.5 * delta;
        }
      }
    }
  }
  // 6. Collision: bodies near this tile, then the ground; inelastic in proportion to the penetration.
  uvec4 range = colliderRanges[slot];
  for (uint c = range.x; c < range.x + range.y; ++c) {
    GrassCollider body = colliders[c];
    vec3 axis = body.b.xyz - body.a.xyz;
    float aa = dot(axis, axis);
    for (int k = 2; k < N; ++k) {
      float t = aa > 1e-12 ? clamp(dot(x[k] - body.a.xyz, axis) / aa, 0.0, 1.0) : 0.0;
      vec3 p = body.a.xyz + t * axis;
      vec3 outward = x[k] - p;
      float dist = length(outward);
      if (dist >= body.a.w) {
        continue;
      }
      float contact = min((body.a.w - dist) / CONTACT_DEPTH, 1.0);
      x[k] = p + (dist > 1e-9 ? outward / dist : vec3(0.0, 1.0, 0.0)) * body.a.w;
      vec3 along = aa > 1e-12 ? axis * (dot(x[k] - xp[k], axis) / aa) : vec3(0.0);
      xp[k] = xp[k] + contact * (x[k] - 0.4 * along - xp[k]);
      if (body.b.w >= sim.trample.x) {
        trample = max(trample, contact);
      }
    }
  }
  for (int k = 2; k < N; ++k) {
    bool ok;
    float g = grassTerrainHeight(x[k].xz, ok);
    if (ok && x[k].y < g) {
      float contact = min((g - x[k].y) / CONTACT_DEPTH, 1.0);
      x[k].y = g;
      xp[k] = xp[k] + contact * (x[k] - xp[k]);
    }
  }
  // 7. Velocity clamp.
  for (int k = 2; k < N; ++k) {
    vec3 v = x[k] - xp[k];
    float speed = length(v);
    if (speed > sim.step.w) {
      xp[k] = x[k] - v * (sim.step.w / speed);
    }
  }
  for (int k = 0; k < N; ++k) {
    knots[blade * uint(N) + uint(k)] = vec4(x[k], 0.0);
    previousKnots[blade * uint(N) + uint(k)] = vec4(xp[k], 0.0);
  }
  simBlades[blade].root.w = trample;
}
