// Shared between C++ and GLSL: lets one struct definition describe a GPU layout for both languages.
// Rules for shared structs: only vec4/ivec4/uvec4/mat4 and 4-aligned groups of 32-bit scalars, no bool, explicit
// padding members; every struct has a SYLVA_ASSERT_SIZE so a layout change breaks the C++ build, not the frame.
#ifndef SYLVA_SHARED_PRELUDE_H
#define SYLVA_SHARED_PRELUDE_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/glm.hpp>
#define SYLVA_GPU_BEGIN namespace sylva::gpu {
#define SYLVA_GPU_END }
#define SYLVA_ASSERT_SIZE(type, bytes) static_assert(sizeof(type) == (bytes), #type " layout changed")
namespace sylva::gpu {
using vec2 = glm::vec2;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = std::uint32_t;
} // namespace sylva::gpu
#else
#define SYLVA_GPU_BEGIN
#define SYLVA_GPU_END
// GLSL has no static_assert; the size is kept as a constant so both languages read the same line.
#define SYLVA_ASSERT_SIZE(type, bytes) const int type##SizeBytes = bytes
#endif

#endif
