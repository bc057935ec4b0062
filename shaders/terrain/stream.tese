#version 450 core
// Each vertex lands on a tile sample: (u, v) · P is a whole number for every level the control stage uses.
#include "stream.glsl"

#ifdef SYLVA_STREAM_POINTS
layout(quads, equal_spacing, ccw, point_mode) in;
#else
layout(quads, equal_spacing, ccw) in;
#endif
patch in int tcTile;
patch in ivec2 tcPatch;

invariant gl_Position;
out vec3 teWorldPos; // relative to the render origin (x, z), metres; y absolute
out vec3 teNormal;
out float teAbsent;
flat out int teLevel;

void main() {
  int level = stream.shape.y;
  ivec4 key = tiles[tcTile].key;
  ivec2 local = tcPatch * level + ivec2(round(gl_TessCoord.xy * float(level)));
  int layer = key.w;
  float h = tileHeight(layer, local);
  // Level-0 index of the sample, relative to the origin: exact integers, the same on both sides of an edge.
  ivec2 index = ((key.xy * stream.shape.x + local) << key.z) - stream.origin.xy;
  vec2 xz = vec2(index) * stream.spacing.xy;
  teAbsent = isnan(h) ? 1.0 : 0.0;
  h = isnan(h) ? 0.0 : h;
  // Normal from central differences of the level's samples, across the tile's border into the same-level
  // neighbour when it is on the GPU (both tiles then give a shared vertex the same normal: no shading seam);
  // one-sided beside a missing neighbour or absent samples.
  float step = float(1 << key.z);
  float hw = tileHeightAcross(tcTile, local - ivec2(1, 0));
  float he = tileHeightAcross(tcTile, local + ivec2(1, 0));
  float hn = tileHeightAcross(tcTile, local - ivec2(0, 1));
  float hs = tileHeightAcross(tcTile, local + ivec2(0, 1));
  bool west = !isnan(hw);
  bool east = !isnan(he);
  bool north = !isnan(hn);
  bool south = !isnan(hs);
  float spanX = (float(west) + float(east)) * step * stream.spacing.x;
  float spanZ = (float(north) + float(south)) * step * stream.spacing.y;
  float dhdx = spanX > 0.0 ? ((east ? he : h) - (west ? hw : h)) / spanX : 0.0;
  float dhdz = spanZ > 0.0 ? ((south ? hs : h) - (north ? hn : h)) / spanZ : 0.0;
  teNormal = normalize(vec3(-dhdx, 1.0, -dhdz));
  teWorldPos = vec3(xz.x, h, xz.y);
  teLevel = key.z;
  gl_Position = frame.viewProj * vec4(teWorldPos, 1.0);
}
