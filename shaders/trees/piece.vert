#version 450
#extension GL_ARB_shader_draw_parameters : require
// Skins one piece vertex (docs/trees.md). Rim vertices are not skinned by weights: they take the canonical
// corner (and its fixed normal) straight through their one joint's frame, the same float operations on both
// sides of a seam, so interlocking pieces meet bit for bit. Interior vertices blend up to four joints; the
// root joint is the parent's terminal joint, turned by the instance's rim rotation.
#include "trees.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in uvec4 aJoints;
layout(location = 3) in vec4 aWeights;
layout(location = 4) in vec2 aUv;
layout(location = 5) in int aRim; // rim << 8 | corner, or -1
layout(location = 6) in uint aInstance;

out vec3 vcWorld;
out vec3 vcNormal;
out vec2 vcUv;
out float vcRootWeight;
flat out uint vcInstance;
flat out uint vcQuadBase;

// Added to gl_DrawIDARB: the command index when the draws are single draws (the per-piece baseline).
uniform uint uDrawBase;

uint globalJoint(uvec4 inst, uint j) { return j == 0u ? inst.x : inst.y + j - 1u; }

void main() {
  uvec4 inst = instances[aInstance].joints;
  uint rotation = SYLVA_TREE_INSTANCE_ROTATION(inst.z);
  uint type = SYLVA_TREE_INSTANCE_TYPE(inst.z);
  vec3 world;
  vec3 normal;
  if (aRim >= 0) {
    uint rim = uint(aRim) >> 8;
    uint corner = uint(aRim) & 255u;
    uint c = rim == 0u ? (corner + rotation) % 6u : corner;
    JointFrame f = joints[globalJoint(inst, rim)];
    vec3 local = trees.corners[c].xyz;
    if ((trees.info.w & 1u) != 0u && rim == 0u) {
      local *= 0.97; // debug: a broken rim, to show the watertightness check catches it
    }
    world = framePoint(f, local);
    normal = frameVector(f, trees.rimNormals[c].xyz);
    vcRootWeight = rim == 0u ? 1.0 : 0.0;
  } else {
    world = vec3(0.0);
    normal = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
      float w = aWeights[k];
      if (w == 0.0) {
        continue;
      }
      uint j = aJoints[k];
      vec3 p;
      vec3 n;
      if (j == 0u) {
        p = rimTurn(aPosition, rotation);
        n = rimTurn(aNormal, rotation);
      } else {
        JointFrame inv = pieceTable[type].inverseBind[j];
        p = framePoint(inv, aPosition);
        n = frameVector(inv, aNormal);
      }
      JointFrame f = joints[globalJoint(inst, j)];
      world += w * framePoint(f, p);
      normal += w * frameVector(f, n);
    }
    vcRootWeight = aJoints.x == 0u ? aWeights.x : 0.0;
  }
  vcWorld = world;
  vcNormal = normalize(normal);
  vcUv = aUv;
  vcInstance = aInstance;
  // The quad chunk this command draws: its first quad id, so the patch id is the quad's stable id.
  vcQuadBase = (uint(gl_DrawIDARB) + uDrawBase - pieceTable[type].range.x) * uint(trees.cull.y);
}
