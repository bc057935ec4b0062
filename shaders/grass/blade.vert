#version 450
// A blade's knot line expanded to a triangle strip (two vertices per knot, paper Fig. 7) and bent downwind:
// the twin of expandBlade (engine/grass/src/Expand.cpp), operation for operation. One instance per drawn
// blade (uvec4: root as float bits, packed patch index / level / fade), vertex 2k + s = knot k, side s.
#include "grass.glsl"
#include "../common/frame.glsl"
#include "../common/wind.glsl"
#include "../shared/GrassSim.h"

layout(location = 0) in uvec4 aInstance;

out vec3 vWorld;
out vec3 vNormal;
out float vAlong;
out float vSide;
flat out vec3 vColour;
flat out uint vInfo;
flat out uvec2 vTile;
flat out float vSimulated; // -1: procedural; else the release ramp 0..1 of a simulated blade

#ifdef SYLVA_GRASS_CAPTURE
// Parity tests: each vertex as computed (position, along; normal, side), instance-major.
layout(std430, binding = SYLVA_GRASS_CAPTURE_BINDING) writeonly buffer Captured {
  vec4 captured[];
};
#endif

// The pool's knots: simulated blades are drawn from them (docs/grass-simulation.md).
layout(std430, binding = SYLVA_GRASS_SIM_POSITION_BINDING) readonly buffer SimKnots {
  vec4 simKnots[];
};

vec3 grassKnot(uint type, int slot) { return bladeTypes[type].knots[slot].xyz; }

// The shortest rotation taking unit a to unit b, applied to v.
vec3 turnLike(vec3 a, vec3 b, vec3 v) {
  vec3 c = cross(a, b);
  float d = dot(a, b);
  if (d < -0.9999) {
    return -v;
  }
  return v * d + cross(c, v) + c * (dot(c, v) / (1.0 + d));
}

void main() {
  // A simulated blade: (marker, pool blade, packed bits, release ramp); its root is the pool's first knot.
  bool simulated = aInstance.x == SYLVA_GRASS_SIMULATED;
  uint poolBlade = aInstance.y;
  vec3 root = simulated ? simKnots[poolBlade * uint(SYLVA_GRASS_SIM_KNOTS)].xyz : uintBitsToFloat(aInstance.xyz);
  uint info = simulated ? aInstance.z : aInstance.w;
  uint index = info & SYLVA_GRASS_INDEX_MASK;
  int lod = int((info >> 22) & 3u);
  GrassBlade b = patchBlades[index];
  uint type = min(b.info.x, grass.options.z - 1u);
  int n = grassLodKnots(lod);
  int first = grassLodFirst(lod);
  int k = min(gl_VertexID >> 1, n - 1);
  float sideSign = (gl_VertexID & 1) == 0 ? -1.0 : 1.0;

  float scale = b.placement.w;
  float cy = cos(b.placement.z);
  float sy = sin(b.placement.z);
  vec2 wind = windVelocity(grass.wind, root.xz);
  float speed = length(wind);
  float theta = min(1.3, 0.12 * abs(speed) / max(bladeTypes[type].colour.w, 0.05));
  vec3 downwind = speed > 1e-6 ? vec3(wind.x, 0.0, wind.y) / speed : vec3(0.0);
  vec3 axis = speed > 1e-6 ? normalize(cross(vec3(0.0, 1.0, 0.0), downwind)) : vec3(1.0, 0.0, 0.0);

  float total = 0.0;
  for (int m = 1; m < n; ++m) {
    total += length(grassKnot(type, first + m) - grassKnot(type, first + m - 1));
  }
  total = max(total, 1e-9);
  // Walk the bent knot line up to knot k + 1, keeping knots k - 1, k, k + 1 and knot k's bend and length.
  int last = min(k + 1, n - 1);
  vec3 centre = root;
  vec3 before = root;
  vec3 here = root;
  vec3 after = root;
  float angleHere = 0.0;
  float alongHere = 0.0;
  float along = 0.0;
  for (int m = 1; m <= last; ++m) {
    vec3 d = grassKnot(type, first + m) - grassKnot(type, first + m - 1);
    vec3 segment = vec3(cy * d.x + sy * d.z, d.y, -sy * d.x + cy * d.z) * scale;
    along += length(d);
    float u = along / total;
    float angle = theta * u * u;
    centre = centre + grassRotate(segment, axis, angle);
    if (m == k - 1) {
      before = centre;
    }
    if (m == k) {
      here = centre;
      angleHere = angle;
      alongHere = along;
    }
    after = centre;
  }
  if (k == 0) {
    before = root;
  }
  vec3 face = grassRotate(vec3(sy, 0.0, cy), axis, angleHere);
  vec3 tangent = normalize(after - before);
  vec3 side = cross(tangent, face);
  side = length(side) > 1e-9 ? normalize(side) : vec3(cy, 0.0, -sy);
  vec3 normal = normalize(cross(side, tangent));
  if (simulated) {
    // The pool's knots, blended back to the procedural pose over the release ramp; the blade's width turns with
    // its simulated tangent.
    float release = uintBitsToFloat(aInstance.w);
    uint knot0 = poolBlade * uint(SYLVA_GRASS_SIM_KNOTS);
    vec3 simBefore = simKnots[knot0 + uint(max(k - 1, 0))].xyz;
    vec3 simHere = simKnots[knot0 + uint(k)].xyz;
    vec3 simAfter = simKnots[knot0 + uint(min(k + 1, n - 1))].xyz;
    simBefore = mix(simBefore, before, release);
    simHere = mix(simHere, here, release);
    simAfter = mix(simAfter, after, release);
    vec3 simTangent = simAfter - simBefore;
    simTangent = length(simTangent) > 1e-9 ? normalize(simTangent) : tangent;
    side = turnLike(tangent, simTangent, side);
    normal = normalize(cross(side, simTangent));
    here = simHere;
  }
  float halfWidth = 0.5 * bladeTypes[type].knots[first + k].w * scale;
  vec3 position = here + side * (sideSign * halfWidth);
  float v = alongHere / total;

#ifdef SYLVA_GRASS_CAPTURE
  uint slot = uint(gl_InstanceID * 2 * n + gl_VertexID) * 2u;
  captured[slot] = vec4(position, v);
  captured[slot + 1u] = vec4(normal, sideSign);
#endif

  // Per-blade colour variation: brightness and a shift towards straw, from the blade's seed.
  uint h = lowbias32(b.info.y);
  float bright = 0.82 + 0.34 * float(h & 0xffu) / 255.0;
  float straw = 0.3 * float((h >> 8) & 0xffu) / 255.0;
  vColour = mix(bladeTypes[type].colour.rgb, vec3(0.42, 0.4, 0.12), straw) * bright;
  vWorld = position;
  vNormal = normal;
  vAlong = v;
  vSide = sideSign;
  vInfo = info;
  vTile = uvec2(floor((root.xz - grass.field.xy) / grass.orient.w));
  vSimulated = simulated ? uintBitsToFloat(aInstance.w) : -1.0;
  gl_Position = frame.viewProj * vec4(position, 1.0);
}
