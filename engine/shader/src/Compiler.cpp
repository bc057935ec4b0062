#include <sylva/shader/Compiler.hpp>

#include <sylva/core/Error.hpp>

namespace sylva::shader {

GLenum stageForPath(const std::string& path) {
  const auto dot = path.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
  if (ext == ".vert") {
    return GL_VERTEX_SHADER;
  }
  if (ext == ".tesc") {
    return GL_TESS_CONTROL_SHADER;
  }
  if (ext == ".tese") {
    return GL_TESS_EVALUATION_SHADER;
  }
  if (ext == ".geom") {
    return GL_GEOMETRY_SHADER;
  }
  if (ext == ".frag") {
    return GL_FRAGMENT_SHADER;
  }
  if (ext == ".comp") {
    return GL_COMPUTE_SHADER;
  }
  fail("shader '{}': unknown stage extension '{}'", path, ext);
}

gl::Program compileProgram(const Library& library, const ProgramDesc& desc) {
  std::vector<gl::StageSource> stages;
  for (const std::string& path : desc.stages) {
    Preprocessed pre = preprocess(library, path, desc.defines);
    stages.push_back({stageForPath(path), std::move(pre.source), std::move(pre.files)});
  }
  return gl::Program(stages, desc.label.empty() ? desc.stages.front() : desc.label, desc.feedbackVaryings);
}

} // namespace sylva::shader
