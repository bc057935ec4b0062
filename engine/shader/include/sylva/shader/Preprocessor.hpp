#pragma once

#include <sylva/shader/Library.hpp>

#include <string>
#include <utility>
#include <vector>

namespace sylva::shader {

/** Preprocessor defines: (name, value) pairs, emitted as `#define name value` after `#version`. */
using Defines = std::vector<std::pair<std::string, std::string>>;

/** A preprocessed shader: one source string whose `#line N M` directives refer to files[M]. */
struct Preprocessed {
  std::string source;             ///< the expanded GLSL, ready for glShaderSource
  std::vector<std::string> files; ///< library paths by the file index M of its `#line N M` directives
};

/**
 * Expands `#include "path"` recursively (path relative to the including file's directory, then to the library
 * root), honours `#pragma once`, inserts `defines` right after the `#version` line, and emits `#line N M`
 * directives so driver messages point at the right file and line (GLSL's `#line` takes a source-string number
 * M; files[M] names it). `#include <...>` lines are left untouched: they only appear in the shared C++/GLSL
 * headers inside `#ifdef __cplusplus`, which the GLSL compiler skips. Does not rely on
 * ARB_shading_language_include. Throws sylva::Error for a missing file, a missing include (naming the
 * including file:line), include cycles, or a file without `#version` first.
 */
Preprocessed preprocess(const Library& library, const std::string& path, const Defines& defines = {});

} // namespace sylva::shader
