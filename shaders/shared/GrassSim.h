// GPU layouts of the grass simulation (docs/grass-simulation.md), shared by C++ and GLSL.
#ifndef SYLVA_SHARED_GRASS_SIM_H
#define SYLVA_SHARED_GRASS_SIM_H

#include "Prelude.h"
#include "Wind.h"

SYLVA_GPU_BEGIN

#define SYLVA_GRASS_SIM_BINDING 15          // uniform block GrassSimUniforms
#define SYLVA_GRASS_SIM_POSITION_BINDING 16 // storage: vec4 knots[] (pool blade-major, 16 per blade)
#define SYLVA_GRASS_SIM_PREVIOUS_BINDING 17 // storage: vec4 previous knots[]
#define SYLVA_GRASS_SIM_BLADE_BINDING 18    // storage: GrassSimBlade[] (per pool blade)
#define SYLVA_GRASS_SIM_WORK_BINDING 19     // storage: uint used slots[] this step
#define SYLVA_GRASS_SIM_COLLIDER_BINDING 20 // storage: GrassCollider[] (bodies near the used slots)
#define SYLVA_GRASS_SIM_RANGE_BINDING 22    // storage: uvec4 ranges[slot] (x: first collider, y: count)
#define SYLVA_GRASS_SIM_SLOT_BINDING 21     // storage: ivec4 slots[] (tile x, z, used, release bits)
#define SYLVA_GRASS_SIM_KNOTS 16
#define SYLVA_GRASS_SIM_UNUSED 0xffffffffu

/** One pool blade: which patch blade it is, where it stands, how trampled it is. */
struct GrassSimBlade {
  vec4 root;   // xyz: root (world metres); w: trample 0..1
  uvec4 info;  // x: patch index (SYLVA_GRASS_SIM_UNUSED: no blade); y, z, w: unused
};
SYLVA_ASSERT_SIZE(GrassSimBlade, 32);

/** A body for the blades: capsule a–b (sphere when a == b). */
struct GrassCollider {
  vec4 a; // xyz: end a (world metres); w: radius (m)
  vec4 b; // xyz: end b; w: mass (kg)
};
SYLVA_ASSERT_SIZE(GrassCollider, 32);

/** One solver step's constants (SolverConstants in C++: computed once, so both sides use the same floats). */
struct GrassSimUniforms {
  vec4 step;     // x: Δt (s); y: velocity kept per step exp(−d·Δt·60); z: gravity·Δt² (m); w: largest move per step (m)
  vec4 shape;    // x: global stiffness; y: knots below this index get global shape; z: local share ½·min(s', 0.95);
                 // w: wind drag
  vec4 trample;  // x: trampling mass (kg); y: softening; z: recovery per step (Δt / recovery time); w: unused
  ivec4 counts;  // x: used slots this step; y: blades per tile; z: local passes; w: length passes
  WindUniforms wind;
};
SYLVA_ASSERT_SIZE(GrassSimUniforms, 128);

SYLVA_GPU_END

#endif
