#include <sylva/gl/Program.hpp>

#include <sylva/core/Error.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <cctype>

namespace sylva::gl {

namespace {

const char* stageName(GLenum stage) {
  switch (stage) {
  case GL_VERTEX_SHADER:
    return "vertex";
  case GL_TESS_CONTROL_SHADER:
    return "tessellation control";
  case GL_TESS_EVALUATION_SHADER:
    return "tessellation evaluation";
  case GL_GEOMETRY_SHADER:
    return "geometry";
  case GL_FRAGMENT_SHADER:
    return "fragment";
  case GL_COMPUTE_SHADER:
    return "compute";
  default:
    return "unknown";
  }
}

std::string firstLines(const std::string& text, int count) {
  std::string out;
  int lines = 0;
  for (char c : text) {
    if (c == '\n') {
      if (++lines == count) {
        break;
      }
      out += " | ";
    } else if (c != '\r') {
      out += c;
    }
  }
  return out;
}

/** Deletes shader objects when linking is done or failed. */
struct ShaderSet {
  std::vector<GLuint> ids;
  ~ShaderSet() {
    for (GLuint id : ids) {
      glDeleteShader(id);
    }
  }
};

} // namespace

std::string translateShaderLog(const std::string& log, const std::vector<std::string>& files) {
  auto name = [&](std::size_t index) {
    return index < files.size() ? files[index] : "source " + std::to_string(index);
  };
  // Reads decimal digits at `i`; returns false (leaving `i`) when there are none.
  auto digits = [&](std::size_t& i, std::size_t& value) {
    std::size_t j = i;
    value = 0;
    while (j < log.size() && std::isdigit(static_cast<unsigned char>(log[j])) != 0) {
      value = value * 10 + static_cast<std::size_t>(log[j] - '0');
      ++j;
    }
    if (j == i) {
      return false;
    }
    i = j;
    return true;
  };
  // Mesa writes "0:12(3): error: ..."; NVIDIA writes "0(12) : error C1008: ..." at the start of a line.
  std::string out;
  std::size_t i = 0;
  while (i < log.size()) {
    const bool lineStart = i == 0 || log[i - 1] == '\n';
    std::size_t j = i;
    std::size_t source = 0;
    std::size_t line = 0;
    std::size_t column = 0;
    if (digits(j, source) && j < log.size()) {
      std::size_t k = j;
      if (log[k] == ':' && digits(++k, line) && k < log.size() && log[k] == '(' && digits(++k, column) &&
          k < log.size() && log[k] == ')') {
        out += name(source) + ":" + std::to_string(line) + "(" + std::to_string(column) + ")";
        i = k + 1;
        continue;
      }
      k = j;
      if (lineStart && log[k] == '(' && digits(++k, line) && k < log.size() && log[k] == ')') {
        out += name(source) + ":" + std::to_string(line);
        i = k + 1;
        continue;
      }
    }
    out += log[i++];
  }
  return out;
}

Program::Program(const std::vector<StageSource>& stages, const std::string& label,
                 const std::vector<std::string>& feedbackVaryings)
    : mLabel(label) {
  if (stages.empty()) {
    fail("{}: program has no stages", label);
  }
  ShaderSet shaders;
  for (const StageSource& stage : stages) {
    const GLuint shader = glCreateShader(stage.stage);
    shaders.ids.push_back(shader);
    const char* text = stage.source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
      GLint length = 0;
      glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
      std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
      glGetShaderInfoLog(shader, length, nullptr, log.data());
      fail("{}: {} shader failed to compile: {}", label, stageName(stage.stage),
           firstLines(translateShaderLog(log.c_str(), stage.files), 4));
    }
  }
  GLuint program = glCreateProgram();
  static_cast<Object&>(*this) = Object(program);
  for (GLuint shader : shaders.ids) {
    glAttachShader(program, shader);
  }
  if (!feedbackVaryings.empty()) {
    std::vector<const char*> names;
    for (const std::string& name : feedbackVaryings) {
      names.push_back(name.c_str());
    }
    glTransformFeedbackVaryings(program, static_cast<GLsizei>(names.size()), names.data(),
                                GL_INTERLEAVED_ATTRIBS);
  }
  glLinkProgram(program);
  for (GLuint shader : shaders.ids) {
    glDetachShader(program, shader);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    fail("{}: program failed to link: {}", label, firstLines(log.c_str(), 4));
  }
  setLabel(GL_PROGRAM, program, label.c_str());
}

void Program::use() const {
  glUseProgram(id());
}

GLint Program::uniformLocation(const std::string& name) const {
  auto it = mLocations.find(name);
  if (it == mLocations.end()) {
    it = mLocations.emplace(name, glGetUniformLocation(id(), name.c_str())).first;
  }
  return it->second;
}

void Program::setUniform(const std::string& name, int value) const {
  glProgramUniform1i(id(), uniformLocation(name), value);
}
void Program::setUniform(const std::string& name, unsigned value) const {
  glProgramUniform1ui(id(), uniformLocation(name), value);
}
void Program::setUniform(const std::string& name, float value) const {
  glProgramUniform1f(id(), uniformLocation(name), value);
}
void Program::setUniform(const std::string& name, const glm::vec2& value) const {
  glProgramUniform2fv(id(), uniformLocation(name), 1, glm::value_ptr(value));
}
void Program::setUniform(const std::string& name, const glm::vec3& value) const {
  glProgramUniform3fv(id(), uniformLocation(name), 1, glm::value_ptr(value));
}
void Program::setUniform(const std::string& name, const glm::vec4& value) const {
  glProgramUniform4fv(id(), uniformLocation(name), 1, glm::value_ptr(value));
}
void Program::setUniform(const std::string& name, const glm::mat4& value) const {
  glProgramUniformMatrix4fv(id(), uniformLocation(name), 1, GL_FALSE, glm::value_ptr(value));
}

glm::ivec3 Program::computeWorkGroupSize() const {
  glm::ivec3 size(0);
  glGetProgramiv(id(), GL_COMPUTE_WORK_GROUP_SIZE, &size.x);
  return size;
}

} // namespace sylva::gl
