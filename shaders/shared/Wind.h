// The wind field's parameters at one moment (std140, binding SYLVA_WIND_BINDING), evaluated by
// shaders/common/wind.glsl and by sylva::wind::windVelocity in C++ with the same operations.
#ifndef SYLVA_SHARED_WIND_H
#define SYLVA_SHARED_WIND_H

#include "Prelude.h"

SYLVA_GPU_BEGIN

#define SYLVA_WIND_BINDING 3

struct WindUniforms {
  vec4 flow;       // x, y: unit mean direction in world (x, z); z: mean speed in m/s; w: time in seconds
  vec4 gusts;      // x: gust strength (fraction of the mean speed added at a gust's peak); y: gust length along
                   // the wind, metres; z: gust width across it, metres; w: gust travel speed in m/s
  vec4 turbulence; // x: strength (fraction of the mean speed); y: eddy size, metres; z: rate in Hz; w: unused
  uvec4 seed;      // x: seed of the gust and turbulence patterns; y, z, w: unused
};
SYLVA_ASSERT_SIZE(WindUniforms, 64);

SYLVA_GPU_END

#endif
