#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/shader/Compiler.hpp>
#include <sylva/shader/Preprocessor.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

namespace sylva::shader {
namespace {

class PreprocessorTest : public ::testing::Test {
protected:
  void write(const std::string& path, const std::string& text) { writeTextFile(mDir / path, text); }
  Library library() const { return Library(mDir.path()); }
  test::TempDir mDir;
};

TEST_F(PreprocessorTest, ExpandsIncludesWithLineDirectives) {
  write("a/main.frag", "#version 450 core\n// comment\n#include \"lib.glsl\"\nvoid main() {}\n");
  write("a/lib.glsl", "float one() { return 1.0; }\n#include \"../common/two.glsl\"\n");
  write("common/two.glsl", "float two() { return 2.0; }\n");
  const Preprocessed out = preprocess(library(), "a/main.frag", {{"QUALITY", "2"}});
  EXPECT_EQ(out.files, (std::vector<std::string>{"a/main.frag", "a/lib.glsl", "common/two.glsl"}));
  EXPECT_EQ(out.source, "#version 450 core\n"
                        "#define QUALITY 2\n"
                        "#line 2 0\n"
                        "// comment\n"
                        "#line 1 1\n"
                        "float one() { return 1.0; }\n"
                        "#line 1 2\n"
                        "float two() { return 2.0; }\n"
                        "#line 3 1\n"
                        "#line 4 0\n"
                        "void main() {}\n");
}

TEST_F(PreprocessorTest, PragmaOnceIncludesOnce) {
  write("m.comp", "#version 450\n#include \"x.glsl\"\n#include \"x.glsl\"\n");
  write("x.glsl", "#pragma once\nint x;\n");
  const std::string source = preprocess(library(), "m.comp").source;
  EXPECT_EQ(source.find("int x;"), source.rfind("int x;")) << source;
}

TEST_F(PreprocessorTest, ReportsMissingIncludeWithFileAndLine) {
  write("m.vert", "#version 450\n\n#include \"nope.glsl\"\n");
  try {
    preprocess(library(), "m.vert");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "m.vert:3: cannot find include \"nope.glsl\"");
  }
}

TEST_F(PreprocessorTest, RejectsCyclesAndMissingVersion) {
  write("c.frag", "#version 450\n#include \"a.glsl\"\n");
  write("a.glsl", "#include \"b.glsl\"\n");
  write("b.glsl", "#include \"a.glsl\"\n");
  EXPECT_THROW(preprocess(library(), "c.frag"), Error);
  write("nov.frag", "void main() {}\n");
  EXPECT_THROW(preprocess(library(), "nov.frag"), Error);
  EXPECT_THROW(preprocess(library(), "absent.frag"), Error);
}

TEST_F(PreprocessorTest, LeavesAngleIncludesForCxx) {
  write("s.vert", "#version 450\n#ifdef __cplusplus\n#include <cstdint>\n#endif\n");
  EXPECT_NE(preprocess(library(), "s.vert").source.find("#include <cstdint>"), std::string::npos);
}

TEST(ShaderLibrary, EmbeddedLibraryHasTheShaderTree) {
  const Library embedded;
  const auto files = embedded.list();
  EXPECT_NE(std::find(files.begin(), files.end(), "demo/patch.tese"), files.end());
  EXPECT_NE(std::find(files.begin(), files.end(), "shared/Frame.h"), files.end());
  // The embedded copy is byte-identical to the source tree it was built from.
  const Library disk(Library::sourceDirectory());
  for (const std::string& file : files) {
    EXPECT_EQ(embedded.read(file), disk.read(file)) << file;
  }
}

TEST(ShaderLibrary, StageFromExtension) {
  EXPECT_EQ(stageForPath("x/y.tesc"), static_cast<GLenum>(GL_TESS_CONTROL_SHADER));
  EXPECT_EQ(stageForPath("x/y.comp"), static_cast<GLenum>(GL_COMPUTE_SHADER));
  EXPECT_THROW(stageForPath("x/y.glsl"), Error);
}

TEST(ShaderLog, TranslatesSourceNumbersToFiles) {
  const std::vector<std::string> files = {"demo/a.frag", "common/b.glsl"};
  EXPECT_EQ(gl::translateShaderLog("1:12(5): error: undeclared", files),
            "common/b.glsl:12(5): error: undeclared");
  EXPECT_EQ(gl::translateShaderLog("0(7) : error C1008: x", files), "demo/a.frag:7 : error C1008: x");
}

} // namespace
} // namespace sylva::shader
