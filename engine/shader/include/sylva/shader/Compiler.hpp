#pragma once

#include <sylva/gl/Program.hpp>
#include <sylva/shader/Preprocessor.hpp>

#include <string>
#include <vector>

namespace sylva::shader {

/** A program to build: stage files (stage from the extension: .vert .tesc .tese .geom .frag .comp) + defines.
 */
struct ProgramDesc {
  std::string label;               ///< name in errors and in GL debug labels
  std::vector<std::string> stages; ///< library paths of the stage files, e.g. "terrain/terrain.vert"
  Defines defines;                 ///< emitted after `#version` in every stage
  /** Outputs captured by transform feedback, interleaved (see gl::Program); empty: none. */
  std::vector<std::string> feedbackVaryings;
};

/** GL stage enum for a file name by extension; throws sylva::Error for unknown extensions. */
GLenum stageForPath(const std::string& path);

/** Preprocesses every stage and links them; errors name the file:line (see gl::Program). Needs a context. */
gl::Program compileProgram(const Library& library, const ProgramDesc& desc);

} // namespace sylva::shader
