// `sylva render --grass` as a user runs it (procedural terrain, a captured blade library, LOD view), and bad
// grass inputs and options that fail with one line naming the file or option and leave no image behind.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/blades/BladeModel.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <vector>

namespace sylva {
namespace {

using test::at;
using test::lineCount;
using test::runSylva;
namespace fs = std::filesystem;

const std::string kSmall = " --size 257 --spacing 2 --width 240 --height 135 ";

/** Fraction of the image's lower half where green clearly dominates. */
double greenFraction(const Image& image) {
  int green = 0;
  int total = 0;
  for (int y = image.height() / 2; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      green +=
          image.get(x, y, 1) > image.get(x, y, 0) + 0.05f && image.get(x, y, 1) > image.get(x, y, 2) ? 1 : 0;
      ++total;
    }
  }
  return static_cast<double>(green) / total;
}

TEST(GrassCli, RenderDrawsAFieldFromTheGround) {
  test::TempDir dir;
  const test::RunResult r = runSylva(dir, "render --grass" + kSmall + "-o " + at(dir, "grass.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  const Image image = loadImage(dir / "grass.png");
  EXPECT_GT(greenFraction(image), 0.8);
  // Captured blades from the shipped library, and the LOD debug view.
  const std::string library = test::quote(test::sourcePath("data/blades/slim.json").string()) + "," +
                              test::quote(test::sourcePath("data/blades/bamboo.json").string());
  const test::RunResult captured =
      runSylva(dir, "render --grass --grass-types " + library + " --grass-view lod --wind-speed 8" + kSmall +
                        "-o " + at(dir, "lod.png"));
  ASSERT_EQ(captured.status, 0) << captured.err;
  EXPECT_TRUE(fs::exists(dir / "lod.png"));
}

TEST(GrassCli, BadInputsFailWithOneLineAndNoImage) {
  test::TempDir dir;
  writeTextFile(dir / "broken.json", "{\"version\": 1, \"blades\": [");
  writeTextFile(dir / "notes.txt", "not an image");
  Image wide(64, 16, 1, PixelType::U8);
  saveImage(dir / "wide.png", wide);
  // A blade library written in millimetres: each blade 1000 times too long and too wide.
  blades::BladeModelFile millimetres = blades::loadBladeModels(test::sourcePath("data/blades/slim.json"));
  for (blades::BladeModel& blade : millimetres.blades) {
    for (blades::BladeLod& lod : blade.lods) {
      for (glm::vec3& p : lod.positions) {
        p *= 1000.0f;
      }
      for (float& w : lod.widths) {
        w *= 1000.0f;
      }
    }
  }
  blades::saveBladeModels(dir / "mm.json", millimetres);
  const std::pair<std::string, std::string> cases[] = {
      {"--grass-types " + at(dir, "mm.json"), "mm.json: /blades/0: blade model"},
      {"--grass-types " + at(dir, "missing.json"), "missing.json"},
      {"--grass-types " + at(dir, "broken.json"), "broken.json"},
      {"--grass-paint " + at(dir, "wide.png"), "wide.png"},
      {"--grass-paint " + at(dir, "notes.txt"), "notes.txt"},
      {"--grass-blades 0", "--grass-blades"},
      {"--grass-density nan", "--grass-density"},
      {"--grass-lod 40,10", "--grass-lod"},
      {"--grass-lod 10", "--grass-lod"},
      {"--grass-layer moss", "moss"},
      {"--grass-blades 100 --grass-per-tile 500", "--grass-per-tile"},
      {"--wind-speed inf", "--wind-speed"},
  };
  for (const auto& [args, named] : cases) {
    const fs::path out = dir / "out.png";
    const test::RunResult r =
        runSylva(dir, "render --grass " + args + kSmall + "-o " + test::quote(out.string()));
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

// The camera a render logs (--log-level info) is the options that render the same bytes again: the grass
// camera, the camera that films the balls (with where they drop, which --camera-pos once moved out of view),
// an exaggerated terrain (Y in true metres), and the forest camera. Passing a camera back once showed only
// ground:
// --look-at was re-aimed and the near plane differed.
TEST(GrassCli, TheLoggedCameraRendersTheSameFrameAgain) {
  test::TempDir dir;
  const std::vector<std::string> worlds = {
      "--grass", "--grass --physics balls --balls 3 --frames 3 --exaggeration 1.7", "--trees"};
  for (std::size_t w = 0; w < worlds.size(); ++w) {
    const std::string args = "render " + worlds[w] + kSmall;
    const fs::path first = dir / fmt::format("first{}.png", w);
    const test::RunResult chosen =
        runSylva(dir, "--log-level info " + args + "-o " + test::quote(first.string()));
    ASSERT_EQ(chosen.status, 0) << chosen.err;
    const std::size_t at = chosen.err.find("camera: --camera-pos");
    ASSERT_NE(at, std::string::npos) << chosen.err;
    const std::size_t begin = at + std::string("camera: ").size();
    const std::string options = chosen.err.substr(begin, chosen.err.find(" (these", begin) - begin);
    EXPECT_EQ(options.find("--balls-at") != std::string::npos, worlds[w].find("balls") != std::string::npos)
        << options;
    const fs::path again = dir / fmt::format("again{}.png", w);
    const test::RunResult given = runSylva(dir, args + options + " -o " + test::quote(again.string()));
    ASSERT_EQ(given.status, 0) << given.err;
    EXPECT_EQ(test::readAll(first), test::readAll(again)) << worlds[w] << ": " << options;
  }
}

TEST(GrassCli, PhysicsBallsFilmAnAnimation) {
  test::TempDir dir;
  const test::RunResult r = runSylva(
      dir, "render --grass --physics balls --balls 3 --frames 8 --fps 20 --size 257 --spacing 2 --width 320 "
           "--height 180 --gif " +
               at(dir, "balls.gif") + " -o " + at(dir, "last.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(test::readAll(dir / "balls.gif").substr(0, 6), "GIF89a");
  const Image last = loadImage(dir / "last.png");
  EXPECT_EQ(last.width(), 320);
  // The balls are in view: red checker pixels.
  int red = 0;
  for (int y = 0; y < last.height(); ++y) {
    for (int x = 0; x < last.width(); ++x) {
      red += last.get(x, y, 0) > 0.5f && last.get(x, y, 1) < 0.3f && last.get(x, y, 2) < 0.3f ? 1 : 0;
    }
  }
  EXPECT_GT(red, 10);
  const std::pair<std::string, std::string> bad[] = {
      {"render --physics balls", "--physics"},
      {"render --grass --physics balls --balls 0", "--balls"},
      {"render --grass --physics balls --grass-pool 0", "--grass-pool"},
      {"render --grass --physics balls --trample-recovery nan", "--trample-recovery"},
      {"render --grass --frames 2 --fps 0", "--fps"},
  };
  for (const auto& [args, named] : bad) {
    const test::RunResult e = runSylva(dir, args + kSmall + "-o " + at(dir, "bad.png"));
    EXPECT_NE(e.status, 0) << args;
    EXPECT_EQ(lineCount(e.err), 1u) << args << ": " << e.err;
    EXPECT_NE(e.err.find(named), std::string::npos) << args << ": " << e.err;
    EXPECT_FALSE(fs::exists(dir / "bad.png")) << args;
  }
}

} // namespace
} // namespace sylva
