#pragma once

#include <sylva/gl/Program.hpp>
#include <sylva/shader/Preprocessor.hpp>

#include <string>
#include <vector>

namespace sylva::shader {

/** A program to build: stage files (stage from the extension: .vert .tesc .tese .geom .frag .comp) + defines.
 */
struct ProgramDesc {
  std::string label;
  std::vector<std::string> stages;
  Defines defines;
};

/** GL stage enum for a file name by extension; throws sylva::Error for unknown extensions. */
GLenum stageForPath(const std::string& path);

/** Preprocesses every stage and links them; errors name the file:line (see gl::Program). Needs a context. */
gl::Program compileProgram(const Library& library, const ProgramDesc& desc);

} // namespace sylva::shader
