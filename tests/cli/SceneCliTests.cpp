// `sylva render SCENE.json` as a user runs it: frame sequences that are deterministic (the same bytes
// whatever the split into shards or processes), resumable after a SIGKILL (no partial frame, the same frames
// as an uninterrupted run), GIF output, and one-line errors naming the file and JSON path for bad scene files
// and frame ranges, with no output written. They render, so they need a GL context (label gl).
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>

namespace sylva {
namespace {

namespace fs = std::filesystem;
using test::quote;
using test::readAll;
using test::runSylva;

const std::string kMeadow = std::string(SYLVA_SOURCE_DIR) + "/data/scenes/meadow.json";
// Small frames along the fly-over path: every frame differs (camera, wind, balls), each renders quickly.
const std::string kSequence = quote(kMeadow) + " --camera flyover --width 160 --height 90";

/** The documented frame file name: frame_ and five or more digits. */
std::string frameFile(int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%05d.png", frame);
  return name;
}

std::vector<std::string> frameFiles(const fs::path& dir) {
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

void expectSameFrames(const fs::path& expected, const fs::path& actual, int first, int last) {
  for (int f = first; f <= last; ++f) {
    const std::string name = frameFile(f);
    ASSERT_TRUE(fs::exists(actual / name)) << actual / name;
    EXPECT_TRUE(readAll(expected / name) == readAll(actual / name)) << name << " differs";
  }
}

TEST(SceneCli, SequencesAreDeterministicAcrossShardsAndProcesses) {
  test::TempDir dir;
  const test::RunResult full =
      runSylva(dir, "render " + kSequence + " --frames 0-3 --out " + test::at(dir, "full"));
  ASSERT_EQ(full.status, 0) << full.err;
  EXPECT_EQ(frameFiles(dir / "full"), (std::vector<std::string>{"frame_00000.png", "frame_00001.png",
                                                                "frame_00002.png", "frame_00003.png"}));
  // Consecutive frames differ (the path moves): the comparison below is not trivially true.
  EXPECT_FALSE(readAll(dir / "full" / "frame_00000.png") == readAll(dir / "full" / "frame_00003.png"));
  for (const char* shard : {"0/2", "1/2"}) {
    const test::RunResult r = runSylva(dir, "render " + kSequence + " --frames 0-3 --shard " + shard +
                                                " --out " + test::at(dir, "split"));
    ASSERT_EQ(r.status, 0) << r.err;
  }
  expectSameFrames(dir / "full", dir / "split", 0, 3);
  // One frame alone in a fresh process: the simulation steps through the earlier frames' times first.
  const test::RunResult alone =
      runSylva(dir, "render " + kSequence + " --frames 3-3 --out " + test::at(dir, "alone"));
  ASSERT_EQ(alone.status, 0) << alone.err;
  expectSameFrames(dir / "full", dir / "alone", 3, 3);
  // A second run over complete frames renders nothing and changes nothing.
  const auto before = fs::last_write_time(dir / "full" / "frame_00002.png");
  const test::RunResult again =
      runSylva(dir, "render " + kSequence + " --frames 0-3 --out " + test::at(dir, "full"));
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(fs::last_write_time(dir / "full" / "frame_00002.png"), before);
}

TEST(SceneCli, AKilledSequenceResumesToTheSameFrames) {
  test::TempDir dir;
  const test::RunResult full =
      runSylva(dir, "render " + kSequence + " --frames 0-5 --out " + test::at(dir, "full"));
  ASSERT_EQ(full.status, 0) << full.err;
  // Start the same sequence in the background and SIGKILL it once its second frame exists.
  const fs::path out = dir / "killed";
  const std::string command = quote(SYLVA_EXE) + " render " + kSequence + " --frames 0-5 --out " +
                              quote(out.string()) + " >/dev/null 2>&1 </dev/null & echo $!";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  int pid = 0;
  ASSERT_EQ(std::fscanf(pipe, "%d", &pid), 1);
  ::pclose(pipe);
  ASSERT_GT(pid, 0); // never kill(-1, ...)
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(out / "frame_00001.png") && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(fs::exists(out / "frame_00001.png")) << "the background render never wrote frame 1";
  ::kill(pid, SIGKILL);
  while (::kill(pid, 0) == 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  // Every frame file present after the kill is complete; unfinished ones are only temporaries.
  int complete = 0;
  for (const std::string& name : frameFiles(out)) {
    if (name.starts_with("frame_") && name.ends_with(".png")) {
      EXPECT_NO_THROW((void)loadImage(out / name)) << name << " is partial";
      ++complete;
    }
  }
  EXPECT_GE(complete, 2);
  EXPECT_LT(complete, 6) << "the run finished before the kill: the test proves nothing";
  const test::RunResult resumed =
      runSylva(dir, "render " + kSequence + " --frames 0-5 --out " + quote(out.string()));
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("already complete"), std::string::npos) << resumed.err;
  expectSameFrames(dir / "full", out, 0, 5);
  for (const std::string& name : frameFiles(out)) {
    EXPECT_TRUE(name.starts_with("frame_") && name.ends_with(".png")) << "left behind: " << name;
  }
}

TEST(SceneCli, EncodesTheSequenceAsGifAndMp4) {
  test::TempDir dir;
  const test::RunResult r =
      runSylva(dir, "render " + kSequence + " --frames 0-2 --out " + test::at(dir, "seq") + " --gif " +
                        test::at(dir, "seq.gif") + " --mp4 " + test::at(dir, "video/seq.mp4"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string gif = readAll(dir / "seq.gif");
  ASSERT_GT(gif.size(), 6u);
  EXPECT_EQ(gif.substr(0, 6), "GIF89a");
  // ISO base media: the first box is 'ftyp' (ffmpeg is installed by scripts/setup-debian.sh).
  const std::string mp4 = readAll(dir / "video" / "seq.mp4");
  ASSERT_GT(mp4.size(), 8u) << r.err;
  EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  EXPECT_FALSE(fs::exists(dir / "video" / "seq.mp4.tmp.mp4"));
  // With a shard of the range missing, nothing is encoded and the user is told why.
  const test::RunResult partial =
      runSylva(dir, "render " + kSequence + " --frames 0-3 --shard 0/2 --out " + test::at(dir, "half") +
                        " --gif " + test::at(dir, "half.gif"));
  ASSERT_EQ(partial.status, 0) << partial.err;
  EXPECT_NE(partial.err.find("not encoding"), std::string::npos) << partial.err;
  EXPECT_FALSE(fs::exists(dir / "half.gif"));
}

/** Writes `json` as a scene file next to the real data (relative paths resolve against data/scenes). */
fs::path writeScene(const test::TempDir& dir, const std::string& name, const std::string& json) {
  const fs::path path = dir / name;
  std::ofstream(path) << json;
  return path;
}

TEST(SceneCli, BenchCountsEveryPassesWork) {
  // `sylva bench scene` writes, beside each pass's times, the work it made the GPU do (pipeline statistics):
  // the figures that carry from llvmpipe to any GPU.
  test::TempDir dir;
  const fs::path report = dir / "bench.json";
  const test::RunResult r =
      runSylva(dir, "bench scene --scene " + quote(kMeadow) +
                        " --frames 1 --warmup 0 --width 160 --height 90 -o " + quote(report.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = loadJsonFile(report);
  std::map<std::string, nlohmann::json> counts;
  for (const nlohmann::json& pass : json.at("passes")) {
    counts[pass.at("pass").get<std::string>()] = pass.at("counts");
  }
  for (const char* pass : {"shadows", "terrain", "grass", "water", "sky"}) {
    ASSERT_TRUE(counts.contains(pass)) << pass;
    EXPECT_GT(counts[pass].at("fragment_invocations").get<long long>(), 0) << pass;
    EXPECT_GT(counts[pass].at("clipped_primitives").get<long long>(), 0) << pass;
  }
  // The sky is one triangle over the view: every pixel shaded once (helper invocations add a few at most).
  EXPECT_EQ(counts["sky"].at("primitives_submitted"), 1);
  const long long sky = counts["sky"].at("fragment_invocations").get<long long>();
  EXPECT_GE(sky, 160 * 90);
  EXPECT_LE(sky, 160 * 90 * 11 / 10);
  // The terrain is tessellated; the grass cull is compute only.
  EXPECT_GT(counts["terrain"].at("tess_evaluations").get<long long>(), 0);
  ASSERT_TRUE(counts.contains("grass cull"));
  EXPECT_GT(counts["grass cull"].at("compute_invocations").get<long long>(), 0);
  EXPECT_EQ(counts["grass cull"].at("fragment_invocations"), 0);
}

TEST(SceneCli, BadScenesAndRangesFailWithOneLineAndNoOutput) {
  test::TempDir dir;
  struct Case {
    std::string args;
    std::vector<std::string> expect; // substrings of the one-line error
  };
  const fs::path typo = writeScene(dir, "typo.json", R"({"sylva_scene": 1, "terrain": {"sead": 3},
    "cameras": {"main": {"position": {"at": [1, 2, 3]}, "target": {"at": [0, 0, 0]}}}})");
  const fs::path missing =
      writeScene(dir, "missing.json", R"({"sylva_scene": 1, "terrain": {"dem": "nope.tif"},
    "cameras": {"main": {"position": {"at": [1, 2, 3]}, "target": {"at": [0, 0, 0]}}}})");
  const fs::path absurd = writeScene(dir, "absurd.json", R"({"sylva_scene": 1,
    "forests": [{"species": {"almond": 1}, "count": 50000000}],
    "cameras": {"main": {"position": {"at": [1, 2, 3]}, "target": {"at": [0, 0, 0]}}}})");
  const fs::path newer = writeScene(dir, "newer.json", R"({"sylva_scene": 99})");
  const fs::path broken = writeScene(dir, "broken.json", "{\"sylva_scene\": 1,\n  \"terrain\": {,}}");
  const std::vector<Case> cases = {
      {quote(typo.string()), {"typo.json", "/terrain/sead", "seed"}},
      {quote(missing.string()), {"missing.json", "/terrain/dem", "nope.tif"}},
      {quote(absurd.string()), {"absurd.json", "/forests/0/count"}},
      {quote(newer.string()), {"newer.json", "newer"}},
      {quote(broken.string()), {"broken.json:2:"}},
      {kSequence + " --frames 0-5,3-8", {"--frames", "overlaps"}},
      {kSequence + " --frames 0-3 --shard 2/2", {"--shard"}},
      {quote(kMeadow) + " --camera nowhere", {"--camera", "nowhere"}},
  };
  for (const Case& c : cases) {
    const test::RunResult r = runSylva(dir, "render " + c.args + " --out " + test::at(dir, "out"));
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_EQ(test::lineCount(r.err), 1u) << c.args << "\n" << r.err;
    for (const std::string& s : c.expect) {
      EXPECT_NE(r.err.find(s), std::string::npos) << c.args << ": '" << s << "' not in: " << r.err;
    }
    EXPECT_FALSE(fs::exists(dir / "out")) << c.args << " wrote output";
  }
}

// `sylva scene check` lists every error of a file, one line each and a count, where render stops at the
// first; a valid scene is one "ok" line on stdout with what it holds.
TEST(SceneCli, CheckListsEveryErrorWithoutRendering) {
  test::TempDir dir;
  const fs::path two = writeScene(dir, "two.json", R"({"sylva_scene": 1, "terrain": {"sead": 3},
    "forests": [{"species": {"almond": 1}, "count": 50000000}],
    "cameras": {"main": {"position": {"at": [1, 2, 3]}, "target": {"at": [0, 0, 0]}}}})");
  const test::RunResult bad = runSylva(dir, "scene check " + quote(two.string()));
  EXPECT_EQ(bad.status, 2);
  EXPECT_EQ(test::lineCount(bad.err), 3u) << bad.err;
  EXPECT_NE(bad.err.find("two.json: /terrain/sead"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("two.json: /forests/0/count"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("2 errors in 1 of 1 scene file"), std::string::npos) << bad.err;
  const test::RunResult good = runSylva(dir, "scene check " + quote(kMeadow));
  EXPECT_EQ(good.status, 0) << good.err;
  EXPECT_NE(good.out.find("meadow.json: ok (terrain "), std::string::npos) << good.out;
  EXPECT_EQ(good.err, "");
}

// A lake without "folding" takes the data folder's wave swash (docs/scenes.md; it once failed with a message
// naming no file); a still whose --out is a directory is refused before the scene is built.
TEST(SceneCli, ALakeWithoutFoldingRendersAndOutputsAreCheckedFirst) {
  test::TempDir dir;
  const fs::path lake = writeScene(dir, "lake.json", R"({"sylva_scene": 1,
    "terrain": {"seed": 1, "size": 129, "spacing": 2.0, "relief": 40.0},
    "water": [{"level": 15.0}],
    "cameras": {"main": {"position": {"at": [200, 60, 200]}, "target": {"at": [128, 0, 128]}}},
    "output": {"camera": "main", "width": 96, "height": 54}})");
  const test::RunResult r =
      runSylva(dir, "render " + quote(lake.string()) + " --out " + test::at(dir, "lake.png"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "lake.png"));
  const test::RunResult d =
      runSylva(dir, "render " + quote(kMeadow) + " --out " + quote(dir.path().string()));
  EXPECT_EQ(d.status, 2) << d.err;
  EXPECT_EQ(test::lineCount(d.err), 1u) << d.err;
  EXPECT_NE(d.err.find("--out " + dir.path().string() + ": is a directory"), std::string::npos) << d.err;
}

// A forest asking for more trees than its spacing and region leave room for warns with the numbers (it once
// said so only at info level).
TEST(SceneCli, AForestThatDoesNotFitSaysHowManyTreesItPlaced) {
  test::TempDir dir;
  const fs::path crowded = writeScene(dir, "crowded.json", R"({"sylva_scene": 1,
    "terrain": {"seed": 1, "size": 129, "spacing": 2.0, "relief": 10.0},
    "forests": [{"species": {"almond": 1}, "count": 500, "spacing": 5.0, "max_slope": 60.0,
                 "region": {"centre": [128.0, 128.0], "radius": 20.0}}],
    "cameras": {"main": {"position": {"at": [160, 40, 160]}, "target": {"at": [128, 0, 128]}}},
    "output": {"camera": "main", "width": 64, "height": 36}})");
  const test::RunResult r =
      runSylva(dir, "render " + quote(crowded.string()) + " --out " + test::at(dir, "crowded.png"));
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("/forests/0/count: 500 trees asked, "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("warn"), std::string::npos) << r.err;
}

} // namespace
} // namespace sylva
