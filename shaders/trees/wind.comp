#version 450
// One step of every joint spring of every tree (sylva/trees/JointWind.hpp): one invocation per global joint,
// the twin of stepJointWind in engine/trees/src/JointWind.cpp.
#include "jointwind.glsl"

layout(local_size_x = SYLVA_TREE_WIND_GROUP) in;

layout(std140, binding = SYLVA_TREE_WIND_STEP_BINDING) uniform JointWindBlock {
  WindUniforms jointWind;
  JointWindStepGpu jointStep;
};
layout(std430, binding = SYLVA_TREE_WIND_BINDING) buffer Motion {
  vec4 motion[];
};
layout(std430, binding = SYLVA_TREE_WIND_REST_BINDING) readonly buffer Rest {
  TreeJointRest jointRest[];
};

void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j >= jointStep.counts.x) {
    return;
  }
  motion[j] = jointWindStep(jointRest[j], motion[j], jointWind, jointStep.step.x, jointStep.step.y);
}
