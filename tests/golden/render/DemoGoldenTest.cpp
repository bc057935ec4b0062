#include <sylva/core/Files.hpp>
#include <sylva/render/gpu/DemoScene.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>

#include "GlTest.hpp"
#include "Golden.hpp"
#include "TempDir.hpp"

namespace sylva::render {
namespace {

using DemoGolden = test::GlTest;

Image renderDemo(const shader::Library& library, int width, int height, bool wireframe = false) {
  DemoScene scene(library);
  RenderTarget target(width, height);
  target.begin(glm::vec4(0.62f, 0.72f, 0.85f, 1.0f));
  scene.render(scene.defaultCamera(), width, height, 1.0, nullptr, wireframe);
  return target.readColor();
}

// Tolerance: llvmpipe is deterministic for one build, but another LLVM version may round transcendental
// functions (sin, exp, pow in toSrgb) differently by an ulp; that moves a few channels by 1-2 steps.
constexpr Tolerance kDemoTolerance{2, 0.001};

TEST_F(DemoGolden, Scene) {
  test::expectGolden(renderDemo(shaders(), 320, 240), "demo_320x240", kDemoTolerance);
}

TEST_F(DemoGolden, Wireframe) {
  // Wireframe lines are 1 px wide: a different tessellation rounding moves whole lines, so allow more pixels.
  test::expectGolden(renderDemo(shaders(), 320, 240, true), "demo_wireframe_320x240", {2, 0.005});
}

// The golden check must catch a change in a shader's output: render with a copy of the shader tree whose
// fragment shader is subtly altered (5% darker) and require the comparison to fail.
TEST_F(DemoGolden, DetectsAShaderChange) {
  test::TempDir dir;
  const shader::Library embedded;
  for (const std::string& file : embedded.list()) {
    std::string text = *embedded.read(file);
    if (file == "demo/patch.frag") {
      const std::string from = "outColor = vec4(toSrgb(";
      ASSERT_NE(text.find(from), std::string::npos);
      text.replace(text.find(from), from.size(), "outColor = vec4(0.95 * toSrgb(");
    }
    writeTextFile(dir / file, text);
  }
  const Image altered = renderDemo(shader::Library(dir.path()), 320, 240);
  const Image reference = loadImage(test::goldenReferencePath("demo_320x240"));
  const CompareResult result = compareImages(altered, reference, kDemoTolerance);
  EXPECT_FALSE(result.passed) << "a 5% darker surface went unnoticed";
  EXPECT_GT(result.failingFraction(), 0.3);
}

} // namespace
} // namespace sylva::render
