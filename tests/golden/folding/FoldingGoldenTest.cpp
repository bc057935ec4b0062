// Golden frames of the shipped folding examples, drawn by the GL renderer: a change to the synthesis, the
// encoding-independent equations or the shaders that alters what users see fails here.
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Synthesis.hpp>
#include <sylva/folding/gpu/FoldRenderer.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"
#include "Golden.hpp"

namespace sylva::folding {
namespace {

using FoldingGolden = test::GlTest;

/** The canvas of example `name` at time t (seconds), rendered by the GL renderer. */
Image renderExample(const shader::Library& library, const std::string& name, double t) {
  const std::filesystem::path path = test::sourcePath("data/folding/" + name);
  const Project project = loadProject(path);
  const ProjectImages images = loadProjectImages(project, path.string());
  const Textures textures = synthesize(project, images);
  gpu::FoldRenderer renderer(library);
  renderer.upload(textures, project.profiles, project.jumpLayers);
  const Image frame = renderer.render(t);
  // The GL and CPU renderers agree exactly on llvmpipe (tests/gl/folding); check it on this frame too, so a
  // golden failure says whether the equations or only the GL side moved.
  EXPECT_EQ(frame, renderFrame(textures, project.profiles, project.jumpLayers, t));
  return cropToEntry(frame, textures.atlas.entries[static_cast<std::size_t>(project.canvasIndex())]);
}

// Tolerance: the frame is integer arithmetic on bytes except the position function (exp, cos) and the
// bilinear weights; another LLVM version may round those by an ulp and move a few channels by one step.
constexpr render::Tolerance kFoldTolerance{1, 0.0005};

TEST_F(FoldingGolden, BeachAtTheHeightOfTheSwash) {
  test::expectGolden(renderExample(shaders(), "beach.json", 1.6), "fold_beach_t1.6", kFoldTolerance);
}

TEST_F(FoldingGolden, BirdInMidFlight) {
  test::expectGolden(renderExample(shaders(), "flyover.json", 2.5), "fold_flyover_t2.5", kFoldTolerance);
}

TEST_F(FoldingGolden, CatSquinting) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("chelsea.png"));
  test::expectGolden(renderExample(shaders(), "cat.json", 1.6), "fold_cat_t1.6", kFoldTolerance);
}

} // namespace
} // namespace sylva::folding
