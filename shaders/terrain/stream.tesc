#version 450 core
// Level P everywhere, P / 2 on a tile-border edge whose neighbour tile is one level coarser: that edge then
// keeps the even samples only, which are the coarser tile's samples there (decimation), so the two meet exactly.
#include "stream.glsl"

layout(vertices = 4) out;
flat in int vTile[];
flat in ivec2 vPatch[];
patch out int tcTile;
patch out ivec2 tcPatch;

void main() {
  gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;
  if (gl_InvocationID == 0) {
    int tile = vTile[0];
    ivec2 p = vPatch[0];
    int last = stream.shape.z - 1;
    int coarser = tiles[tile].flags.x;
    float level = float(stream.shape.y);
    float half_ = max(level * 0.5, 1.0);
    // PatchEdge order: west (u = 0), north (v = 0), east (u = 1), south (v = 1).
    gl_TessLevelOuter[0] = (p.x == 0 && (coarser & 1) != 0) ? half_ : level;
    gl_TessLevelOuter[1] = (p.y == 0 && (coarser & 2) != 0) ? half_ : level;
    gl_TessLevelOuter[2] = (p.x == last && (coarser & 4) != 0) ? half_ : level;
    gl_TessLevelOuter[3] = (p.y == last && (coarser & 8) != 0) ? half_ : level;
    gl_TessLevelInner[0] = level;
    gl_TessLevelInner[1] = level;
    tcTile = tile;
    tcPatch = p;
  }
}
