#version 450
// Pass 2 of the foliage: one billboard per anchor (instance), a quad on the front plane of the anchor's sphere
// facing the baked view direction, its centre carried by the anchor's joint frame (wind moves it). The image
// is turned in the billboard plane by the anchor's spin. Trees past the far field skip their billboards.
#include "foliage.glsl"
#include "../common/frame.glsl"
#include "fade.glsl"

layout(std430, binding = SYLVA_TREE_JOINT_BINDING) readonly buffer Joints {
  JointFrame joints[];
};
layout(std430, binding = SYLVA_TREE_FOLIAGE_BINDING) readonly buffer Anchors {
  FoliageAnchorGpu anchors[];
};
layout(std430, binding = SYLVA_TREE_CENTRE_BINDING) readonly buffer TreeCentres {
  vec4 treeCentres[]; // base (xyz, m), crown height (w, m)
};

out vec3 fWorld;
out vec2 fUv;
flat out float fRadius;
flat out uint fTree;
flat out uint fSpecies;
flat out float fBlend;

void main() {
  FoliageAnchorGpu a = anchors[gl_InstanceID];
  JointFrame f = joints[a.info.x];
  vec4 p1 = vec4(a.place.xyz, 1.0);
  vec3 centre = vec3(dot(f.x, p1), dot(f.y, p1), dot(f.z, p1));
  float radius = a.place.w;
  // Strip corners (−1, −1), (1, −1), (−1, 1), (1, 1): counter-clockwise seen from the camera.
  vec2 xy = vec2((gl_VertexID & 1) != 0 ? 1.0 : -1.0, (gl_VertexID & 2) != 0 ? 1.0 : -1.0);
  vec2 turned = vec2(a.spin.x * xy.x - a.spin.y * xy.y, a.spin.y * xy.x + a.spin.x * xy.y);
  fWorld = centre + radius * (turned.x * foliage.right.xyz + turned.y * foliage.up.xyz - foliage.forward.xyz);
  fUv = 0.5 * xy + 0.5;
  fRadius = radius;
  fTree = a.info.y;
  fSpecies = min(a.info.z, uint(SYLVA_TREE_MAX_SPECIES - 1));
  // The far-field dissolve of the tree's pieces (piece.frag): distance to the crown centre.
  vec4 c = treeCentres[a.info.y];
  fBlend = farBlend(distance(frame.cameraPos.xyz, c.xyz + vec3(0.0, 0.5 * c.w, 0.0)), foliage.far.xy);
  // Beyond the pieces' draw distance (TreeLod::drawDistance) the billboards go with them.
  bool beyond = foliage.far.z > 0.0 && distance(frame.cameraPos.xyz, centre) - radius > foliage.far.z;
  gl_Position = fBlend >= 1.0 || beyond ? vec4(2.0, 2.0, 2.0, 1.0) : frame.viewProj * vec4(fWorld, 1.0);
}
