#version 450
// Tessellation levels of one quad (docs/trees.md): each outer level depends only on its edge's two skinned
// end points, symmetrically (midpoint distance and length), so the two quads sharing an edge (also across a
// rim, where the end points are bit-identical) choose the same level; the inner levels from the quad's centre.
#include "trees.glsl"
#include "../common/frame.glsl"

layout(vertices = 4) out;

in vec3 vcWorld[];
in vec3 vcNormal[];
in vec2 vcUv[];
in float vcRootWeight[];
flat in uint vcInstance[];
flat in uint vcQuadBase[];

out vec3 teWorld[];
out vec3 teNormal[];
out vec2 teUv[];
out float teRootWeight[];
flat out uint teInstance[];
flat out uint teQuadBase[];

float edgeLevel(vec3 a, vec3 b) {
  if (trees.tess.z > 0.0) {
    return trees.tess.z;
  }
  vec3 m = (a + b) * 0.5;
  float len = length(a - b);
  float d = max(length(m - frame.cameraPos.xyz), 1e-3);
  return clamp(trees.tess.x * len / d, 1.0, trees.tess.y);
}

void main() {
  teWorld[gl_InvocationID] = vcWorld[gl_InvocationID];
  teNormal[gl_InvocationID] = vcNormal[gl_InvocationID];
  teUv[gl_InvocationID] = vcUv[gl_InvocationID];
  teRootWeight[gl_InvocationID] = vcRootWeight[gl_InvocationID];
  teInstance[gl_InvocationID] = vcInstance[gl_InvocationID];
  teQuadBase[gl_InvocationID] = vcQuadBase[gl_InvocationID];
  if (gl_InvocationID == 0) {
    // GL quad edges: outer[0] is u = 0 (corners 0, 3), [1] v = 0 (0, 1), [2] u = 1 (1, 2), [3] v = 1 (2, 3).
    float l0 = edgeLevel(vcWorld[0], vcWorld[3]);
    float l1 = edgeLevel(vcWorld[0], vcWorld[1]);
    float l2 = edgeLevel(vcWorld[1], vcWorld[2]);
    float l3 = edgeLevel(vcWorld[2], vcWorld[3]);
    gl_TessLevelOuter[0] = l0;
    gl_TessLevelOuter[1] = l1;
    gl_TessLevelOuter[2] = l2;
    gl_TessLevelOuter[3] = l3;
    float inner;
    if (trees.tess.z > 0.0) {
      inner = trees.tess.z;
    } else {
      vec3 centre = (vcWorld[0] + vcWorld[1] + vcWorld[2] + vcWorld[3]) * 0.25;
      float size = 0.25 * (length(vcWorld[0] - vcWorld[1]) + length(vcWorld[1] - vcWorld[2]) +
                           length(vcWorld[2] - vcWorld[3]) + length(vcWorld[3] - vcWorld[0]));
      inner = clamp(trees.tess.x * size / max(length(centre - frame.cameraPos.xyz), 1e-3), 1.0, trees.tess.y);
    }
    gl_TessLevelInner[0] = inner;
    gl_TessLevelInner[1] = inner;
  }
}
