#version 450
// Grass culling, bookkeeping between the passes (one invocation). Stage 0, after the tile pass: the blade
// pass's dispatch size from the visible tile count (capped at 65535 groups, which then loop) and the tiles
// that did not fit the list. Stage 1, after the blade pass: each instance count clamped to its list's
// capacity, so a full list draws what it holds (the dropped instances are counted).
#include "grass.glsl"

layout(local_size_x = 1) in;

layout(std430, binding = SYLVA_GRASS_COMMAND_BINDING) buffer Commands {
  uint commands[SYLVA_GRASS_COMMAND_UINTS];
};

uniform int uStage;

void main() {
  if (uStage == 0) {
    uint found = commands[SYLVA_GRASS_STATS_OFFSET + 6];
    uint kept = min(found, grass.lists.w);
    commands[SYLVA_GRASS_STATS_OFFSET + 5] = found - kept;
    commands[SYLVA_GRASS_DISPATCH_OFFSET] = min(kept, 65535u);
  } else {
    for (int k = 0; k < 3; ++k) {
      commands[k * 4 + 1] = min(commands[k * 4 + 1], grass.lists[k]);
    }
    commands[3 * 4 + 1] = min(commands[3 * 4 + 1], grass.simulated.x);
  }
}
