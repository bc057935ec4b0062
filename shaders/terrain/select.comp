#version 450 core
// GPU quadtree selection: the same nodes, edge levels and patch records as the CPU Quadtree::select with the
// restricted level map (docs/terrain-lod.md, "GPU selection"). One workgroup walks the tree level by level
// (barriers between levels), appends leaves as TerrainNode records with the indirect draw's instance count,
// then stitches edges from the split bits. Float operations are `precise` and in the CPU's order, so every
// split and culling decision is bit-identical.
#include "../shared/Terrain.h"

layout(local_size_x = SYLVA_TERRAIN_SELECT_GROUP_SIZE) in;

layout(std430, binding = SYLVA_TERRAIN_SELECT_NODE_BINDING) readonly buffer SelectNodes {
  TerrainSelectNode treeNodes[];
};
layout(std430, binding = SYLVA_TERRAIN_SELECT_PARAMS_BINDING) readonly buffer SelectParams {
  TerrainSelectParams params;
};
layout(std430, binding = SYLVA_TERRAIN_SELECT_LIST_BINDING) coherent buffer SelectLists {
  uvec2 items[];
};
layout(std430, binding = SYLVA_TERRAIN_SELECT_SPLIT_BINDING) coherent buffer SelectSplit {
  uint splitBits[];
};
layout(std430, binding = SYLVA_TERRAIN_SELECT_COUNTER_BINDING) coherent buffer SelectCounters {
  TerrainSelectCounters counters;
};
layout(std430, binding = SYLVA_TERRAIN_NODE_BINDING) coherent buffer TerrainNodes {
  TerrainNode nodes[];
};

uint depthOffset(int d) { return params.offsets[d / 4][d % 4]; }
uint bitOffset(int d) { return params.bitOffsets[d / 4][d % 4]; }
int gridWidth(int d) { return params.grid.x << d; }
int gridHeight(int d) { return params.grid.y << d; }

bool splitAt(int d, int x, int z) {
  if (d >= params.grid.z || x < 0 || z < 0 || x >= gridWidth(d) || z >= gridHeight(d)) {
    return false;
  }
  uint bit = bitOffset(d) + uint(z) * uint(gridWidth(d)) + uint(x);
  return (splitBits[bit >> 5] & (1u << (bit & 31u))) != 0u;
}

// sylva::Frustum::test(box) != Outside, with glm's dot order ((x + y) + z).
bool intersects(vec3 lo, vec3 hi) {
  precise vec3 c = 0.5 * (lo + hi);
  precise vec3 e = 0.5 * (hi - lo);
  for (int i = 0; i < 6; ++i) {
    vec4 p = params.planes[i];
    precise float distance = ((p.x * c.x + p.y * c.y) + p.z * c.z) + p.w;
    precise float radius = (abs(p.x) * e.x + abs(p.y) * e.y) + abs(p.z) * e.z;
    if (distance < -radius) {
      return false;
    }
  }
  return true;
}

void visit(int d, uvec2 g, uint nextList) {
  int gx = int(g.x);
  int gz = int(g.y);
  TerrainSelectNode n = treeNodes[depthOffset(d) + uint(gz) * uint(gridWidth(d)) + uint(gx)];
  if (!(n.range.x <= n.range.y)) {
    return; // absent: outside the data
  }
  precise float size = ldexp(params.camera.w, -d);
  precise float x0 = float(gx) * size;
  precise float z0 = float(gz) * size;
  if (params.flags.x != 0 && !intersects(vec3(x0, n.range.x, z0), vec3(x0 + size, n.range.y, z0 + size))) {
    return;
  }
  bool split = false;
  if (d < params.grid.w) {
    vec3 cam = params.camera.xyz;
    precise float dx = max(max(x0 - cam.x, cam.x - (x0 + size)), 0.0);
    precise float dy = max(max(n.range.z - cam.y, cam.y - n.range.w), 0.0);
    precise float dz = max(max(z0 - cam.z, cam.z - (z0 + size)), 0.0);
    precise float limit = params.lod.y > 0.0 ? params.lod.y * n.error.x + params.lod.z * size : params.lod.x * size;
    precise float d2 = (dx * dx + dy * dy) + dz * dz;
    split = d2 < limit * limit;
  }
  if (split) {
    uint bit = bitOffset(d) + uint(gz) * uint(gridWidth(d)) + uint(gx);
    atomicOr(splitBits[bit >> 5], 1u << (bit & 31u));
    uint at = nextList == 0u ? atomicAdd(counters.lists.x, 4u) : atomicAdd(counters.lists.y, 4u);
    uint capacity = uint(params.flags.z);
    if (at + 4u > capacity) {
      atomicAdd(counters.lists.z, 4u);
      return;
    }
    for (uint k = 0u; k < 4u; ++k) {
      items[nextList * capacity + at + k] = uvec2(uint(gx * 2) + (k & 1u), uint(gz * 2) + (k >> 1u));
    }
    return;
  }
  uint leaf = atomicAdd(counters.draw.y, 1u);
  float t = params.lod.w;
  nodes[leaf].rect = vec4(x0, size, z0, n.range.x);
  nodes[leaf].tessOuter = vec4(t);
  nodes[leaf].tessInner = vec4(t, n.range.y, 0.0, 0.0);
  nodes[leaf].grid = ivec4(gx, d, gz, -1);
}

void sync() {
  memoryBarrierBuffer();
  barrier();
}

void main() {
  uint lid = gl_LocalInvocationID.x;
  uint capacity = uint(params.flags.z);
  uint roots = uint(params.grid.x * params.grid.y);
  for (uint i = lid; i < roots; i += gl_WorkGroupSize.x) {
    items[i] = uvec2(i % uint(params.grid.x), i / uint(params.grid.x));
  }
  if (lid == 0u) {
    counters.draw = uvec4(4u, 0u, 0u, 0u);
    counters.lists = uvec4(min(roots, capacity), 0u, 0u, 0u);
  }
  sync();
  uint list = 0u;
  for (int d = 0; d <= params.grid.z; ++d) {
    uint count = list == 0u ? counters.lists.x : counters.lists.y;
    sync();
    if (lid == 0u) {
      if (list == 0u) {
        counters.lists.y = 0u;
      } else {
        counters.lists.x = 0u;
      }
    }
    sync();
    for (uint i = lid; i < min(count, capacity); i += gl_WorkGroupSize.x) {
      visit(d, items[list * capacity + i], 1u - list);
    }
    sync();
    list = 1u - list;
  }
  // Edge levels: doubled where the same-depth square across the edge split (restriction makes it one finer).
  uint leaves = counters.draw.y;
  if (params.flags.y != 0) {
    const ivec2 dirs[4] = ivec2[4](ivec2(-1, 0), ivec2(0, -1), ivec2(1, 0), ivec2(0, 1));
    for (uint i = lid; i < leaves; i += gl_WorkGroupSize.x) {
      ivec4 g = nodes[i].grid;
      float t = params.lod.w;
      vec4 outer = vec4(t);
      uint flags = 0u;
      for (int e = 0; e < 4; ++e) {
        if (splitAt(g.y, g.x + dirs[e].x, g.z + dirs[e].y)) {
          outer[e] = 2.0 * t;
          flags |= 1u << uint(e);
        }
      }
      nodes[i].tessOuter = outer;
      nodes[i].tessInner.z = float(flags);
    }
  }
}
