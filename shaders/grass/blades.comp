#version 450
// Grass culling, pass 2: one work group per visible tile, its invocations stepping through the tile's range
// of the patch. Each blade kept by the density is tested against the frustum (sphere around its upright
// extent), the draw distance and, far away, its orientation; survivors are appended to the instance list of
// their level of detail (two lists inside a cross-fade band). Tiles near the camera go on into the near
// layers' tuft blades. The CPU reference is cullField (Cull.cpp).
#include "grass.glsl"
#include "../shared/GrassSim.h"

layout(local_size_x = SYLVA_GRASS_BLADE_GROUP) in;

layout(std430, binding = SYLVA_GRASS_VISIBLE_BINDING) readonly buffer VisibleTiles {
  ivec2 visibleTiles[];
};
layout(std430, binding = SYLVA_GRASS_INSTANCE_BINDING) writeonly buffer Instances {
  uvec4 instances[];
};
layout(std430, binding = SYLVA_GRASS_COMMAND_BINDING) buffer Commands {
  uint commands[SYLVA_GRASS_COMMAND_UINTS];
};

// Simulated tiles (tile x, z, used, release ramp bits), options.x of them; none without simulation.
layout(std430, binding = SYLVA_GRASS_SIM_SLOT_BINDING) readonly buffer SimSlots {
  ivec4 simSlots[];
};

shared uint groupCounts[4]; // blades, culled by frustum, distance, orientation
shared int groupSlot;       // the tile's pool slot, or -1

void append(int lod, int fade, float amount, vec3 root, uint index) {
  uint slot = atomicAdd(commands[lod * 4 + 1], 1u);
  if (slot < grass.lists[lod]) {
    uint base = lod == 0 ? 0u : lod == 1 ? grass.lists.x : grass.lists.x + grass.lists.y;
    instances[base + slot] =
        uvec4(floatBitsToUint(root), grassPackInfo(index, lod, fade, amount));
  } else {
    atomicAdd(commands[SYLVA_GRASS_STATS_OFFSET + 4], 1u);
  }
}

// A blade of a simulated tile: one instance drawn from the pool's knots (16 of them: level 0). `marker` says
// whether it is the pool blade itself or a tuft blade following it (then `pool` carries its layer too).
void appendSimulated(uint marker, uint pool, uint index, int fade, float amount, float release) {
  uint slot = atomicAdd(commands[3 * 4 + 1], 1u);
  if (slot >= grass.simulated.x) {
    atomicAdd(commands[SYLVA_GRASS_STATS_OFFSET + 4], 1u);
    return;
  }
  uint base = grass.lists.x + grass.lists.y + grass.lists.z;
  instances[base + slot] = uvec4(marker, pool, grassPackInfo(index, 0, fade, amount), floatBitsToUint(release));
}

// How far near layer `layer` is drawn (nearLayerReach, Cull.cpp).
float tuftReach(int layer, int layers) {
  return grass.near.x * sqrt(float(layers - layer) / float(layers - 1));
}

// lodInstances (Cull.cpp): one instance, or two inside a cross-fade band.
void appendInstances(float distance, vec3 root, uint index) {
  float half_ = 0.5 * grass.lod.z;
  for (int k = 0; k < 2; ++k) {
    float start = grass.lod[k] - half_;
    if (grass.lod.z > 0.0 && distance >= start && distance < start + grass.lod.z) {
      float amount = (distance - start) / grass.lod.z;
      append(k, 1, amount, root, index);
      append(k + 1, 2, amount, root, index);
      return;
    }
  }
  int lod = distance < grass.lod.x ? 0 : distance < grass.lod.y ? 1 : 2;
  float farStart = grass.eye.w - grass.lod.w;
  if (grass.lod.w > 0.0 && distance >= farStart) {
    append(lod, 1, min((distance - farStart) / grass.lod.w, 1.0), root, index);
    return;
  }
  append(lod, 0, 0.0, root, index);
}

void main() {
  if (gl_LocalInvocationIndex < 4u) {
    groupCounts[gl_LocalInvocationIndex] = 0u;
  }
  barrier();
  // The dispatch is capped at 65535 groups: groups step through the visible tiles.
  uint visible = min(commands[SYLVA_GRASS_STATS_OFFSET + 6], grass.lists.w);
  for (uint t = gl_WorkGroupID.x; t < visible; t += gl_NumWorkGroups.x) {
  ivec2 tile = visibleTiles[t];
  if (gl_LocalInvocationIndex == 0u) {
    groupSlot = -1;
    for (uint s = 0u; s < grass.options.x; ++s) {
      if (simSlots[s].z != 0 && simSlots[s].xy == tile) {
        groupSlot = int(s);
        break;
      }
    }
  }
  barrier();
  int simSlot = groupSlot;
  uint n = uint(grass.tiles.w);
  uint start = grassTileStart(tile, n);
  vec2 corner = grass.field.xy + vec2(tile) * grass.orient.w;
  int perTile = min(grass.tiles.z, grass.tiles.w);
  // Tiles within the near layers' reach (horizontally) also walk their tuft blades (forEachTuftBlade).
  int layers = int(grass.near.y);
  vec2 closest = clamp(grass.eye.xz, corner, corner + vec2(grass.orient.w));
  int count = layers > 1 && length(closest - grass.eye.xz) < grass.near.x ? perTile * layers : perTile;
  for (int j = int(gl_LocalInvocationIndex); j < count; j += SYLVA_GRASS_BLADE_GROUP) {
    uint index = (start + uint(j)) % n;
    GrassBlade b = patchBlades[index];
    vec2 xz = corner + b.placement.xy;
    bool tuft = j >= perTile;
    int guide = j % perTile;
    float reach = 0.0;
    if (tuft) {
      // Beside field blade `guide`, which must itself be drawn.
      reach = tuftReach(j / perTile, layers);
      vec2 at = corner + patchBlades[(start + uint(guide)) % n].placement.xy;
      xz = at + (b.placement.xy / grass.orient.w - 0.5) * (2.0 * grass.near.z);
      if (at.x < 0.0 || at.y < 0.0 || at.x > grass.field.z || at.y > grass.field.w ||
          xz.x < 0.0 || xz.y < 0.0 || xz.x > grass.field.z || xz.y > grass.field.w ||
          length(xz - grass.eye.xz) >= reach) {
        continue;
      }
      bool guideOk;
      grassTerrainHeight(at, guideOk);
      if (!guideOk || (float(guide) + 0.5) / float(grass.tiles.z) >= grassDensity(at)) {
        continue;
      }
    } else if (xz.x < 0.0 || xz.y < 0.0 || xz.x > grass.field.z || xz.y > grass.field.w) {
      continue;
    }
    bool ok;
    float height = grassTerrainHeight(xz, ok);
    if (!ok || (!tuft && (float(j) + 0.5) / float(grass.tiles.z) >= grassDensity(xz))) {
      continue;
    }
    vec3 root = vec3(xz.x, height, xz.y);
    if (tuft && length(root - grass.eye.xyz) >= reach) {
      continue;
    }
    float bladeHeight = bladeTypes[min(b.info.x, grass.options.z - 1u)].size.x * b.placement.w;
    vec3 centre = root + vec3(0.0, 0.5 * bladeHeight, 0.0);
    bool inside = true;
    for (int i = 0; i < 6; ++i) {
      if (dot(grass.planes[i].xyz, centre) + grass.planes[i].w < -0.5 * bladeHeight) {
        inside = false;
      }
    }
    if (!inside) {
      atomicAdd(groupCounts[1], 1u);
      continue;
    }
    float distance = length(root - grass.eye.xyz);
    if (distance > grass.eye.w) {
      atomicAdd(groupCounts[2], 1u);
      continue;
    }
    if (distance > grass.orient.x) {
      vec2 face = vec2(sin(b.placement.z), cos(b.placement.z));
      vec2 view = root.xz - grass.eye.xz;
      float len = length(view);
      if (len > 1e-6 && abs(dot(face, view / len)) < grass.orient.y) {
        atomicAdd(groupCounts[3], 1u);
        continue;
      }
    }
    atomicAdd(groupCounts[0], 1u);
    if (tuft) {
      // tuftFade (Cull.cpp): dithered out over the last quarter of the layer's reach.
      atomicAdd(commands[SYLVA_GRASS_STATS_OFFSET + 7], 1u);
      float fadeStart = 0.75 * reach;
      int fade = distance >= fadeStart ? 1 : 0;
      float amount = fade == 1 ? min((distance - fadeStart) / (reach - fadeStart), 1.0) : 0.0;
      if (simSlot >= 0) {
        uint pool = (uint(simSlot) * grass.options.w + uint(guide)) | (uint(j / perTile) << 24);
        appendSimulated(SYLVA_GRASS_TUFT_SIMULATED, pool, index, fade, amount, intBitsToFloat(simSlots[simSlot].w));
      } else {
        append(0, fade, amount, root, index);
      }
    } else if (simSlot >= 0) {
      float farStart = grass.eye.w - grass.lod.w;
      bool fading = grass.lod.w > 0.0 && distance >= farStart;
      float amount = fading ? min((distance - farStart) / grass.lod.w, 1.0) : 0.0;
      appendSimulated(SYLVA_GRASS_SIMULATED, uint(simSlot) * grass.options.w + uint(j), index, fading ? 1 : 0, amount,
                      intBitsToFloat(simSlots[simSlot].w));
    } else {
      appendInstances(distance, root, index);
    }
  }
  barrier();
  }
  barrier();
  if (gl_LocalInvocationIndex < 4u && groupCounts[gl_LocalInvocationIndex] > 0u) {
    atomicAdd(commands[SYLVA_GRASS_STATS_OFFSET + gl_LocalInvocationIndex], groupCounts[gl_LocalInvocationIndex]);
  }
}
