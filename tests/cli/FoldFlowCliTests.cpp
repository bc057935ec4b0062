// `sylva fold flow` as a user runs it: a generated clip with a known motion gives a project whose zone has a
// points tool carrying that motion (mapped onto the zone), plus a flow picture; a bad video, a missing one,
// an unknown zone or a frame past the end fail with one line on stderr and leave no file behind.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/folding/Flow.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace sylva {
namespace {

using test::at;
using test::lineCount;
using test::runSylva;

namespace fs = std::filesystem;
using test::quote;

/** The known motion: background (2.5, −1.25) px/frame, a disc on the right that turns and grows. */
folding::SyntheticMotion motion() {
  folding::SyntheticMotion m;
  m.centre = folding::Vec2(176.0, 100.0);
  m.radius = 48.0;
  m.rotationRad = 0.04;
  m.scale = 1.03;
  return m;
}

/** clip.avi (256×192, 4 frames), img.png (512×384) and p.json with zone "eye" over (160, 120)-(288, 216). */
void writeInputs(const test::TempDir& dir) {
  folding::saveVideo(dir / "clip.avi", folding::syntheticVideo({256, 192}, 4, motion(), 3));
  saveImage(dir / "img.png", Image(512, 384, 4, PixelType::U8));
  writeTextFile(dir / "p.json", R"({"format": "sylva-fold", "version": 1,
    "atlas": {"images": [{"id": "img", "file": "img.png"}]},
    "profiles": [{"id": "p", "period_s": 2, "fn": {"type": "sine"}}],
    "zones": [{"id": "eye", "image": "img", "profile": "p",
               "shape": {"type": "rect", "min": [160, 120], "max": [288, 216]}}]})");
}

TEST(FoldFlowCli, SyntheticVideoGivesAProjectWithAPointsTool) {
  const test::TempDir dir;
  writeInputs(dir);
  const test::RunResult r =
      runSylva(dir, "fold flow " + at(dir, "clip.avi") + " --project " + at(dir, "p.json") +
                        " --zone eye --frames 1,2 --spacing 8 --picture " + at(dir, "flow.png") + " --out " +
                        at(dir, "sub/edited.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("flow 1 -> 2"));
  EXPECT_THAT(r.out, testing::HasSubstr("mapping zone: 0.5 x 0.5 image px per frame px"));
  EXPECT_THAT(r.out, testing::HasSubstr("anchors: "));

  const Image picture = loadImage(dir / "flow.png");
  EXPECT_EQ(picture.width(), 256);
  EXPECT_EQ(picture.height(), 192);

  const nlohmann::json edited = loadJsonFile(dir / "sub/edited.json");
  EXPECT_EQ(edited["atlas"]["images"][0]["file"], "../img.png") << "image paths follow the new location";
  const nlohmann::json& tools = edited["zones"][0]["tools"];
  ASSERT_EQ(tools.size(), 1u);
  EXPECT_EQ(tools[0]["type"], "points");
  const nlohmann::json& pairs = tools[0]["pairs"];
  ASSERT_GE(pairs.size(), 100u);
  std::size_t background = 0;
  for (const nlohmann::json& pair : pairs) {
    const folding::Vec2 a(pair[0][0].get<double>(), pair[0][1].get<double>());
    const folding::Vec2 b(pair[1][0].get<double>(), pair[1][1].get<double>());
    EXPECT_TRUE(a.x > 160 && a.x < 288 && a.y > 120 && a.y < 216) << a.x << ", " << a.y;
    // Away from the disc and the frame border, the background's motion at half scale.
    const folding::Vec2 p = (a - folding::Vec2(160, 120)) * 2.0;
    if (glm::length(p - motion().centre) > motion().radius + 12.0 && p.x > 16 && p.y > 16 && p.y < 176) {
      EXPECT_NEAR(b.x - a.x, 1.25, 0.15);
      EXPECT_NEAR(b.y - a.y, -0.625, 0.15);
      ++background;
    }
  }
  EXPECT_GT(background, 30u);

  // The written project is valid: `fold info` reads it.
  const test::RunResult info = runSylva(dir, "fold info " + at(dir, "sub/edited.json"));
  EXPECT_EQ(info.status, 0) << info.err;
  EXPECT_THAT(info.out, testing::HasSubstr("tools: points"));
}

TEST(FoldFlowCli, BadInputsFailWithOneLineAndWriteNothing) {
  const test::TempDir dir;
  writeInputs(dir);
  std::ofstream(dir / "bad.avi") << "RIFF....AVI not really a video";
  struct Case {
    std::string args;
    std::string message;
  };
  const std::string project = " --project " + at(dir, "p.json");
  const std::string clip = "fold flow " + at(dir, "clip.avi") + project;
  const std::vector<Case> cases = {
      {"fold flow " + at(dir, "bad.avi") + project + " --zone eye", "bad.avi: cannot decode"},
      {"fold flow " + at(dir, "none.avi") + project + " --zone eye", "none.avi: no such file"},
      {"fold flow " + at(dir, "seq/%04d.png") + project + " --zone eye", "no such directory"},
      {clip + " --zone nope", "p.json has no zone 'nope'"},
      {clip + " --zone eye --frames 0,7", "clip.avi has 4 frames (0..3), no frame 7"},
      {clip + " --zone eye --min-magnitude 500", "no anchors suggested"},
      {clip + " --zone eye --method lucas", "--method"},
  };
  for (const Case& c : cases) {
    const test::RunResult r =
        runSylva(dir, c.args + " --picture " + at(dir, "flow.png") + " --out " + at(dir, "out.json"));
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_EQ(lineCount(r.err), 1u) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, testing::HasSubstr(c.message)) << c.args;
    EXPECT_FALSE(fs::exists(dir / "out.json")) << c.args;
    EXPECT_FALSE(fs::exists(dir / "flow.png")) << c.args;
  }
}

} // namespace
} // namespace sylva
