#pragma once

#include <sylva/texsynth/Texture.hpp>

#include <cstdint>

namespace sylva::texsynth {

/**
 * Procedural bark: a deterministic size × size texture (16..4096) with 6 channels: brown colour in [0, 1]
 * and a tangent-space normal (texture frame) from a height field of vertical grooves (ridges along the rows,
 * wavering and of varying depth) plus fine value noise. The CI fallback when bark photos are absent; same
 * seed, same texels on every platform.
 */
Texture proceduralBark(int size, std::uint64_t seed);

} // namespace sylva::texsynth
