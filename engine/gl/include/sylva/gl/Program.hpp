#pragma once

#include <sylva/gl/Object.hpp>

#include <glm/glm.hpp>

#include <string>
#include <unordered_map>
#include <vector>

namespace sylva::gl {

/** One shader stage's final source text, plus names that translate `#line N M` source numbers M in logs. */
struct StageSource {
  GLenum stage = GL_VERTEX_SHADER; ///< GL_VERTEX_SHADER, GL_COMPUTE_SHADER, …
  std::string source;              ///< the complete GLSL text
  /** files[M] is the file name for `#line N M`; file 0 is the stage's main file. */
  std::vector<std::string> files;
};

/**
 * Linked program object. Construction compiles and links all stages and throws sylva::Error whose message
 * names the failing file:line (translated through StageSource::files) and the driver's log. Move-only.
 */
class Program : public Object<detail::deleteProgram> {
public:
  /** An empty wrapper (no GL object; no context needed), to be assigned later. */
  explicit Program(NoCreateT) {}
  /**
   * Compiles and links `stages`; `label` names the program in errors and GL debug labels. `feedbackVaryings`
   * (outputs of the last vertex-processing stage, e.g. "gl_Position") are captured by transform feedback,
   * interleaved in the order given.
   */
  Program(const std::vector<StageSource>& stages, const std::string& label,
          const std::vector<std::string>& feedbackVaryings = {});

  /** Makes this the current program (glUseProgram). */
  void use() const;
  /** Uniform location by name, cached; -1 when the uniform is absent or optimised out (setters ignore -1). */
  GLint uniformLocation(const std::string& name) const;
  ///@{
  /** Sets uniform `name` of this program (glProgramUniform*: no need to use() it); nothing when absent. */
  void setUniform(const std::string& name, int value) const;
  void setUniform(const std::string& name, unsigned value) const;
  void setUniform(const std::string& name, float value) const;
  void setUniform(const std::string& name, const glm::vec2& value) const;
  void setUniform(const std::string& name, const glm::vec3& value) const;
  void setUniform(const std::string& name, const glm::vec4& value) const;
  void setUniform(const std::string& name, const glm::mat4& value) const;
  ///@}
  /** Work-group size declared by a compute shader (local_size_x/y/z). */
  glm::ivec3 computeWorkGroupSize() const;
  /** The label given at construction. */
  const std::string& label() const { return mLabel; }

private:
  std::string mLabel;
  mutable std::unordered_map<std::string, GLint> mLocations;
};

/** Translates `0(12)`-style or `0:12:`-style driver log positions into `file:line` using `files`. */
std::string translateShaderLog(const std::string& log, const std::vector<std::string>& files);

} // namespace sylva::gl
