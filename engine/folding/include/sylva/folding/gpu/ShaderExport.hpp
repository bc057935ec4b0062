#pragma once

#include <sylva/folding/Project.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/shader/Library.hpp>

#include <filesystem>
#include <string>

namespace sylva::folding::gpu {

/**
 * What saveTextures writes for `textures` under `project`'s encoding: jumpMax = max(textures.jumpMax(), 1e-6)
 * pixels, K = textures.jump.size() layers, fold layers when textures.fold is non-empty. Pure CPU.
 */
EncodedInfo encodedInfo(const Project& project, const Textures& textures);

/**
 * The text of the exported `folding.glsl`: a self-contained GLSL 4.50 snippet (no `#version`; paste it, or
 * include it, after the host shader's `#version` line) with the evaluation functions of folding/fold.glsl,
 * the project's profiles and breakpoints as constants, the uniforms it reads (folding_color, folding_init,
 * folding_jump<k>, folding_fold<k>, folding_phase[]) and
 *   vec4 foldingSample(ivec2 texel)   // frame colour of atlas texel (row 0 = first row of the files), [0, 1]
 *   vec4 foldingSampleUv(vec2 uv)     // the same at the nearest texel of uv ∈ [0, 1]² (v = 0: first row)
 * decoding the textures exactly as saveTextures encodes them (docs/folding.md "Encoding"). Throws
 * sylva::Error when `info` disagrees with the project (layer count, limits) or the library lacks
 * folding/fold.glsl.
 */
std::string exportedShaderSource(const shader::Library& library, const Project& project,
                                 const EncodedInfo& info);

/**
 * The same evaluation for WebGL 2 (GLSL ES 3.00, no `#version` or precision lines: the host adds them): no
 * binding qualifiers, and the data textures are RGBA16UI (`usampler2D`, the 16-bit integers as stored)
 * instead of RGBA16 UNORM, which WebGL lacks. Needs the rgba16 encoding.
 */
std::string webShaderSource(const shader::Library& library, const Project& project, const EncodedInfo& info);

/**
 * Writes one self-contained HTML file that plays the project's canvas image in a browser with WebGL 2: the
 * colour atlas and the 16-bit data textures embedded (base64 of the raw texels), webShaderSource, a
 * play/pause button, a time slider and speed control. With `?t=SECONDS&dump=1` in the URL it draws that one
 * frame and writes its pixels (hex RGBA rows, top first) into `<pre id="out">`, for tests. Atomic.
 */
void writeWebPreview(const std::filesystem::path& path, const shader::Library& library,
                     const Project& project, const Textures& textures);

/**
 * Writes `folding.glsl` (exportedShaderSource) and `README.md` (encoding, uniform list, how to bind, the
 * per-frame phase formula) into `dir`, each atomically; creates `dir`. Made for the textures as saveTextures
 * writes them next to it (RGBA16 PNGs as GL_RGBA16 UNORM textures, or EXR as float textures).
 */
void exportShader(const std::filesystem::path& dir, const shader::Library& library, const Project& project,
                  const EncodedInfo& info);

} // namespace sylva::folding::gpu
