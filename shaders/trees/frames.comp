#version 450
// Every joint's world frame from the springs' bends (sylva/trees/JointWind.hpp): one invocation per global
// joint composes its chain from the tree's base down, frames[j] = base · local · … · local(j), in the order
// forestJointFrames in engine/trees/src/JointWind.cpp multiplies parent by child.
#include "jointwind.glsl"

layout(local_size_x = SYLVA_TREE_WIND_GROUP) in;

layout(std140, binding = SYLVA_TREE_WIND_STEP_BINDING) uniform JointWindBlock {
  WindUniforms jointWind;
  JointWindStepGpu jointStep;
};
layout(std430, binding = SYLVA_TREE_WIND_BINDING) readonly buffer Motion {
  vec4 motion[];
};
layout(std430, binding = SYLVA_TREE_WIND_REST_BINDING) readonly buffer Rest {
  TreeJointRest jointRest[];
};
layout(std430, binding = SYLVA_TREE_JOINT_BINDING) writeonly buffer Frames {
  JointFrame frames[];
};

JointFrame localOf(uint j) {
  TreeJointRest r = jointRest[j];
  return jointLocalFrame(r, r.probe.zw + motion[j].xy);
}

void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= jointStep.counts.x) {
    return;
  }
  // The chain from j up to its tree's base (at most SYLVA_TREE_MAX_JOINT_CHAIN joints).
  uint chain[SYLVA_TREE_MAX_JOINT_CHAIN];
  int n = 0;
  uint a = j;
  while (a != SYLVA_TREE_NO_PARENT && n < SYLVA_TREE_MAX_JOINT_CHAIN) {
    chain[n] = a;
    n += 1;
    a = jointRest[a].info.x;
  }
  JointFrame f = localOf(chain[n - 1]);
  for (int i = n - 2; i >= 0; --i) {
    f = composeFrames(f, localOf(chain[i]));
  }
  frames[j] = f;
}
