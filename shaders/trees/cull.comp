#version 450
// Culls every piece instance of every tree against the frustum, the draw distance and its size on screen,
// appending the visible ones to their piece type's list and counting them into that type's indirect draw
// command (cullInstances in C++ is the reference).
#include "trees.glsl"
#include "../common/frame.glsl"
#include "fade.glsl"

layout(local_size_x = SYLVA_TREE_CULL_GROUP) in;

layout(std430, binding = SYLVA_TREE_VISIBLE_BINDING) writeonly buffer Visible {
  uint visible[];
};
// Five uints per piece type: count, instanceCount, firstIndex, baseVertex, baseInstance.
layout(std430, binding = SYLVA_TREE_COMMAND_BINDING) buffer Commands {
  uint commands[];
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= trees.info.x) {
    return;
  }
  uvec4 inst = instances[i].joints;
  // Far field: a tree whose crown is past the fade band is its impostor alone; its pieces would draw nothing.
  if (trees.far.y > trees.far.x &&
      farBlend(crownDistance(inst.w & 0xffffffu, frame.cameraPos.xyz), trees.far.xy) >= 1.0) {
    return;
  }
  uint type = SYLVA_TREE_INSTANCE_TYPE(inst.z);
  TreePieceGpu piece = pieceTable[type];
  JointFrame root = joints[inst.x];
  // Rotation about the rim axis moves the sphere's centre around it: take the axis point and widen the radius.
  // A stretched piece reaches `reach` model units further up its axis: centre half-way, widen by half.
  vec3 c = piece.sphere.xyz;
  float scale = length(vec3(root.x.x, root.y.x, root.z.x));
  float reach = float(SYLVA_TREE_INSTANCE_REACH(inst.z)) / 256.0;
  vec3 centre = framePoint(root, vec3(0.0, c.y + 0.5 * reach, 0.0));
  float radius = (piece.sphere.w + length(c.xz) + 0.5 * reach) * scale * trees.cull.x;
  for (int p = 0; p < 6; ++p) {
    if (dot(trees.frustum[p].xyz, centre) + trees.frustum[p].w < -radius) {
      return;
    }
  }
  float d = distance(centre, frame.cameraPos.xyz);
  if (trees.tess.w > 0.0 && d - radius > trees.tess.w) {
    return;
  }
  // Size culling: under TreeLod::minPixels across (cull.z per metre of distance, cull.w for orthographic),
  // or a branch under TreeLod::minWidthPixels wide (far.zw; the root rim is 2 model units across).
  if (2.0 * radius < trees.cull.z * d + trees.cull.w || 2.0 * scale < trees.far.z * d + trees.far.w) {
    return;
  }
  // The type's first command hands out the slot; its other quad chunks count the same instances.
  uint slot = atomicAdd(commands[piece.range.x * 5u + 1u], 1u);
  for (uint k = 1u; k < piece.range.y; ++k) {
    atomicAdd(commands[(piece.range.x + k) * 5u + 1u], 1u);
  }
  visible[piece.range.z + slot] = i;
}
