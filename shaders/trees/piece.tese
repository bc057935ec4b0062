#version 450
// Phong tessellation adapted to quads (Boubekeur & Alexa 2008 with bilinear weights; the CPU twin is
// phongQuad in engine/trees/src/Tessellation.cpp). On an edge only that edge's two corners have non-zero
// weights, so the two quads sharing it (and two pieces sharing a rim) compute the same points. `precise`
// keeps the compiler from fusing or reordering those operations differently in the two patches.
#include "trees.glsl"
#include "../common/frame.glsl"

layout(quads, fractional_odd_spacing, ccw) in;

in vec3 teWorld[];
in vec3 teNormal[];
in vec2 teUv[];
in float teRootWeight[];
flat in uint teInstance[];
flat in uint teQuadBase[];

out vec3 fWorld;
out vec3 fNormal;
out vec2 fUv;
out float fRootWeight;
flat out uint fInstance;
flat out uint fPatch;
flat out float fLevel;
out vec2 fTile;         // tile coordinates: x across in [0, 1], y along the branch in [0, repeat]
flat out uint fTileRepeat; // tiles along the quad's grain (tileRepeat)
flat out uint fTileClass; // the quad table entry x: class | rotation << 8 | side flips << 10 | repeat
flat out uint fTileEdges; // the quad's four edge ids

const float kAlpha = 0.75;

vec3 project(vec3 q, vec3 p, vec3 n) {
  precise vec3 r = q - dot(q - p, n) * n;
  return r;
}

void main() {
  float u = gl_TessCoord.x;
  float v = gl_TessCoord.y;
  precise float w0 = (1.0 - u) * (1.0 - v);
  precise float w1 = u * (1.0 - v);
  precise float w2 = u * v;
  precise float w3 = (1.0 - u) * v;
  precise vec3 p = w0 * teWorld[0] + w1 * teWorld[1] + w2 * teWorld[2] + w3 * teWorld[3];
  precise vec3 phong = w0 * project(p, teWorld[0], teNormal[0]) + w1 * project(p, teWorld[1], teNormal[1]) +
                       w2 * project(p, teWorld[2], teNormal[2]) + w3 * project(p, teWorld[3], teNormal[3]);
  precise vec3 world = (1.0 - kAlpha) * p + kAlpha * phong;
  fWorld = world;
  fNormal = normalize(w0 * teNormal[0] + w1 * teNormal[1] + w2 * teNormal[2] + w3 * teNormal[3]);
  fUv = w0 * teUv[0] + w1 * teUv[1] + w2 * teUv[2] + w3 * teUv[3];
  fRootWeight = w0 * teRootWeight[0] + w1 * teRootWeight[1] + w2 * teRootWeight[2] + w3 * teRootWeight[3];
  fInstance = teInstance[0];
  // The quad's stable id within its piece (gl_PrimitiveID restarts with every command and instance).
  fPatch = teQuadBase[0] + uint(gl_PrimitiveID);
  fLevel = gl_TessLevelInner[0];
  uint z = instances[teInstance[0]].joints.z;
  uvec2 entry = quadTileEntry(SYLVA_TREE_INSTANCE_TYPE(z), fPatch);
  fTileRepeat = tileRepeat(entry.x, SYLVA_TREE_INSTANCE_STRETCH(z));
  fTile = tileCoord(vec2(u, v), (entry.x >> 8) & 3u) * vec2(1.0, float(fTileRepeat));
  fTileClass = entry.x;
  fTileEdges = entry.y;
  gl_Position = frame.viewProj * vec4(world, 1.0);
}
