// `sylva fold` as a user runs it: synth writes the documented files; render writes PNG frames, an animated
// GIF (read back with giflib), a sprite sheet whose JSON rectangles fit its PNG, and video through an
// `ffmpeg` found on PATH (a fake one here proves the pipe and the rename; none gives the one-line message);
// bad projects fail with one line naming the file and the field and leave no files. Projects and their image
// are written by each test into its own directory.
#include "CliRun.hpp"
#include "ExternalData.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <fmt/format.h>
#include <gif_lib.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva {
namespace {

using test::lineCount;
using test::runSylva;

namespace fs = std::filesystem;
using test::quote;
using test::readAll;

constexpr int kWidth = 72;
constexpr int kHeight = 56;

/** `sylva <args>` with PATH set to `path` (so which ffmpeg it finds, if any, is the test's choice). */
test::RunResult runWithPath(const test::TempDir& dir, const std::string& path, const std::string& args) {
  return test::runProgram("/usr/bin/env", dir.path(),
                          quote("PATH=" + path) + " " + quote(SYLVA_EXE) + " " + args);
}

/** Every entry under `root` (files and directories), none if it does not exist. */
std::vector<fs::path> entriesUnder(const fs::path& root) {
  std::vector<fs::path> entries;
  if (fs::exists(root)) {
    for (const auto& e : fs::recursive_directory_iterator(root)) {
      entries.push_back(e.path());
    }
  }
  return entries;
}

/** A kWidth×kHeight RGBA picture with structure everywhere (gradients and a checker), saved as `name`. */
void writePicture(const test::TempDir& dir, const std::string& name) {
  Image image(kWidth, kHeight, 4, PixelType::U8);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      image.set(x, y, 0, static_cast<float>(x) / (kWidth - 1));
      image.set(x, y, 1, static_cast<float>(y) / (kHeight - 1));
      image.set(x, y, 2, ((x / 6) + (y / 6)) % 2 == 0 ? 0.9f : 0.1f);
      image.set(x, y, 3, 1.0f);
    }
  }
  saveImage(dir / name, image);
}

/** A valid project over pic.png: one zone moving down with a fold polygon, a 1 s piecewise blink. */
nlohmann::json project() {
  return nlohmann::json::parse(R"({
    "format": "sylva-fold", "version": 1, "seed": 7,
    "atlas": {"gutter_px": 4, "images": [{"id": "pic", "file": "pic.png"}]},
    "profiles": [{"id": "blink", "period_s": 1.0, "shift": 0.0,
                  "fn": {"type": "piecewise", "knots": [[0, 0], [0.4, 1], [0.6, 1], [1, 0]]}}],
    "zones": [{"id": "lid", "image": "pic",
               "shape": {"type": "polygon", "pts": [[10, 8], [60, 10], [62, 46], [12, 44]]},
               "profile": "blink", "interp": {"type": "modified_shepard", "R": 24},
               "tools": [{"type": "translate", "v": [0, 5]},
                         {"type": "points", "pairs": [[[30, 20], [30, 27]]]}],
               "folding": {"type": "polygon", "pts": [[20, 18], [50, 18], [50, 32], [20, 32]]}}]
  })");
}

/** Writes pic.png and `json` as `name` into `dir`; returns the project path. */
fs::path writeProject(const test::TempDir& dir, const nlohmann::json& json,
                      const std::string& name = "p.json") {
  writePicture(dir, "pic.png");
  writeTextFile(dir / name, json.dump(2));
  return dir / name;
}

/** A GIF read back with giflib (image count, screen size, whether the NETSCAPE loop block is there). */
struct GifInfo {
  bool ok = false;
  int images = 0;
  int width = 0;
  int height = 0;
  bool loops = false;
  int delayCs = -1;
};

GifInfo readGif(const fs::path& path) {
  GifInfo info;
  int error = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &error);
  if (gif == nullptr) {
    return info;
  }
  if (DGifSlurp(gif) == GIF_OK) {
    info.ok = true;
    info.images = gif->ImageCount;
    info.width = gif->SWidth;
    info.height = gif->SHeight;
    for (int i = 0; i < gif->ImageCount; ++i) {
      const SavedImage& image = gif->SavedImages[i];
      for (int e = 0; e < image.ExtensionBlockCount; ++e) {
        const ExtensionBlock& block = image.ExtensionBlocks[e];
        if (block.Function == APPLICATION_EXT_FUNC_CODE && block.ByteCount == 11 &&
            std::memcmp(block.Bytes, "NETSCAPE2.0", 11) == 0) {
          info.loops = true;
        }
      }
      GraphicsControlBlock gcb;
      if (i == 0 && DGifSavedExtensionToGCB(gif, 0, &gcb) == GIF_OK) {
        info.delayCs = gcb.DelayTime;
      }
    }
  }
  DGifCloseFile(gif, &error);
  return info;
}

TEST(CliFold, HelpListsTheSubcommands) {
  const test::TempDir dir;
  const test::RunResult r = runSylva(dir, "fold --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* sub : {"synth", "render", "view", "export-shader", "info"}) {
    EXPECT_NE(r.out.find(sub), std::string::npos) << sub << " missing from\n" << r.out;
  }
  const test::RunResult top = runSylva(dir, "--help");
  EXPECT_NE(top.out.find("fold"), std::string::npos);
}

TEST(CliFold, SynthWritesTheDocumentedFiles) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path out = dir / "out";
  const test::RunResult r =
      runSylva(dir, "fold synth " + quote(file.string()) + " -o " + quote(out.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("anchors"), std::string::npos) << r.out;
  for (const char* name :
       {"color.png", "init.png", "jump.png", "folding.json", "vectors.png", "t0.png", "t1.png"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  const Image color = loadImage(out / "color.png");
  const Image init = loadImage(out / "init.png");
  const Image jump = loadImage(out / "jump.png");
  EXPECT_EQ(init.type(), PixelType::U16);
  EXPECT_EQ(jump.type(), PixelType::U16);
  EXPECT_EQ(init.channels(), 4);
  EXPECT_EQ(init.width(), color.width());
  EXPECT_EQ(init.height(), color.height());
  EXPECT_EQ(jump.width(), color.width());
  // The canvas is never cropped: the atlas holds at least the whole picture.
  EXPECT_GE(color.width(), kWidth);
  EXPECT_GE(color.height(), kHeight);
  const nlohmann::json info = loadJsonFile(out / "folding.json");
  EXPECT_EQ(info.at("format"), "sylva-fold-textures");
  EXPECT_GT(info.at("jump_max_px").get<double>(), 0.0);
  // No temporaries left behind.
  for (const fs::path& p : entriesUnder(out)) {
    EXPECT_EQ(p.filename().string().find(".tmp."), std::string::npos) << p;
  }
}

TEST(CliFold, RenderWritesAGifThatGiflibReadsBack) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path gif = dir / "out" / "anim.gif";
  const test::RunResult r = runSylva(dir, "fold render " + quote(file.string()) +
                                              " --frames 6 --fps 20 --gif " + quote(gif.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(readAll(gif).substr(0, 6), "GIF89a");
  const GifInfo info = readGif(gif);
  ASSERT_TRUE(info.ok);
  EXPECT_EQ(info.images, 6);
  EXPECT_EQ(info.width, kWidth);
  EXPECT_EQ(info.height, kHeight);
  EXPECT_TRUE(info.loops);
  EXPECT_EQ(info.delayCs, 5); // 20 fps
  // Only the GIF was asked for: no frames directory.
  EXPECT_EQ(entriesUnder(dir / "out").size(), 1u);
  // Deterministic: the same project gives the same bytes.
  const fs::path again = dir / "out" / "again.gif";
  ASSERT_EQ(runSylva(dir, "fold render " + quote(file.string()) + " --frames 6 --fps 20 --gif " +
                              quote(again.string()))
                .status,
            0);
  EXPECT_EQ(readAll(gif), readAll(again));
}

TEST(CliFold, SpriteSheetRectanglesMatchThePng) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path sheet = dir / "out" / "sheet.png";
  const test::RunResult r =
      runSylva(dir, "fold render " + quote(file.string()) + " --frames 7 --fps 10 --columns 3 --sprites " +
                        quote(sheet.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const Image png = loadImage(sheet);
  EXPECT_EQ(png.width(), 3 * kWidth);
  EXPECT_EQ(png.height(), 3 * kHeight);
  const nlohmann::json json = loadJsonFile(dir / "out" / "sheet.json");
  EXPECT_EQ(json.at("columns").get<int>(), 3);
  EXPECT_DOUBLE_EQ(json.at("fps").get<double>(), 10.0);
  EXPECT_EQ(json.at("image").get<std::string>(), "sheet.png");
  const nlohmann::json& frames = json.at("frames");
  ASSERT_EQ(frames.size(), 7u);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const nlohmann::json& f = frames[i];
    EXPECT_EQ(f.at("index").get<std::size_t>(), i);
    const int x = f.at("x").get<int>();
    const int y = f.at("y").get<int>();
    EXPECT_EQ(f.at("w").get<int>(), kWidth);
    EXPECT_EQ(f.at("h").get<int>(), kHeight);
    EXPECT_GE(x, 0);
    EXPECT_GE(y, 0);
    EXPECT_LE(x + kWidth, png.width());
    EXPECT_LE(y + kHeight, png.height());
    EXPECT_NEAR(f.at("t").get<double>(), static_cast<double>(i) / 10.0, 1e-12);
  }
}

TEST(CliFold, PngSequenceHasOneFilePerFrame) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path frames = dir / "frames";
  const test::RunResult r =
      runSylva(dir, "fold render " + quote(file.string()) + " --frames 5 -o " + quote(frames.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<fs::path> files = entriesUnder(frames);
  ASSERT_EQ(files.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    const fs::path f = frames / fmt::format("frame_{:04}.png", i);
    ASSERT_TRUE(fs::exists(f)) << f;
    const Image image = loadImage(f);
    EXPECT_EQ(image.width(), kWidth);
    EXPECT_EQ(image.height(), kHeight);
  }
  // The s = 0 frame (t = 0, piecewise p(0) = 0) is the input picture.
  EXPECT_EQ(loadImage(frames / "frame_0000.png").converted(PixelType::U8),
            loadImage(dir / "pic.png").converted(PixelType::U8));
}

// Profiles of different periods loop together only at a common multiple: 0.3 s and 0.4 s are back at their
// start after 1.2 s (12 frames at 10 fps, where the longest period would cut the 0.3 s zone mid-cycle and the
// loop would jump); periods with no common multiple within the limits render the longest period and warn.
TEST(CliFold, MixedPeriodsLoopAtTheirCommonMultipleOrWarn) {
  const test::TempDir dir;
  for (const auto& [second, frames, warns] : {std::tuple{0.4, 12u, false}, std::tuple{0.41, 4u, true}}) {
    nlohmann::json json = project();
    json["profiles"][0]["period_s"] = 0.3;
    json["profiles"].push_back(json["profiles"][0]);
    json["profiles"][1]["id"] = "slow";
    json["profiles"][1]["period_s"] = second;
    json["zones"].push_back(json["zones"][0]);
    json["zones"][1]["id"] = "other";
    json["zones"][1]["profile"] = "slow";
    json["zones"][1]["shape"]["pts"] = {{2, 2}, {9, 2}, {9, 9}, {2, 9}};
    json["zones"][1].erase("folding");
    json["zones"][1]["tools"] = {{{"type", "translate"}, {"v", {1, 0}}}};
    const fs::path file = writeProject(dir, json, fmt::format("mixed-{}.json", second));
    const fs::path out = dir / fmt::format("frames-{}", second);
    const test::RunResult r =
        runSylva(dir, "fold render " + quote(file.string()) + " --fps 10 -o " + quote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(entriesUnder(out).size(), frames) << second;
    EXPECT_EQ(r.err.find("loop jumps") != std::string::npos, warns) << r.err;
    if (warns) {
      EXPECT_EQ(lineCount(r.err), 1u) << r.err;
      EXPECT_NE(r.err.find("--duration"), std::string::npos) << r.err;
      EXPECT_NE(r.err.find(file.filename().string()), std::string::npos) << r.err;
    }
  }
}

// The project example of docs/folding.md, on the photo it names: it synthesises and moves, and its settings
// do not cancel its own translate (the example once combined zone_boundary zero anchors with R beyond the
// zone's depth); the same zone with R = 40 gets the warning naming the zone and the fix.
TEST(CliFold, TheDocumentedExampleMovesAndATranslateItCancelsWarns) {
  const fs::path photo = test::externalData("chelsea.png");
  SYLVA_REQUIRE_EXTERNAL_DATA(photo);
  const test::TempDir dir;
  const std::string docs = readTextFile(test::sourcePath("docs/folding.md"));
  const std::size_t begin = docs.find("```json\n{\"format\": \"sylva-fold\"");
  ASSERT_NE(begin, std::string::npos);
  const std::size_t end = docs.find("```", begin + 7);
  nlohmann::json example = nlohmann::json::parse(docs.substr(begin + 7, end - begin - 7));
  example["atlas"]["images"][0]["file"] = photo.string();
  for (const double radius : {0.0, 40.0}) {
    nlohmann::json json = example;
    if (radius > 0.0) {
      json["zones"][0]["interp"]["R"] = radius;
    }
    writeTextFile(dir / "example.json", json.dump());
    const test::RunResult r = runSylva(dir, "fold synth " + quote((dir / "example.json").string()) + " -o " +
                                                quote((dir / "syn").string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_THAT(r.out, testing::Not(testing::HasSubstr("jumpMax 0.000")));
    if (radius > 0.0) {
      EXPECT_EQ(lineCount(r.err), 1u) << r.err;
      EXPECT_THAT(r.err,
                  testing::HasSubstr("example.json: /zones/0 ('eyeL'): its zone_boundary zero anchors"));
      EXPECT_THAT(r.err, testing::HasSubstr("give R below"));
    } else {
      EXPECT_EQ(r.err, "") << "the documented example warns";
    }
  }
}

TEST(CliFold, VideoWithoutFfmpegIsOneClearLineAndNoFile) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  fs::create_directories(dir / "empty-bin");
  const fs::path mp4 = dir / "out" / "anim.mp4";
  const test::RunResult r =
      runWithPath(dir, (dir / "empty-bin").string(),
                  "fold render " + quote(file.string()) + " --frames 3 --mp4 " + quote(mp4.string()) +
                      " --gif " + quote((dir / "out" / "a.gif").string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err, "sylva: error: ffmpeg not found on PATH: install it (apt install ffmpeg) or write "
                   "--gif/--sprites/--frames instead\n");
  EXPECT_TRUE(entriesUnder(dir / "out").empty());
}

/** Writes an executable `ffmpeg` shell script with `body` into `dir`/bin; returns a PATH with it first. */
std::string fakeFfmpeg(const test::TempDir& dir, const std::string& body) {
  const fs::path bin = dir / "bin";
  fs::create_directories(bin);
  writeTextFile(bin / "ffmpeg", "#!/bin/sh\n" + body);
  fs::permissions(bin / "ffmpeg", fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec);
  return bin.string() + ":/usr/bin:/bin";
}

TEST(CliFold, VideoPipesRawFramesToFfmpegAndRenamesItsOutput) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  // Writes its arguments and the number of bytes it read from stdin into its output (the last argument).
  const std::string path = fakeFfmpeg(dir, "for a in \"$@\"; do last=\"$a\"; done\n"
                                           "{ echo \"$*\"; wc -c | tr -d ' '; } > \"$last\"\n");
  const fs::path mp4 = dir / "out" / "anim.mp4";
  const fs::path webm = dir / "out" / "anim.webm";
  const test::RunResult r =
      runWithPath(dir, path,
                  "fold render " + quote(file.string()) + " --frames 4 --fps 12 --mp4 " +
                      quote(mp4.string()) + " --webm " + quote(webm.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string expectedBytes = std::to_string(4 * kWidth * kHeight * 4);
  const std::string mp4Text = readAll(mp4);
  EXPECT_NE(mp4Text.find("-f rawvideo -pix_fmt rgba -s 72x56 -r 12 -i pipe:0"), std::string::npos) << mp4Text;
  EXPECT_NE(mp4Text.find("libx264"), std::string::npos) << mp4Text;
  EXPECT_NE(mp4Text.find("yuv420p"), std::string::npos) << mp4Text;
  EXPECT_NE(mp4Text.find("\n" + expectedBytes + "\n"), std::string::npos) << mp4Text;
  const std::string webmText = readAll(webm);
  EXPECT_NE(webmText.find("libvpx-vp9"), std::string::npos) << webmText;
  EXPECT_NE(webmText.find("\n" + expectedBytes + "\n"), std::string::npos) << webmText;
  // ffmpeg wrote a temporary name; only the renamed results remain.
  EXPECT_EQ(entriesUnder(dir / "out").size(), 2u);
}

TEST(CliFold, RealFfmpegWritesPlayableVideos) {
  // ffmpeg is optional at run time and not installed on CI; where it is, the encodes must really decode.
  if (std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "ffmpeg/ffprobe not installed";
  }
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path mp4 = dir / "anim.mp4";
  const fs::path webm = dir / "anim.webm";
  const test::RunResult r =
      runSylva(dir, "fold render " + quote(file.string()) + " --frames 6 --fps 12 --mp4 " +
                        quote(mp4.string()) + " --webm " + quote(webm.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const fs::path& video : {mp4, webm}) {
    const test::RunResult probe = test::runProgram("ffprobe", dir.path(),
                                                   "-v error -count_frames -select_streams v:0 -show_entries "
                                                   "stream=width,height,nb_read_frames -of csv=p=0 " +
                                                       quote(video.string()));
    ASSERT_EQ(probe.status, 0) << probe.err;
    EXPECT_EQ(probe.out, "72,56,6\n") << video;
  }
}

TEST(CliFold, TemplateAnimatesAZoneAndWritesAProjectThatSynthesises) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path out = dir / "sub" / "blink.json";
  fs::create_directories(out.parent_path());
  const nlohmann::json original = nlohmann::json::parse(readAll(file));
  const std::string zone = original["zones"][0]["id"].get<std::string>();
  const test::RunResult r = runSylva(dir, "fold template " + quote(file.string()) + " --zone " + zone +
                                              " --template blink --period 3 -o " + quote(out.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json edited = nlohmann::json::parse(readAll(out));
  EXPECT_EQ(edited["zones"][0]["profile"], "blink");
  EXPECT_EQ(edited["profiles"].back()["id"], "blink");
  EXPECT_EQ(edited["profiles"].back()["period_s"], 3.0);
  EXPECT_EQ(nlohmann::json::parse(readAll(file)), original) << "with -o the input stays as it was";
  // The written project still finds its image from its new directory.
  const test::RunResult synth =
      runSylva(dir, "fold synth " + quote(out.string()) + " -o " + quote((dir / "t").string()));
  EXPECT_EQ(synth.status, 0) << synth.err;
  const test::RunResult bad =
      runSylva(dir, "fold template " + quote(file.string()) + " --zone nope --template blink");
  EXPECT_EQ(bad.status, 2);
  EXPECT_THAT(bad.err, ::testing::HasSubstr("--zone: " + file.string() + " has no zone 'nope'"));
  // Bare file names, run where the project is (they once crashed: "cannot make absolute path").
  ASSERT_EQ(file.parent_path(), dir.path());
  const test::RunResult bare = test::runSylvaFrom(dir.path(), dir,
                                                  "fold template " + quote(file.filename().string()) +
                                                      " --zone " + zone + " --template blink -o bare.json");
  ASSERT_EQ(bare.status, 0) << bare.err;
  EXPECT_EQ(nlohmann::json::parse(readAll(dir / "bare.json"))["atlas"]["images"][0]["file"], "pic.png");
  const test::RunResult bareSynth =
      test::runSylvaFrom(dir.path(), dir, "fold synth bare.json -o " + quote((dir / "t2").string()));
  EXPECT_EQ(bareSynth.status, 0) << bareSynth.err;
}

TEST(CliFold, FfmpegFailureIsOneLineAndLeavesNothing) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const std::string path = fakeFfmpeg(dir, "head -c 100 >/dev/null\n"
                                           "echo 'frame=    0 fps=0.0' >&2\n"
                                           "echo \"Unknown encoder 'libx264'\" >&2\n"
                                           "exit 1\n");
  const fs::path mp4 = dir / "out" / "anim.mp4";
  const test::RunResult r = runWithPath(
      dir, path, "fold render " + quote(file.string()) + " --frames 3 --mp4 " + quote(mp4.string()));
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("ffmpeg failed (exit 1): Unknown encoder 'libx264'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("anim.mp4"), std::string::npos) << r.err;
  EXPECT_TRUE(entriesUnder(dir / "out").empty());
}

struct BadCase {
  const char* name;
  /** Changes the valid project (or replaces the file's text when `text` is set). */
  void (*edit)(nlohmann::json&);
  const char* text;
  /** Substrings the one-line error must hold besides the file name. */
  std::vector<std::string> expect;
};

TEST(CliFold, BadProjectsFailWithOneLineNamingFileAndField) {
  const std::vector<BadCase> cases = {
      {"invalid JSON", nullptr, "{\"format\": \"sylva-fold\", \"version\": 1,,}", {}},
      {"missing image",
       [](nlohmann::json& j) { j["atlas"]["images"][0]["file"] = "missing.png"; },
       nullptr,
       {"/atlas/images/0/file", "missing.png"}},
      {"zone outside the image",
       [](nlohmann::json& j) {
         j["zones"][0]["shape"]["pts"][2] = {400, 46};
       },
       nullptr,
       {"/zones/0"}},
      // The JSON reader itself refuses the overflow, naming the number and the field it was for.
      {"infinite number", nullptr, nullptr, {"1e999", "(in /profiles/0/period_s)"}},
      {"NaN", nullptr, R"({"format": "sylva-fold", "version": 1, "seed": NaN})", {"no NaN", "(in /seed)"}},
      // A 33-byte PNG claiming 20000x20000 pixels is refused from its header, before any decoding.
      {"huge image",
       [](nlohmann::json& j) { j["atlas"]["images"][0]["file"] = "huge.png"; },
       nullptr,
       {"/atlas/images/0/file", "20000×20000", "16384"}},
      {"unknown field", [](nlohmann::json& j) { j["zones"][0]["colour"] = "red"; }, nullptr, {"colour"}},
      {"newer version", [](nlohmann::json& j) { j["version"] = 2; }, nullptr, {"version", "newer"}},
      {"unknown profile",
       [](nlohmann::json& j) { j["zones"][0]["profile"] = "wink"; },
       nullptr,
       {"/zones/0/profile", "wink"}},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.name);
    const test::TempDir dir;
    writePicture(dir, "pic.png");
    writeTextFile(dir / "huge.png",
                  std::string("\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR\x00\x00\x4e\x20\x00\x00\x4e"
                              "\x20\x08\x06\x00\x00\x00\xe3\x70\x46\x39",
                              33));
    std::string text;
    if (c.text != nullptr) {
      text = c.text;
    } else if (c.edit != nullptr) {
      nlohmann::json j = project();
      c.edit(j);
      text = j.dump(2);
    } else {
      // NaN/inf cannot be written by nlohmann; 1e999 overflows to infinity when read.
      text = project().dump(2);
      const std::string key = "\"period_s\": 1.0";
      ASSERT_NE(text.find(key), std::string::npos);
      text.replace(text.find(key), key.size(), "\"period_s\": 1e999");
    }
    writeTextFile(dir / "bad.json", text);
    const fs::path out = dir / "out";
    for (const std::string& args :
         {"fold synth " + quote((dir / "bad.json").string()) + " -o " + quote(out.string()),
          "fold render " + quote((dir / "bad.json").string()) + " --frames 2 --gif " +
              quote((out / "a.gif").string()) + " -o " + quote((out / "frames").string()),
          "fold info " + quote((dir / "bad.json").string())}) {
      const test::RunResult r = runSylva(dir, args);
      EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
      EXPECT_EQ(lineCount(r.err), 1u) << r.err;
      EXPECT_EQ(r.err.rfind("sylva: error: ", 0), 0u) << r.err;
      EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
      for (const std::string& e : c.expect) {
        EXPECT_NE(r.err.find(e), std::string::npos) << "expected '" << e << "' in: " << r.err;
      }
      EXPECT_TRUE(entriesUnder(out).empty()) << args;
    }
  }
}

TEST(CliFold, BadOptionsFailBeforeAnyWork) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path out = dir / "out";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--image nope --gif " + quote((out / "a.gif").string()), "--image"},
      {"--gif " + quote((out / "a.png").string()), "--gif"},
      {"--sprites " + quote((out / "s.jpg").string()), "--sprites"},
      {"--function wobble --gif " + quote((out / "a.gif").string()), "--function"},
  };
  for (const auto& [args, expect] : cases) {
    const test::RunResult r = runSylva(dir, "fold render " + quote(file.string()) + " " + args);
    EXPECT_EQ(r.status, 2) << args;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_TRUE(entriesUnder(out).empty()) << args;
  }
}

TEST(CliFold, InfoDescribesTheProject) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const test::RunResult text = runSylva(dir, "fold info " + quote(file.string()));
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("lid"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("blink"), std::string::npos) << text.out;
  const test::RunResult json = runSylva(dir, "fold info --json " + quote(file.string()));
  ASSERT_EQ(json.status, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j.at("project").at("zones").size(), 1u);
  EXPECT_EQ(j.at("atlas").at("images").at(0).at("size"), nlohmann::json({kWidth, kHeight}));
}

/** Largest per-channel difference of two same-sized images, in 8-bit steps (−1 if the sizes differ). */
int maxDifference(const Image& a, const Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() != b.channels()) {
    return -1;
  }
  int worst = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      for (int c = 0; c < a.channels(); ++c) {
        worst = std::max(worst,
                         static_cast<int>(std::lround(255.0f * std::abs(a.get(x, y, c) - b.get(x, y, c)))));
      }
    }
  }
  return worst;
}

TEST(CliFold, GlRendererFramesMatchTheCpuReference) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const test::RunResult gl =
      runSylva(dir, "fold render " + quote(file.string()) + " --frames 6 --fps 8 --renderer gl -o " +
                        quote((dir / "gl").string()));
  if (gl.status != 0 && gl.err.find("EGL") != std::string::npos) {
    GTEST_SKIP() << "no headless GL context: " << gl.err;
  }
  ASSERT_EQ(gl.status, 0) << gl.err;
  const test::RunResult cpu = runSylva(dir, "fold render " + quote(file.string()) +
                                                " --frames 6 --fps 8 -o " + quote((dir / "cpu").string()));
  ASSERT_EQ(cpu.status, 0) << cpu.err;
  for (int i = 0; i < 6; ++i) {
    const std::string name = fmt::format("frame_{:04}.png", i);
    // The spec's CPU/GPU tolerance: float evaluation order and bilinear weights differ by rounding only.
    EXPECT_LE(maxDifference(loadImage(dir / "gl" / name), loadImage(dir / "cpu" / name)), 2) << name;
  }
}

TEST(CliFold, ExportShaderWritesGlslTexturesAndReadme) {
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path out = dir / "game";
  const test::RunResult r =
      runSylva(dir, "fold export-shader " + quote(file.string()) + " -o " + quote(out.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* name :
       {"folding.glsl", "README.md", "color.png", "init.png", "jump.png", "folding.json"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  const std::string glsl = readAll(out / "folding.glsl");
  EXPECT_NE(glsl.find("foldingSample"), std::string::npos);
  EXPECT_NE(glsl.find("folding_phase"), std::string::npos);
}

TEST(CliFold, ViewOpensAWindowAndSavesAScreenshot) {
  if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr) {
    GTEST_SKIP() << "no display (set DISPLAY or run under xvfb-run); fold view test skipped";
  }
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  const fs::path shot = dir / "view.png";
  const test::RunResult r =
      runSylva(dir, "fold view " + quote(file.string()) + " --frames 5 --fixed-step 0.1 --screenshot " +
                        quote(shot.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const Image image = loadImage(shot);
  EXPECT_GE(image.width(), kWidth);
  EXPECT_GE(image.height(), kHeight);
}

// At --zoom 1 the viewer's canvas shows every texel of the frame once, centred on whole pixels: the window's
// pixels there are the GL renderer's frame at the same time (`fold render --renderer gl`), exactly. At --zoom
// 8 each texel is an 8×8 block of its colour (nearest magnification from 4×), compared at the block centres.
TEST(CliFold, ViewShowsTheRenderedFrameTexelForTexelOnItsCanvas) {
  if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr) {
    GTEST_SKIP() << "no display (set DISPLAY or run under xvfb-run); fold view test skipped";
  }
  const test::TempDir dir;
  const fs::path file = writeProject(dir, project());
  // The viewer's first frame shows t = one fixed step; frame 3 at 10 fps is t = 0.3 s.
  const test::RunResult frames =
      runSylva(dir, "fold render " + quote(file.string()) + " --renderer gl --fps 10 --frames 4 --out " +
                        quote((dir / "frames").string()));
  ASSERT_EQ(frames.status, 0) << frames.err;
  const Image expected = loadImage(dir / "frames" / "frame_0003.png").converted(PixelType::U8);
  ASSERT_EQ(expected.width(), kWidth);
  ASSERT_EQ(expected.height(), kHeight);
  for (const int zoom : {1, 8}) {
    const fs::path shot = dir / fmt::format("view{}.png", zoom);
    const test::RunResult r = runSylva(
        dir, fmt::format("fold view {} --zoom {} --no-ui --frames 1 --fixed-step 0.3 --screenshot {}",
                         quote(file.string()), zoom, quote(shot.string())));
    ASSERT_EQ(r.status, 0) << r.err;
    const Image window = loadImage(shot).converted(PixelType::U8);
    // The canvas centres the image, its corner rounded to a whole pixel.
    const int x0 = static_cast<int>(std::lround(window.width() / 2.0 - zoom * kWidth / 2.0));
    const int y0 = static_cast<int>(std::lround(window.height() / 2.0 - zoom * kHeight / 2.0));
    ASSERT_GE(x0, 0);
    ASSERT_GE(y0, 0);
    ASSERT_LE(x0 + zoom * kWidth, window.width());
    ASSERT_LE(y0 + zoom * kHeight, window.height());
    int worst = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        for (int c = 0; c < 3; ++c) {
          const float shown = window.get(x0 + x * zoom + zoom / 2, y0 + y * zoom + zoom / 2, c);
          worst = std::max(worst,
                           static_cast<int>(std::lround(255.0f * std::abs(shown - expected.get(x, y, c)))));
        }
      }
    }
    EXPECT_EQ(worst, 0) << "zoom " << zoom << ": the canvas does not show the frame texel for texel";
    // Outside the image: the canvas's background.
    EXPECT_LT(window.get(x0 / 2, y0 / 2, 0), 0.2f);
  }
}

} // namespace
} // namespace sylva
