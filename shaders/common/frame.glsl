// The per-frame uniform block, from the layout shared with C++.
#pragma once
#include "../shared/Frame.h"

layout(std140, binding = SYLVA_FRAME_BINDING) uniform FrameBlock {
  FrameUniforms frame;
};
