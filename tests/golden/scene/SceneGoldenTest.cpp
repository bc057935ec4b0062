// The two example scenes (data/scenes/meadow.json and jacksboro.json), each rendered by `sylva render`
// exactly as a user runs it, against llvmpipe references: every pass of the scene (shadows, terrain, trees,
// grass, bodies, water, sky, flare) shows up in these images.
#include "CliRun.hpp"
#include "ExternalData.hpp"
#include "GlTest.hpp"
#include "Golden.hpp"
#include "TempDir.hpp"

#include <sylva/core/Image.hpp>

#include <string>

namespace sylva {
namespace {

using SceneGolden = test::GlTest; // a context of the same device class as the renders (the reference set)

Image renderScene(const std::string& scene, const std::string& extra) {
  test::TempDir dir;
  const test::RunResult r =
      test::runSylva(dir, "render " + test::quote(std::string(SYLVA_SOURCE_DIR) + "/data/scenes/" + scene) +
                              " --width 320 --height 180 " + extra + " -o " + test::at(dir, "still.png"));
  EXPECT_EQ(r.status, 0) << r.err;
  return loadImage(dir / "still.png");
}

// Tolerance: thin blades and twigs move by a pixel with one rounding difference in the rasteriser and the PCF
// shadow edges with it; up to 12 levels on at most 1.5 % of the pixels.
const render::Tolerance kSceneTolerance{12, 0.015};

TEST_F(SceneGolden, MeadowByTheLake) {
  test::expectGolden(renderScene("meadow.json", ""), "scene_meadow", kSceneTolerance);
}

TEST_F(SceneGolden, JacksboroFaultFromItsDem) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  test::expectGolden(renderScene("jacksboro.json", ""), "scene_jacksboro", kSceneTolerance);
}

} // namespace
} // namespace sylva
