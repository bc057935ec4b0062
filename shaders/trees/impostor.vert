#version 450
// Far trees as camera-facing billboards (docs/trees.md "Far field"): one instance per tree the cull kept
// (impostor_cull.comp), four vertices, a quad in front of the tree's bounding sphere covering its silhouette
// (the sphere sheared by the tree's lean in the wind).
#include "impostor.glsl"
#include "../common/frame.glsl"

layout(std430, binding = SYLVA_TREE_IMPOSTOR_VISIBLE_BINDING) readonly buffer ImpostorVisible {
  uint visible[];
};

out vec3 vWorld;
flat out uint vInstance;
// Per tree, for the fragments: the bounding sphere (world), the three views to blend (their cells, weights,
// and frames turned into world space: towards the viewer, right, up).
flat out vec4 vSphere;
flat out vec2 vCells[3];
flat out vec3 vWeights;
flat out vec3 vForward[3];
flat out vec3 vRight[3];
flat out vec3 vUp[3];
// The tree's lean in the wind (world x, z per metre above its base) and its base height: the fragments
// un-shear their rays with them.
flat out vec2 vLean;
flat out float vBaseY;

void main() {
  uint index = visible[gl_InstanceID];
  ImpostorInstanceGpu t = impostors[index];
  vInstance = index;
  uint species = min(t.info.y, uint(SYLVA_TREE_MAX_SPECIES - 1));
  vec4 s = impostor.sphere[species];
  float h = t.placement.w;
  float yaw = uintBitsToFloat(t.info.z);
  vec3 centre = t.placement.xyz + yawRotate(s.xyz * h, yaw);
  float radius = s.w * h;
  vec2 lean = impostorLean(t);
  vLean = lean;
  vBaseY = t.placement.y;
  vSphere = vec4(centre, radius);
  vec3 eye = frame.cameraPos.xyz;
  // The views are chosen for the eye as the upright tree sees it (the eye un-sheared), the quad covers the
  // leaning tree's sphere.
  vec3 eyeUpright = eye - vec3(lean.x, 0.0, lean.y) * (eye.y - vBaseY);
  vec3 v = normalize(eyeUpright - centre);
  vec4 leaned = impostorLeanedSphere(vec4(centre, radius), vBaseY, lean);
  centre = leaned.xyz;
  radius = leaned.w;
  vec3 toEye = eye - centre;
  float dist = length(toEye);
  int views = int(impostor.atlas.x);
  ivec2 cells[3];
  vec3 weights;
  impostorViews(yawRotate(v, -yaw), views, cells, weights);
  vWeights = weights;
  for (int k = 0; k < 3; ++k) {
    vec3 f = hemiOctDecode(vec2(cells[k]) / float(max(views - 1, 1)));
    vec3 r;
    vec3 u;
    impostorBasis(f, r, u);
    vCells[k] = vec2(cells[k]);
    vForward[k] = yawRotate(f, yaw);
    vRight[k] = yawRotate(r, yaw);
    vUp[k] = yawRotate(u, yaw);
  }
  v = toEye / dist;
  vec3 right;
  vec3 up;
  impostorBasis(v, right, up);
  // In front of the sphere, widened so its perspective silhouette fits: tan of the angle over the distance.
  float plane = dist - radius;
  float half_ = radius * plane / sqrt(max(dist * dist - radius * radius, 1e-6)) * 1.02;
  vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
  vec3 world = centre + v * radius + (corner.x * right + corner.y * up) * half_;
  vWorld = world;
  gl_Position = frame.viewProj * vec4(world, 1.0);
}
