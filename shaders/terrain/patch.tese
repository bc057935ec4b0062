#version 450 core
// Places tessellated vertices on an integer lattice so that neighbouring patches produce bit-identical edge
// vertices: every corner and edge vertex is an exact integer count of the finest edge step δ = S_maxDepth / T,
// times δ. A coarse edge (size 2S, level 2L), the finer edges beside it and the corners they share compute the
// same integer and the same δ, hence the same float, the same height and, with `invariant gl_Position`, the
// same clip position: no cracks, not even sub-pixel ones, for every base level T.
#include "terrain.glsl"

#ifdef SYLVA_TERRAIN_POINTS
layout(quads, equal_spacing, ccw, point_mode) in; // TerrainDrawOptions::vertexPoints: one point per vertex
#else
layout(quads, equal_spacing, ccw) in;
#endif
patch in vec4 tcRect;  // x, z: min corner; y: size; w: minY (metres)
patch in vec4 tcOuter; // outer levels, PatchEdge order
patch in ivec4 tcGrid; // grid x, depth, grid z, skirt edge (-1: surface)

invariant gl_Position;
out vec3 teWorldPos;
flat out int teLevel;
flat out int teSkirt;

// Coordinate along one axis of a vertex at parameter t (0..1) on a node at grid index g and depth `depth` of
// size S. Corners and edge vertices are shared with neighbours: they are placed as an exact integer count m of
// the finest edge step δ = S_maxDepth / T (every edge level is T or 2T, so every edge vertex of every patch is
// a multiple of δ), x = float(m)·δ, and both sides of an edge compute the same m, hence the same float. Interior
// vertices are shared with no other patch and are placed directly (the tessellator may round an inner level
// of 1 up to 2, so their parameters are not on the inner-level lattice).
float axisCoord(int g, int depth, float t, float size, bool onEdge, float edgeLevel) {
  int maxDepth = int(uMorphLod.y);
  int tess = int(uMorphLod.z + 0.5);
  float step = ldexp(uMorphLod.x, -maxDepth) / float(tess);
  int perNode = tess << (maxDepth - depth); // δ steps per node edge
  if (t == 0.0) {
    return float(g * perNode) * step;
  }
  if (t == 1.0) {
    return float((g + 1) * perNode) * step;
  }
  if (!onEdge) {
    return (float(g) + t) * size;
  }
  int l = int(edgeLevel + 0.5);
  int k = clamp(int(floor(t * edgeLevel + 0.5)), 1, l - 1);
  return float(g * perNode + k * (perNode / l)) * step;
}

void main() {
  float size = tcRect.y;
  ivec2 g = tcGrid.xz;
  vec2 uv = gl_TessCoord.xy;
  vec2 xz;
  float y;
  if (tcGrid.w < 0) {
    // u along +x, v along +z. A vertex on the north/south edge (v = 0/1) takes that edge's level for x; one on
    // the west/east edge (u = 0/1) takes that edge's level for z.
    bool northSouth = uv.y == 0.0 || uv.y == 1.0;
    bool westEast = uv.x == 0.0 || uv.x == 1.0;
    xz.x = axisCoord(g.x, tcGrid.y, uv.x, size, northSouth, uv.y == 0.0 ? tcOuter[1] : tcOuter[3]);
    xz.y = axisCoord(g.y, tcGrid.y, uv.y, size, westEast, uv.x == 0.0 ? tcOuter[0] : tcOuter[2]);
  } else {
    // Skirt under edge e: top vertices are that edge's surface vertices, bottom ones hang below the node.
    int e = tcGrid.w;
    float level = tcOuter[e];
    float along = axisCoord(e == 0 || e == 2 ? g.y : g.x, tcGrid.y, uv.x, size, true, level);
    if (e == 0 || e == 2) {
      xz = vec2(axisCoord(g.x, tcGrid.y, e == 2 ? 1.0 : 0.0, size, true, level), along);
    } else {
      xz = vec2(along, axisCoord(g.y, tcGrid.y, e == 3 ? 1.0 : 0.0, size, true, level));
    }
  }
  // One call site for surface and skirt tops: the (morphed) height is a function of xz alone.
  y = terrainMorphedHeight(xz);
  if (tcGrid.w >= 0 && uv.y != 0.0) {
    y = tcRect.w - terrain.spacing.w;
  }
  teWorldPos = vec3(xz.x, y, xz.y);
  teLevel = tcGrid.y;
  teSkirt = tcGrid.w >= 0 ? 1 : 0;
  gl_Position = frame.viewProj * vec4(teWorldPos, 1.0);
}
