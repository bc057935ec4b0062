// `sylva capture` as a user runs it: a synthetic depth PNG and a synthetic fakenect recording through the
// real command (blade models, overlay, stage pictures, tracked motion), the same recording replayed through
// the real libfreenect API under `fakenect` (identical models), `--kinect` without a device, and bad inputs
// and options that fail with one line naming the file, frame or option and leave no output behind.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/blades/BladeModel.hpp>
#include <sylva/capture/Depth.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace sylva {
namespace {

using test::at;
using test::lineCount;
using test::runSylva;
using test::runSylvaFrom;

namespace fs = std::filesystem;
using test::quote;

const fs::path kFakenect = "/usr/bin/fakenect";

std::size_t countOf(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++n;
  }
  return n;
}

/** The depth files of a recording, in INDEX.txt order. */
std::vector<std::string> depthFiles(const fs::path& recording) {
  std::vector<std::string> files;
  std::istringstream index(readTextFile(recording / "INDEX.txt"));
  std::string line;
  while (std::getline(index, line)) {
    if (line.starts_with("d-")) {
      files.push_back(line);
    }
  }
  return files;
}

void copyRecording(const fs::path& from, const fs::path& to) {
  fs::copy(from, to, fs::copy_options::recursive);
}

TEST(CaptureCli, SyntheticPngGivesBladeModelsAndAnOverlay) {
  const test::TempDir dir;
  const test::RunResult synth =
      runSylva(dir, "capture synth --shape slender -o " + at(dir, "s.png") + " --truth " + at(dir, "t.json"));
  ASSERT_EQ(synth.status, 0) << synth.err;
  ASSERT_TRUE(fs::exists(dir / "s-colour.png"));
  ASSERT_TRUE(fs::exists(dir / "t.json"));

  const test::RunResult r =
      runSylva(dir, "capture " + at(dir, "s.png") + " --colour " + at(dir, "s-colour.png") + " -o " +
                        at(dir, "m.json") + " --overlay " + at(dir, "o.png"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("5 blades"));
  EXPECT_THAT(r.out, testing::HasSubstr("colour-refined edges"));
  const blades::BladeModelFile models = blades::loadBladeModels(dir / "m.json");
  ASSERT_EQ(models.blades.size(), 5u);
  for (const blades::BladeModel& blade : models.blades) {
    ASSERT_EQ(blade.lods.size(), 3u) << blade.name;
    EXPECT_EQ(blade.lods[0].knotCount(), 64u) << blade.name;
    EXPECT_EQ(blade.lods[1].knotCount(), 32u) << blade.name;
    EXPECT_EQ(blade.lods[2].knotCount(), 16u) << blade.name;
    EXPECT_EQ(blade.source.kind, "depth-png") << blade.name;
  }
  const Image input = loadImage(dir / "s.png");
  const Image overlay = loadImage(dir / "o.png");
  EXPECT_EQ(overlay.width(), input.width());
  EXPECT_EQ(overlay.height(), input.height());

  // Other levels, and the stage pictures for the docs.
  const test::RunResult levels = runSylva(dir, "capture " + at(dir, "s.png") + " --levels 32,8 -q -o " +
                                                   at(dir, "l.json") + " --stages " + at(dir, "stages"));
  ASSERT_EQ(levels.status, 0) << levels.err;
  const blades::BladeModelFile coarse = blades::loadBladeModels(dir / "l.json");
  ASSERT_EQ(coarse.blades.size(), 5u);
  for (const blades::BladeModel& blade : coarse.blades) {
    ASSERT_EQ(blade.lods.size(), 2u) << blade.name;
    EXPECT_EQ(blade.lods[0].knotCount(), 32u) << blade.name;
    EXPECT_EQ(blade.lods[1].knotCount(), 8u) << blade.name;
  }
  for (const char* stage : {"1-depth.png", "2-mask.png", "3-contour.png", "4-signal.png", "5-blades.png"}) {
    EXPECT_TRUE(fs::exists(dir / "stages" / stage)) << stage;
  }

  // --stages alone still writes the model and the overlay where they go by default, and says so.
  fs::create_directories(dir / "w");
  const test::RunResult stages =
      runSylvaFrom(dir / "w", dir, "capture " + at(dir, "s.png") + " --stages " + at(dir, "w/stages"));
  ASSERT_EQ(stages.status, 0) << stages.err;
  EXPECT_TRUE(fs::exists(dir / "w/out/capture/s.blades.json"));
  EXPECT_TRUE(fs::exists(dir / "w/out/capture/s-overlay.png"));
  EXPECT_TRUE(fs::exists(dir / "w/stages/5-blades.png"));
  EXPECT_THAT(stages.out, testing::HasSubstr("wrote out/capture/s.blades.json"));
}

TEST(CaptureCli, SyntheticEvaluatePrintsEveryFrame) {
  const test::TempDir dir;
  const test::RunResult r = runSylva(dir, "capture synth --frames 3 --evaluate -o " + at(dir, "rec"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(countOf(r.out, "blades 5/5"), 3u) << r.out;
  for (const char* frame : {"frame 0: ", "frame 1: ", "frame 2: "}) {
    EXPECT_THAT(r.out, testing::HasSubstr(frame));
  }
}

TEST(CaptureCli, SyntheticLayoutsAndTheSweep) {
  // The classes of the capture sweep from the command line: an occluded cluster draws its extra blade (the
  // truth lists all six), a rolled crossing cluster writes its frame, and --sweep tallies every layout.
  const test::TempDir dir;
  const test::RunResult occluded =
      runSylva(dir, "capture synth --layout occluded --count 6 --roll 0.3 --pitch 0.2 --dropout 0.3 -o " +
                        at(dir, "o.png") + " --truth " + at(dir, "o.json"));
  ASSERT_EQ(occluded.status, 0) << occluded.err;
  EXPECT_EQ(countOf(test::readAll(dir / "o.json"), "\"shape\""), 6u);
  const test::RunResult crossing = runSylva(
      dir, "capture synth --layout crossing --count 6 --roll -0.3 --evaluate -o " + at(dir, "c.png"));
  ASSERT_EQ(crossing.status, 0) << crossing.err;
  EXPECT_THAT(crossing.out, testing::HasSubstr("/6, silhouette IoU"));
  const test::RunResult sweep = runSylva(dir, "capture synth --sweep 12 --seed 5");
  ASSERT_EQ(sweep.status, 0) << sweep.err;
  EXPECT_THAT(sweep.out, testing::HasSubstr("all          12 clusters  count exact"));
  EXPECT_EQ(countOf(sweep.out, " clusters  count exact"), 5u) << sweep.out;
  // Seed 5 is a crossing cluster whose count comes out wrong: the sweep names it.
  EXPECT_THAT(sweep.out, testing::HasSubstr("wrong counts at seeds 5"));
  // A cluster the sweep drew, redrawn on its own and captured with --explain: its front blade is partitioned
  // on its own depth layer. Seed 8 is an occluded cluster of seven blades.
  const test::RunResult drawn = runSylva(dir, "capture synth --sweep-cluster 8 -o " + at(dir, "s8.png"));
  ASSERT_EQ(drawn.status, 0) << drawn.err;
  EXPECT_THAT(drawn.out, testing::HasSubstr("7 slender blades, occluded layout"));
  const test::RunResult explained =
      runSylva(dir, "capture " + at(dir, "s8.png") + " --explain -o " + at(dir, "s8.json"));
  ASSERT_EQ(explained.status, 0) << explained.err;
  EXPECT_THAT(explained.out, testing::HasSubstr("7 blades in 2 clusters"));
  EXPECT_THAT(explained.out, testing::HasSubstr("depth layer 0 of 2"));
  EXPECT_THAT(explained.out, testing::HasSubstr("depth layer 1 of 2"));
  // A dense fan of 13 whose blades merge (11 found): --explain says which blade is probably several.
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 24 -o " + at(dir, "s24.png")).status, 0);
  const test::RunResult dense =
      runSylva(dir, "capture " + at(dir, "s24.png") + " --explain -o " + at(dir, "s24.json"));
  ASSERT_EQ(dense.status, 0) << dense.err;
  EXPECT_THAT(dense.out, testing::HasSubstr("as wide as the cluster's median blade"));
  EXPECT_THAT(dense.out, testing::HasSubstr("probably blades merged"));
  EXPECT_EQ(countOf(explained.out, "merged?"), 0u) << "the occluded fan is captured whole";
  // A dense fan of 13 whose tips part only near their ends: the notches between them are junctions (13
  // blades). Without notches its merged blades are split between their tips (9 blades without the split, 12
  // when wider than 1.6× the median blade, all 13 when wider than 1.4× the narrow blades): --explain says
  // where.
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 3 --layout dense -o " + at(dir, "d3.png")).status,
            0);
  const test::RunResult notched = runSylva(dir, "capture " + at(dir, "d3.png") + " --explain");
  ASSERT_EQ(notched.status, 0) << notched.err;
  EXPECT_THAT(notched.out, testing::HasSubstr("13 blades in 1 cluster"));
  EXPECT_EQ(countOf(notched.out, "split: "), 0u) << notched.out;
  const test::RunResult split =
      runSylva(dir, "capture " + at(dir, "d3.png") + " --explain --notch-prominence 0");
  ASSERT_EQ(split.status, 0) << split.err;
  EXPECT_THAT(split.out, testing::HasSubstr("13 blades in 1 cluster"));
  EXPECT_THAT(split.out, testing::HasSubstr("the cluster's narrow blades) was cut at"));
  EXPECT_THAT(split.out, testing::HasSubstr("split: the blade"));
  EXPECT_THAT(split.out, testing::HasSubstr("between two of its tips"));
  // Crossing fans of eight blades that merge in the outline up to tips that part in depth: --explain names
  // each split, and the eighth blade, whose neighbours hide all but its end, found by its surface;
  // --no-depth-split keeps them merged.
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 20 -o " + at(dir, "s20.png")).status, 0);
  const test::RunResult parted = runSylva(dir, "capture " + at(dir, "s20.png") + " --explain");
  ASSERT_EQ(parted.status, 0) << parted.err;
  EXPECT_THAT(parted.out, testing::HasSubstr("8 blades in 1 cluster"));
  EXPECT_EQ(countOf(parted.out, "parts in depth towards its tip into 2 surfaces"), 2u) << parted.out;
  EXPECT_EQ(countOf(parted.out, "where no blade ends: one blade more"), 1u) << parted.out;
  const test::RunResult unparted =
      runSylva(dir, "capture " + at(dir, "s20.png") + " --explain --no-depth-split");
  ASSERT_EQ(unparted.status, 0) << unparted.err;
  EXPECT_THAT(unparted.out, testing::HasSubstr("5 blades in 1 cluster"));
  EXPECT_EQ(countOf(unparted.out, "parts in depth"), 0u);
  // --layout narrows the sweep to one class, and the hint redraws a cluster of that class.
  const test::RunResult crossing8 = runSylva(dir, "capture synth --sweep 8 --layout crossing");
  ASSERT_EQ(crossing8.status, 0) << crossing8.err;
  EXPECT_THAT(crossing8.out, testing::HasSubstr("crossing      8 clusters"));
  EXPECT_EQ(countOf(crossing8.out, " clusters  count exact"), 2u) << crossing8.out; // crossing and all
  EXPECT_THAT(crossing8.out, testing::HasSubstr("--sweep-cluster SEED --layout crossing"));
  // A cluster redrawn from its seed and captured from the PNG is counted as --evaluate (and the sweep)
  // counted it: both capture the depth the file holds, whole millimetres.
  const test::RunResult evaluated =
      runSylva(dir, "capture synth --sweep-cluster 10 --layout crossing --evaluate -o " + at(dir, "c10.png"));
  ASSERT_EQ(evaluated.status, 0) << evaluated.err;
  const std::size_t slash = evaluated.out.find("/", evaluated.out.find("frame 0: blades "));
  ASSERT_NE(slash, std::string::npos) << evaluated.out;
  const std::size_t count = evaluated.out.rfind(' ', slash);
  const std::string found = evaluated.out.substr(count + 1, slash - count - 1);
  const test::RunResult recaptured = runSylva(dir, "capture " + at(dir, "c10.png") + " --no-colour");
  ASSERT_EQ(recaptured.status, 0) << recaptured.err;
  EXPECT_THAT(recaptured.out, testing::HasSubstr(": " + found + " blades in")) << evaluated.out;
  // A dense fan with a short pointed tip beyond its overlapping neighbours: a blade, unless --pointed-tip 1
  // (and --tip-surfaces 0, which would find it by its surface instead).
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 488 -o " + at(dir, "p.png")).status, 0);
  const test::RunResult pointed = runSylva(dir, "capture " + at(dir, "p.png") + " --no-colour");
  ASSERT_EQ(pointed.status, 0) << pointed.err;
  EXPECT_THAT(pointed.out, testing::HasSubstr("13 blades in"));
  const test::RunResult blunt =
      runSylva(dir, "capture " + at(dir, "p.png") + " --no-colour --pointed-tip 1 --tip-surfaces 0");
  ASSERT_EQ(blunt.status, 0) << blunt.err;
  EXPECT_THAT(blunt.out, testing::HasSubstr("12 blades in"));
  EXPECT_NE(runSylva(dir, "capture " + at(dir, "p.png") + " --pointed-tip 0").status, 0);
  // A dense fan whose neighbours hide all but the last pixels of two blades merged in the outline: they part
  // in depth over their outer third, which --explain names; --depth-split-outer 0 keeps them merged (with
  // --tip-surfaces 0, which would find the hidden one by its surface instead).
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 89 -o " + at(dir, "o.png")).status, 0);
  const test::RunResult outer = runSylva(dir, "capture " + at(dir, "o.png") + " --no-colour --explain");
  ASSERT_EQ(outer.status, 0) << outer.err;
  EXPECT_THAT(outer.out, testing::HasSubstr("12 blades in"));
  EXPECT_EQ(countOf(outer.out, "(over the outer 35 % of its length"), 1u) << outer.out;
  const test::RunResult inner = runSylva(
      dir, "capture " + at(dir, "o.png") + " --no-colour --explain --depth-split-outer 0 --tip-surfaces 0");
  ASSERT_EQ(inner.status, 0) << inner.err;
  EXPECT_THAT(inner.out, testing::HasSubstr("11 blades in"));
  EXPECT_EQ(countOf(inner.out, "over the outer"), 0u);
  EXPECT_NE(runSylva(dir, "capture " + at(dir, "o.png") + " --depth-split-outer 1").status, 0);
  // Crossing fans where two blades show only their ends, with no junction in the outline: each end is a
  // depth surface of its own ending in a free tip where no captured blade ends, which --explain names;
  // --tip-surfaces 0 leaves them out.
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 557 -o " + at(dir, "t.png")).status, 0);
  const test::RunResult tips = runSylva(dir, "capture " + at(dir, "t.png") + " --no-colour --explain");
  ASSERT_EQ(tips.status, 0) << tips.err;
  EXPECT_THAT(tips.out, testing::HasSubstr("7 blades in"));
  EXPECT_EQ(countOf(tips.out, "where no blade ends: one blade more"), 2u) << tips.out;
  const test::RunResult noTips =
      runSylva(dir, "capture " + at(dir, "t.png") + " --no-colour --explain --tip-surfaces 0");
  ASSERT_EQ(noTips.status, 0) << noTips.err;
  EXPECT_THAT(noTips.out, testing::HasSubstr("5 blades in"));
  EXPECT_EQ(countOf(noTips.out, "where no blade ends"), 0u);
  EXPECT_NE(runSylva(dir, "capture " + at(dir, "t.png") + " --tip-surfaces 1").status, 0);
  // Crossing fans where the front blade crosses a back one at a shallow angle and breaks it in two depth
  // layers: --explain says it was joined; --no-join keeps the broken-off part as a blade.
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 331 -o " + at(dir, "j.png")).status, 0);
  const test::RunResult joined = runSylva(dir, "capture " + at(dir, "j.png") + " --no-colour --explain");
  ASSERT_EQ(joined.status, 0) << joined.err;
  EXPECT_THAT(joined.out, testing::HasSubstr("4 blades in"));
  EXPECT_EQ(countOf(joined.out, "joined: the blade with its tip at"), 1u) << joined.out;
  EXPECT_THAT(joined.out, testing::HasSubstr("broke off where a nearer blade crosses it"));
  const test::RunResult apart =
      runSylva(dir, "capture " + at(dir, "j.png") + " --no-colour --explain --no-join");
  ASSERT_EQ(apart.status, 0) << apart.err;
  EXPECT_THAT(apart.out, testing::HasSubstr("5 blades in"));
  EXPECT_EQ(countOf(apart.out, "joined: "), 0u);
  // An occluded fan: the blade behind the narrow one is measured as wide as where both its edges show,
  // unless --no-occluded-widths.
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 12 -o " + at(dir, "o.png")).status, 0);
  ASSERT_EQ(runSylva(dir, "capture " + at(dir, "o.png") + " --no-colour -o " + at(dir, "wide.json")).status,
            0);
  ASSERT_EQ(runSylva(dir, "capture " + at(dir, "o.png") + " --no-colour --no-occluded-widths -o " +
                              at(dir, "shown.json"))
                .status,
            0);
  EXPECT_NE(test::readAll(dir / "wide.json"), test::readAll(dir / "shown.json"));
  // A dense fan whose blades overlap: those found on a medial axis are measured over their own depth surface,
  // unless --no-surface-widths (then as wide as the region they share).
  ASSERT_EQ(runSylva(dir, "capture synth --sweep-cluster 787 -o " + at(dir, "d.png")).status, 0);
  const test::RunResult own = runSylva(dir, "capture " + at(dir, "d.png") + " --no-colour");
  const test::RunResult shared =
      runSylva(dir, "capture " + at(dir, "d.png") + " --no-colour --no-surface-widths");
  ASSERT_EQ(own.status, 0) << own.err;
  ASSERT_EQ(shared.status, 0) << shared.err;
  EXPECT_THAT(own.out, testing::HasSubstr("13 blades in"));
  EXPECT_THAT(shared.out, testing::HasSubstr("13 blades in"));
  EXPECT_NE(own.out, shared.out) << "the medial-axis blades' widths differ";
  const test::RunResult both = runSylva(dir, "capture synth --sweep 4 --sweep-cluster 8");
  EXPECT_NE(both.status, 0);
  const test::RunResult one =
      runSylva(dir, "capture synth --layout occluded --count 1 -o " + at(dir, "x.png"));
  EXPECT_NE(one.status, 0);
  EXPECT_THAT(one.err, testing::HasSubstr("the occluded layout needs at least 2 blades"));
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

TEST(CaptureCli, RecordingIsTrackedAndReplaysThroughLibfreenect) {
  const test::TempDir dir;
  const test::RunResult synth = runSylva(dir, "capture synth --frames 8 -o " + at(dir, "rec"));
  ASSERT_EQ(synth.status, 0) << synth.err;
  ASSERT_TRUE(fs::exists(dir / "rec" / "INDEX.txt"));

  const test::RunResult r = runSylva(dir, "capture " + at(dir, "rec") + " -o " + at(dir, "a.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("5 blades"));
  EXPECT_THAT(r.out, testing::HasSubstr("tracked through the recording"));
  const nlohmann::json a = loadJsonFile(dir / "a.json");
  ASSERT_EQ(a["blades"].size(), 5u);
  for (const nlohmann::json& blade : a["blades"]) {
    EXPECT_EQ(blade["source"]["motionFrames"], 8);
    EXPECT_EQ(blade["source"]["kind"], "fakenect");
  }

  const test::RunResult part =
      runSylva(dir, "capture " + at(dir, "rec") + " --frames 2-5 -q -o " + at(dir, "part.json"));
  ASSERT_EQ(part.status, 0) << part.err;
  const nlohmann::json p = loadJsonFile(dir / "part.json");
  ASSERT_FALSE(p["blades"].empty());
  for (const nlohmann::json& blade : p["blades"]) {
    EXPECT_EQ(blade["source"]["motionFrames"], 4);
    EXPECT_EQ(blade["source"]["frame"], 2);
  }

  if (!fs::exists(kFakenect)) {
    GTEST_SKIP() << kFakenect.string() << " is missing (install libfreenect-bin): the replay is not tested";
  }
  const test::RunResult replay =
      test::runProgram(kFakenect.string(), dir.path(),
                       at(dir, "rec") + " " + quote(SYLVA_EXE) + " capture --kinect -o " + at(dir, "b.json"));
  ASSERT_EQ(replay.status, 0) << replay.out << replay.err;
  EXPECT_THAT(replay.out, testing::HasSubstr("tracked through the recording"));
  const nlohmann::json b = loadJsonFile(dir / "b.json");
  ASSERT_EQ(b["blades"].size(), a["blades"].size());
  for (std::size_t i = 0; i < a["blades"].size(); ++i) {
    EXPECT_EQ(b["blades"][i]["lods"], a["blades"][i]["lods"]) << "blade " << i;
    EXPECT_EQ(b["blades"][i]["source"]["kind"], "kinect");
    EXPECT_EQ(b["blades"][i]["source"]["motionFrames"], 8);
  }
}

TEST(CaptureCli, KinectWithoutADeviceFailsWithOneLine) {
  const test::TempDir dir;
  // No replay: FAKENECT_PATH unset, whatever the test's environment holds.
  const test::RunResult r =
      test::runProgram("/usr/bin/env", dir.path(),
                       "-u FAKENECT_PATH " + quote(SYLVA_EXE) + " capture --kinect -o " +
                           at(dir, "out/k.json") + " --overlay " + at(dir, "out/k.png"));
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  const bool noDevice = r.err.find("no Kinect v1 found") != std::string::npos;
  const bool noUsb = r.err.find("libfreenect could not start") != std::string::npos;
  EXPECT_TRUE(noDevice || noUsb) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CaptureCli, BadInputsFailWithOneLineAndWriteNothing) {
  const test::TempDir dir;
  ASSERT_EQ(runSylva(dir, "capture synth -o " + at(dir, "s.png")).status, 0);
  ASSERT_EQ(runSylva(dir, "capture synth --frames 4 --no-colour -o " + at(dir, "rec")).status, 0);
  const std::vector<std::string> depth = depthFiles(dir / "rec");
  ASSERT_EQ(depth.size(), 4u);

  saveImage(dir / "grey8.png", Image(64, 48, 1, PixelType::U8));
  saveImage(dir / "zero16.png", Image(64, 48, 1, PixelType::U16));
  Image dot(1, 1, 1, PixelType::U16);
  dot.set(0, 0, 0, 0.02f);
  saveImage(dir / "dot.png", dot);
  capture::DepthFrame background(640, 480);
  std::fill(background.depth.begin(), background.depth.end(), 1.5f);
  capture::saveDepthPng(dir / "background.png", background);
  copyRecording(dir / "rec", dir / "noindex");
  fs::remove(dir / "noindex" / "INDEX.txt");
  copyRecording(dir / "rec", dir / "truncated");
  fs::resize_file(dir / "truncated" / depth[2], 1000);

  struct Case {
    std::string args;
    std::vector<std::string> message;
  };
  const std::string png = "capture " + at(dir, "s.png");
  const std::vector<Case> cases = {
      {"capture " + at(dir, "grey8.png") + " --format png", {"grey8.png", "16-bit", "got 8-bit"}},
      {"capture " + at(dir, "zero16.png"), {"zero16.png", "no valid depth pixel"}},
      {"capture " + at(dir, "dot.png"), {"dot.png", "1x1 frame is too small"}},
      {"capture " + at(dir, "background.png"), {"background.png", "no blades found"}},
      {"capture " + at(dir, "background.png") + " --near 0.3 --far 0.5",
       {"background.png", "no blades found", "empty mask"}},
      {"capture " + at(dir, "none.png"), {"none.png", "no such file"}},
      {"capture " + at(dir, "noindex"), {"noindex", "INDEX.txt is missing"}},
      {"capture " + at(dir, "truncated"), {depth[2], "frame 2", "truncated"}},
      {"capture " + at(dir, "rec") + " --frames 2-9", {"--frames 2-9", "4 depth frames"}},
      {png + " --frames 1", {"--frames 1", "s.png has 1 depth frame"}},
      {png + " --levels 16,32", {"--levels", "16,32", "decrease"}},
      {png + " --roi 100,0,50,10", {"--roi", "100,0,50,10"}},
      {png + " --centre nonsense", {"--centre", "nonsense"}},
      {png + " --levels 64,32 --knots 32", {"--levels", "--knots 32"}},
  };
  for (const Case& c : cases) {
    const test::RunResult r =
        runSylva(dir, c.args + " -o " + at(dir, "out/x.json") + " --overlay " + at(dir, "out/x.png"));
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_EQ(lineCount(r.err), 1u) << c.args << "\n" << r.err;
    for (const std::string& part : c.message) {
      EXPECT_THAT(r.err, testing::HasSubstr(part)) << c.args;
    }
    EXPECT_FALSE(fs::exists(dir / "out")) << c.args;
    if (c.args.find("--roi") == std::string::npos) {
      EXPECT_THAT(r.err, testing::Not(testing::HasSubstr("--roi"))) << c.args;
    }
  }

  // A depth file listed in INDEX.txt but missing is a warning naming it and its frame; the other frames are
  // captured.
  copyRecording(dir / "rec", dir / "gap");
  fs::remove(dir / "gap" / depth[1]);
  const test::RunResult gap = runSylva(dir, "capture " + at(dir, "gap") + " -q -o " + at(dir, "gap.json"));
  ASSERT_EQ(gap.status, 0) << gap.err;
  EXPECT_EQ(lineCount(gap.err), 1u) << gap.err;
  EXPECT_THAT(gap.err, testing::HasSubstr("warning: "));
  EXPECT_THAT(gap.err, testing::HasSubstr(depth[1]));
  EXPECT_THAT(gap.err, testing::HasSubstr("frame 1"));
  const nlohmann::json g = loadJsonFile(dir / "gap.json");
  ASSERT_FALSE(g["blades"].empty());
  EXPECT_EQ(g["blades"][0]["source"]["motionFrames"], 3);
}

} // namespace
} // namespace sylva
