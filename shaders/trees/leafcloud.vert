#version 450
// Pass 1 of the foliage (2.5D impostors): the leaf cloud, in cloud units inside the unit sphere, projected
// orthographically along the camera's view direction (foliageBakeMatrix: window depth = t across the sphere).
#include "foliage.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec3 aTint;

out vec3 vCloud;
out vec3 vNormal;
out vec2 vUv;
out vec3 vTint;
out float vT;

void main() {
  vCloud = aPosition;
  vNormal = aNormal;
  vUv = aUv;
  vTint = aTint;
  // t = (z − (z_c − R)) / 2R with z along the view direction, z_c = 0, R = 1.
  vT = 0.5 * (dot(aPosition, foliage.forward.xyz) + 1.0);
  gl_Position = foliage.bake * vec4(aPosition, 1.0);
}
