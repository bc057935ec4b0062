// Uniforms of the built-in demo scene (std140, binding SYLVA_DEMO_BINDING).
#ifndef SYLVA_SHARED_DEMO_H
#define SYLVA_SHARED_DEMO_H

#include "Prelude.h"

SYLVA_GPU_BEGIN

#define SYLVA_DEMO_BINDING 1
#define SYLVA_DEMO_GROUP_SIZE 8

struct DemoUniforms {
  vec4 grid;   // x: patches per side; y: world size in metres; z: height scale in metres; w: base tess level
  vec4 wave;   // x: time in seconds; y: ripple frequency per metre; z, w: ripple centre x, z in metres
  ivec4 field; // x, y: height texture size in texels; z, w: padding
};
SYLVA_ASSERT_SIZE(DemoUniforms, 48);

SYLVA_GPU_END

#endif
