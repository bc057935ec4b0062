#pragma once

#include <sylva/texsynth/Texture.hpp>

#include <cstdint>
#include <string>

namespace sylva::texsynth {

/**
 * Procedural bark: a deterministic size × size texture (16..4096) with 6 channels: brown colour in [0, 1]
 * and a tangent-space normal (texture frame) from a height field of vertical grooves (ridges along the rows,
 * wavering and of varying depth) plus fine value noise. The CI fallback when bark photos are absent; same
 * seed, same texels on every platform.
 */
Texture proceduralBark(int size, std::uint64_t seed);

/**
 * The source texture a command names: "procedural" is proceduralBark(1024, 1) (a `normalPath` with it is an
 * error: it has its own normals), anything else a photo and its optional normal map (loadPhotoTexture).
 */
Texture loadSourceTexture(const std::string& colourPath, const std::string& normalPath);

} // namespace sylva::texsynth
