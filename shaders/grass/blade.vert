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
out float vFlatten;        // 0 standing … 1 lying flat (simulated blades pressed down from their procedural pose)

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

// A blade's procedural pose around knot k: knots k − 1, k and k + 1 of its knot line bent downwind (the walk of
// expandBlade), knot k's bend angle and length along the line, the line's length and the bend's axis.
struct Walk {
  vec3 before;
  vec3 here;
  vec3 after;
  float angleHere;
  float alongHere;
  float total;
  vec3 axis;
};

Walk walkBlade(GrassBlade b, uint type, vec3 root, int k, int n, int first) {
  float scale = b.placement.w;
  float cy = cos(b.placement.z);
  float sy = sin(b.placement.z);
  vec2 wind = windVelocity(grass.wind, root.xz);
  float speed = length(wind);
  float theta = min(1.3, 0.12 * abs(speed) / max(bladeTypes[type].colour.w, 0.05));
  vec3 downwind = speed > 1e-6 ? vec3(wind.x, 0.0, wind.y) / speed : vec3(0.0);
  Walk w;
  w.axis = speed > 1e-6 ? normalize(cross(vec3(0.0, 1.0, 0.0), downwind)) : vec3(1.0, 0.0, 0.0);

  float total = 0.0;
  for (int m = 1; m < n; ++m) {
    total += length(grassKnot(type, first + m) - grassKnot(type, first + m - 1));
  }
  w.total = max(total, 1e-9);
  // Walk the bent knot line up to knot k + 1, keeping knots k - 1, k, k + 1 and knot k's bend and length.
  int last = min(k + 1, n - 1);
  vec3 centre = root;
  w.before = root;
  w.here = root;
  w.after = root;
  w.angleHere = 0.0;
  w.alongHere = 0.0;
  float along = 0.0;
  for (int m = 1; m <= last; ++m) {
    vec3 d = grassKnot(type, first + m) - grassKnot(type, first + m - 1);
    vec3 segment = vec3(cy * d.x + sy * d.z, d.y, -sy * d.x + cy * d.z) * scale;
    along += length(d);
    float u = along / w.total;
    float angle = theta * u * u;
    centre = centre + grassRotate(segment, w.axis, angle);
    if (m == k - 1) {
      w.before = centre;
    }
    if (m == k) {
      w.here = centre;
      w.angleHere = angle;
      w.alongHere = along;
    }
    w.after = centre;
  }
  if (k == 0) {
    w.before = root;
  }
  return w;
}

void main() {
  // A simulated blade: (marker, pool blade, packed bits, release ramp); its root is the pool's first knot. A
  // tuft blade following one stands beside that root (forEachTuftBlade) on the terrain.
  bool tuft = aInstance.x == SYLVA_GRASS_TUFT_SIMULATED;
  bool simulated = aInstance.x == SYLVA_GRASS_SIMULATED || tuft;
  uint poolBlade = aInstance.y & SYLVA_GRASS_POOL_MASK;
  vec3 poolRoot = simulated ? simKnots[poolBlade * uint(SYLVA_GRASS_SIM_KNOTS)].xyz : vec3(0.0);
  vec3 root = simulated ? poolRoot : uintBitsToFloat(aInstance.xyz);
  uint info = simulated ? aInstance.z : aInstance.w;
  uint index = info & SYLVA_GRASS_INDEX_MASK;
  int lod = int((info >> 22) & 3u);
  GrassBlade b = patchBlades[index];
  if (tuft) {
    vec2 xz = poolRoot.xz + (b.placement.xy / grass.orient.w - 0.5) * (2.0 * grass.near.z);
    bool ok;
    root = vec3(xz.x, grassTerrainHeight(xz, ok), xz.y);
  }
  uint type = min(b.info.x, grass.options.z - 1u);
  int n = grassLodKnots(lod);
  int first = grassLodFirst(lod);
  int k = min(gl_VertexID >> 1, n - 1);
  float sideSign = (gl_VertexID & 1) == 0 ? -1.0 : 1.0;

  float scale = b.placement.w;
  float cy = cos(b.placement.z);
  float sy = sin(b.placement.z);
  Walk w = walkBlade(b, type, root, k, n, first);
  vec3 before = w.before;
  vec3 here = w.here;
  vec3 after = w.after;
  float alongHere = w.alongHere;
  float total = w.total;
  vec3 face = grassRotate(vec3(sy, 0.0, cy), w.axis, w.angleHere);
  vec3 tangent = normalize(after - before);
  vec3 side = cross(tangent, face);
  side = length(side) > 1e-9 ? normalize(side) : vec3(cy, 0.0, -sy);
  vec3 normal = normalize(cross(side, tangent));
  float flatten = 0.0;
  if (simulated) {
    // The pool's knots, blended back to the procedural pose over the release ramp; the blade's width turns with
    // its simulated tangent.
    float release = uintBitsToFloat(aInstance.w);
    uint knot0 = poolBlade * uint(SYLVA_GRASS_SIM_KNOTS);
    vec3 simBefore = simKnots[knot0 + uint(max(k - 1, 0))].xyz;
    vec3 simHere = simKnots[knot0 + uint(k)].xyz;
    vec3 simAfter = simKnots[knot0 + uint(min(k + 1, n - 1))].xyz;
    if (tuft) {
      // Its own pose moved as far as its field blade's simulated knots are from that blade's procedural pose,
      // scaled by their lengths: unmoved at activation (no pop), flattened where the field blade is trampled.
      uint perTile = uint(grass.tiles.z);
      uint patchSize = uint(grass.tiles.w);
      uint guideIndex = (index + patchSize - ((aInstance.y >> 24) * perTile) % patchSize) % patchSize;
      GrassBlade g = patchBlades[guideIndex];
      uint guideType = min(g.info.x, grass.options.z - 1u);
      Walk gw = walkBlade(g, guideType, poolRoot, k, n, first);
      float ratio = (bladeTypes[type].size.x * scale) / max(bladeTypes[guideType].size.x * g.placement.w, 1e-6);
      simBefore = before + (simBefore - gw.before) * ratio;
      simHere = here + (simHere - gw.here) * ratio;
      simAfter = after + (simAfter - gw.after) * ratio;
    }
    simBefore = mix(simBefore, before, release);
    simHere = mix(simHere, here, release);
    simAfter = mix(simAfter, after, release);
    vec3 simTangent = simAfter - simBefore;
    simTangent = length(simTangent) > 1e-9 ? normalize(simTangent) : tangent;
    side = turnLike(tangent, simTangent, side);
    normal = normalize(cross(side, simTangent));
    // How far the knot lies below where the procedural blade holds it, in half blade lengths: flattened
    // blades are shaded as the sky-lit, glossy mat a trampled path is (blade.frag).
    flatten = clamp((here.y - simHere.y) / max(0.5 * bladeTypes[type].size.x * scale, 1e-3), 0.0, 1.0);
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
  vFlatten = flatten;
  gl_Position = frame.viewProj * vec4(position, 1.0);
}
