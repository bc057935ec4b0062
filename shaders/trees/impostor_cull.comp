#version 450
// Culls the far trees (docs/trees.md "Far field"): keeps those dissolving in or beyond the far range's start
// (far-only trees always), not too near and within the frustum (its sphere sheared by its lean in the wind), appending them to the visible list and
// counting them into the instanced draw's command.
#include "impostor.glsl"
#include "../common/frame.glsl"

layout(local_size_x = SYLVA_TREE_IMPOSTOR_CULL_GROUP) in;

layout(std430, binding = SYLVA_TREE_IMPOSTOR_VISIBLE_BINDING) writeonly buffer ImpostorVisible {
  uint visible[];
};
layout(std430, binding = SYLVA_TREE_IMPOSTOR_COMMAND_BINDING) buffer ImpostorCommand {
  uint command[4]; // count, instance count, first, base instance
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= impostor.info.x) {
    return;
  }
  ImpostorInstanceGpu t = impostors[i];
  uint species = min(t.info.y, uint(SYLVA_TREE_MAX_SPECIES - 1));
  vec4 s = impostor.sphere[species];
  float h = t.placement.w;
  vec3 centre = t.placement.xyz + yawRotate(s.xyz * h, uintBitsToFloat(t.info.z));
  vec4 leaned = impostorLeanedSphere(vec4(centre, s.w * h), t.placement.y, impostorLean(t));
  if (impostorVisible(t, frame.cameraPos.xyz, leaned.xyz, leaned.w)) {
    visible[atomicAdd(command[1], 1u)] = i;
  }
}
