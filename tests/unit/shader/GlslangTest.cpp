// Every shader stage in the library is valid GLSL 4.50 for the reference compiler (glslangValidator), after
// our preprocessor: this catches errors llvmpipe tolerates but stricter drivers (NVIDIA) reject, and runs
// without GL.
#include <sylva/core/Files.hpp>
#include <sylva/shader/Compiler.hpp>
#include <sylva/shader/Preprocessor.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>

namespace sylva::shader {
namespace {

std::vector<std::string> stageFiles() {
  std::vector<std::string> out;
  for (const std::string& file : Library().list()) {
    const auto dot = file.rfind('.');
    const std::string ext = file.substr(dot);
    if (ext == ".vert" || ext == ".tesc" || ext == ".tese" || ext == ".geom" || ext == ".frag" ||
        ext == ".comp") {
      out.push_back(file);
    }
  }
  return out;
}

std::string run(const std::string& command, int& status) {
  std::string output;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {
    status = -1;
    return "popen failed";
  }
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) {
    output += buffer.data();
  }
  status = ::pclose(pipe);
  return output;
}

class Glslang : public ::testing::TestWithParam<std::string> {};

TEST_P(Glslang, StageValidates) {
  const std::string validator = GLSLANG_VALIDATOR;
  ASSERT_FALSE(validator.empty() || validator.find("NOTFOUND") != std::string::npos)
      << "glslangValidator not found (install glslang-tools)";
  const std::string path = GetParam();
  const Preprocessed pre = preprocess(Library(), path);
  test::TempDir dir;
  // glslangValidator picks the stage from the extension.
  const std::filesystem::path file = dir / ("shader" + path.substr(path.rfind('.')));
  writeTextFile(file, pre.source);
  int status = 0;
  const std::string output = run(validator + " " + file.string(), status);
  EXPECT_EQ(status, 0) << path << ":\n" << gl::translateShaderLog(output, pre.files);
}

INSTANTIATE_TEST_SUITE_P(AllStages, Glslang, ::testing::ValuesIn(stageFiles()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) {
                               c = '_';
                             }
                           }
                           return name;
                         });

} // namespace
} // namespace sylva::shader
