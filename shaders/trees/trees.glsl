// Shared declarations of the tree passes (docs/trees.md): uniforms, joint frames, instances, piece table.
#pragma once
#include "../shared/Trees.h"
#include "../common/hash.glsl"

layout(std140, binding = SYLVA_TREE_BINDING) uniform TreeBlock {
  TreeUniforms trees;
};

layout(std430, binding = SYLVA_TREE_JOINT_BINDING) readonly buffer Joints {
  JointFrame joints[];
};

layout(std430, binding = SYLVA_TREE_INSTANCE_BINDING) readonly buffer Instances {
  TreeInstanceGpu instances[];
};

layout(std430, binding = SYLVA_TREE_PIECE_BINDING) readonly buffer PieceTable {
  TreePieceGpu pieceTable[];
};

layout(std430, binding = SYLVA_TREE_CENTRE_BINDING) readonly buffer TreeCentres {
  vec4 treeCentres[]; // base (xyz, m), crown height (w, m)
};

/** Distance from `camera` to the centre of tree `tree`'s crown (half its height above the base), metres: the
 * distance of the far field's fade (cullInstances in C++ measures it the same way). */
float crownDistance(uint tree, vec3 camera) {
  vec4 c = treeCentres[tree];
  return distance(camera, c.xyz + vec3(0.0, 0.5 * c.w, 0.0));
}

// Per quad of every piece type: x tile class | rotation << 8, y four edge ids (sylva::trees::quadTileTable).
layout(std430, binding = SYLVA_TREE_QUAD_BINDING) readonly buffer QuadTable {
  uvec2 quadTiles[];
};

/** The quad table entry of quad `quad` of piece type `type`. */
uvec2 quadTileEntry(uint type, uint quad) {
  return quadTiles[trees.quadTable[type / 4u][type % 4u] + quad];
}

/** Tile coordinates of quad point uv for tile rotation r (tileCoord in sylva/trees/Bark.hpp). */
vec2 tileCoord(vec2 uv, uint r) {
  r &= 3u;
  if (r == 0u) {
    return uv;
  }
  if (r == 1u) {
    return vec2(uv.y, 1.0 - uv.x);
  }
  if (r == 2u) {
    return vec2(1.0 - uv.x, 1.0 - uv.y);
  }
  return vec2(1.0 - uv.y, uv.x);
}

/** instanceTileSeed and chooseTile of sylva/trees/Bark.hpp. */
uint instanceTileSeed(uint rootJoint) { return lowbias32(rootJoint * 0x9e3779b9u + 0x7f4a7c15u); }
uint chooseTile(uint seed, uint quad, uint first, uint count) {
  return first + lowbias32(seed ^ (quad * 0x85ebca6bu + 0x27d4eb2fu)) % count;
}

/** tileRepeat of sylva/trees/Bark.hpp: tiles along the grain of a quad (its table entry x) in an instance of
 * tile stretch `stretch` (SYLVA_TREE_INSTANCE_STRETCH), in the same integer arithmetic. */
uint tileRepeat(uint entry, uint stretch) {
  int ratio = int((entry >> 16) & 255u);
  int growth = int(entry >> 24);
  int scaled = ratio * 16 + (int(stretch) - 16) * growth + 128;
  return scaled <= 0 ? 1u : uint(clamp(scaled / 256, 1, SYLVA_TREE_MAX_TILE_REPEAT));
}

/** sideEdgeColour of sylva/trees/Bark.hpp: part `part` of an edge along the grain (rim edges: colour 0). */
uint sideEdgeColour(uint seed, uint edge, uint part, uint colours) {
  if (edge == 255u || colours <= 1u) {
    return 0u;
  }
  return lowbias32(seed ^ (edge * 0x9e3779b9u + 0x165667b1u + part * 0x68e31da4u)) % colours;
}

/** innerEdgeColour of sylva/trees/Bark.hpp: the edge between sub-tiles `sub` − 1 and `sub` of a quad. */
uint innerEdgeColour(uint seed, uint quad, uint sub, uint colours) {
  if (colours <= 1u) {
    return 0u;
  }
  return lowbias32(seed ^ (quad * 0x2c1b3c6du + sub * 0x297a2d39u + 0x1b873593u)) % colours;
}

/** edgeColour of sylva/trees/Bark.hpp: rim edges (id 255) have colour 0. */
uint edgeColour(uint seed, uint edge, uint colours) {
  if (edge == 255u || colours <= 1u) {
    return 0u;
  }
  return lowbias32(seed ^ (edge * 0x9e3779b9u + 0x165667b1u)) % colours;
}

/** barkTile of sylva/trees/Bark.hpp: the layer within a bark set of sub-tile `sub` of `repeat` of a quad
 * (class, rotation, edge ids). */
uint barkTile(uint rootJoint, uint quad, uint classRotation, uint edges, uint sub, uint repeat) {
  uint cls = min(classRotation & 255u, uint(SYLVA_TREE_MAX_TILE_CLASSES - 1));
  uint rotation = (classRotation >> 8) & 3u;
  uint seed = instanceTileSeed(rootJoint);
  uint colours = uint(trees.bark.w);
  uint block = 0u;
  uint weight = 1u;
  for (uint k = 0u; k < 4u; ++k) {
    uint e = (rotation + k) & 3u;
    uint colour;
    if (k == 0u && sub > 0u) {
      colour = innerEdgeColour(seed, quad, sub, colours);
    } else if (k == 2u && sub + 1u < repeat) {
      colour = innerEdgeColour(seed, quad, sub + 1u, colours);
    } else if ((k & 1u) == 1u) {
      bool flip = ((classRotation >> (10u + k / 2u)) & 1u) != 0u;
      colour = sideEdgeColour(seed, (edges >> (8u * e)) & 255u, flip ? repeat - 1u - sub : sub, colours);
    } else {
      colour = edgeColour(seed, (edges >> (8u * e)) & 255u, colours);
    }
    block += colour * weight;
    weight *= colours;
  }
  uint variants = max(trees.tileCount[cls], 1u);
  return chooseTile(seed, quad + 256u * sub, trees.tileFirst[cls] + block * variants, variants);
}

/** subTile of sylva/trees/Bark.hpp: the sub-tile of grain coordinate `along` (tile y × repeat). */
uint subTileOf(float along, uint repeat) { return min(uint(max(floor(along), 0.0)), max(repeat, 1u) - 1u); }

/** A point through a frame (three rows of a 3x4 matrix). */
vec3 framePoint(JointFrame f, vec3 p) {
  vec4 p1 = vec4(p, 1.0);
  return vec3(dot(f.x, p1), dot(f.y, p1), dot(f.z, p1));
}

/** A direction through a frame's linear part. */
vec3 frameVector(JointFrame f, vec3 v) {
  return vec3(dot(f.x.xyz, v), dot(f.y.xyz, v), dot(f.z.xyz, v));
}

/** Rotation of a rim frame by `steps` × 60° about +y (rimRotation in C++), applied to p. */
vec3 rimTurn(vec3 p, uint steps) {
  vec3 c = trees.corners[steps % 6u].xyz; // (cos, 0, sin) of 60°·steps
  return vec3(c.x * p.x - c.z * p.z, p.y, c.z * p.x + c.x * p.z);
}
