// fakenect recordings: the frame file formats, INDEX.txt parsing, missing and corrupt files, and the writer's
// all-or-nothing folders.
#include <sylva/capture/Fakenect.hpp>
#include <sylva/core/Error.hpp>

#include "CliRun.hpp"
#include "TempDir.hpp"

#include "CaptureTestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace sylva::capture {
namespace {

using testutil::contains;
using testutil::errorOf;

namespace fs = std::filesystem;

std::vector<std::byte> bytesOf(const std::string& text) {
  std::vector<std::byte> bytes(text.size());
  // memcpy with a null pointer is undefined even for zero bytes (UBSan), and an empty vector has one.
  if (!text.empty()) {
    std::memcpy(bytes.data(), text.data(), text.size());
  }
  return bytes;
}

void writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary).write(text.data(), static_cast<std::streamsize>(text.size()));
}

/** A 640×480 raw frame with a pattern per frame number, covering 0..1084, 2047 and out-of-range raws. */
RawDepth pattern(int n) {
  RawDepth raw;
  raw.width = 640;
  raw.height = 480;
  raw.raw.resize(640 * 480);
  for (int y = 0; y < 480; ++y) {
    for (int x = 0; x < 640; ++x) {
      const int i = y * 640 + x;
      raw.raw[static_cast<std::size_t>(i)] = static_cast<std::uint16_t>(
          (x + y) % 97 == 0 ? 2047 : (x * 7 + y * 13 + n * 101) % (x % 50 == 0 ? 2048 : 1085));
    }
  }
  return raw;
}

Image rgbPattern(int n) {
  Image image(640, 480, 3, PixelType::U8);
  auto v = image.values<std::uint8_t>();
  for (std::size_t i = 0; i < v.size(); ++i) {
    v[i] = static_cast<std::uint8_t>(i * 3 + static_cast<std::size_t>(n) * 17);
  }
  return image;
}

std::vector<std::string> indexLines(const fs::path& folder) {
  std::vector<std::string> lines;
  std::ifstream in(folder / "INDEX.txt");
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> folderNames(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(FakenectDecode, DepthIsLittleEndianAfterAOneLineHeader) {
  const std::string file =
      std::string("P5 3 2 65535\n") + std::string("\x01\x00\xff\x07\x00\x00\x34\x12\xff\xff\x2a\x00", 12);
  const RawDepth raw = decodeFakenectDepth(bytesOf(file), "x.pgm");
  EXPECT_EQ(raw.width, 3);
  EXPECT_EQ(raw.height, 2);
  EXPECT_EQ(raw.raw, (std::vector<std::uint16_t>{1, 2047, 0, 0x1234, 0xffff, 42}));
  const DepthFrame frame = depthFromKinectRaw(raw);
  EXPECT_FLOAT_EQ(frame.at(0, 0), kinectRawToMetres(1));
  EXPECT_EQ(frame.at(1, 0), 0.0f);
  EXPECT_EQ(frame.at(1, 1), 0.0f);
  EXPECT_EQ(frame.intrinsics, CameraIntrinsics::kinectV1Scaled(3, 2));
}

TEST(FakenectDecode, MalformedDepthFilesNameTheFile) {
  const auto error = [](const std::string& file) {
    return errorOf([&] { (void)decodeFakenectDepth(bytesOf(file), "d.pgm"); });
  };
  EXPECT_TRUE(contains(error("P6 1 1 65535\n\x01\x02"), "d.pgm: not a fakenect depth frame"));
  EXPECT_TRUE(contains(error("P5 1 1 65535"), "d.pgm: not a fakenect depth frame"));
  EXPECT_TRUE(contains(error(""), "d.pgm: "));
  EXPECT_TRUE(contains(error("P5 1 1 255\n\x01"), "maximum value must be 65535"));
  EXPECT_TRUE(contains(error("P5 x 1 65535\n\x01\x02"), "d.pgm: malformed depth frame header"));
  EXPECT_TRUE(
      contains(error("P5 2 2 65535\n\x01\x02\x03"), "d.pgm: truncated depth data: 3 of 8 bytes for 2x2"));
  EXPECT_TRUE(contains(error("P5 1 1 65535\n\x01\x02\x03"), "1 bytes after the 1x1 depth data"));
  // Absurd sizes fail on the header, before anything is allocated.
  EXPECT_TRUE(contains(error("P5 100000 100000 65535\n\x01\x02"), "100000x100000 is out of range"));
  EXPECT_TRUE(contains(error("P5 60000 60000 65535\n\x01\x02"), "out of range"));
  EXPECT_TRUE(contains(error("P5 16384 16384 65535\n\x01\x02"), "truncated depth data"));
  EXPECT_TRUE(contains(error("P5 0 4 65535\n"), "out of range"));
  EXPECT_TRUE(contains(error("P5 -1 4 65535\n"), "out of range"));
  EXPECT_TRUE(contains(error("P5 1 1 65535 7\n\x01\x02"), "not a fakenect depth frame"));
}

TEST(FakenectDecode, Rgb) {
  const Image image =
      decodeFakenectRgb(bytesOf(std::string("P6 2 1 255\n\x01\x02\x03\x04\x05\x06", 17)), "r.ppm");
  ASSERT_EQ(image.width(), 2);
  ASSERT_EQ(image.channels(), 3);
  EXPECT_EQ(image.values<std::uint8_t>()[5], 6);
  EXPECT_TRUE(contains(errorOf([] { (void)decodeFakenectRgb(bytesOf("P6 2 1 255\n\x01"), "r.ppm"); }),
                       "r.ppm: truncated RGB data: 1 of 6 bytes"));
  EXPECT_TRUE(contains(errorOf([] { (void)decodeFakenectRgb(bytesOf("P5 2 1 255\n\x01\x02"), "r.ppm"); }),
                       "r.ppm: not a fakenect RGB frame"));
}

TEST(FakenectWriter, WritesWhatFakenectAndTheReaderBothRead) {
  const test::TempDir dir;
  const fs::path folder = dir / "rec";
  {
    FakenectWriter writer(folder);
    writer.addRgb(rgbPattern(0), 100.01);
    writer.addRawDepth(pattern(0), 100.02);
    writer.addRawDepth(pattern(1), 100.0533);
    writer.addRgb(rgbPattern(1), 100.06);
    writer.addRawDepth(pattern(2), 100.0866);
    EXPECT_FALSE(fs::exists(folder)); // nothing in place before finish()
    writer.finish();
  }
  ASSERT_TRUE(fs::is_directory(folder));
  EXPECT_EQ(folderNames(dir.path()), std::vector<std::string>{"rec"}); // no temporary left

  // fakenect parses each INDEX line with sscanf("%c-%lf-%u-%*s") and opens "<folder>/<line>".
  const std::vector<std::string> lines = indexLines(folder);
  ASSERT_EQ(lines.size(), 5u);
  const double walltimes[] = {100.01, 100.02, 100.0533, 100.06, 100.0866};
  const char kinds[] = {'r', 'd', 'd', 'r', 'd'};
  unsigned previous = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    char kind = 0;
    double walltime = 0;
    unsigned timestamp = 0;
    ASSERT_EQ(std::sscanf(lines[i].c_str(), "%c-%lf-%u-%*s", &kind, &walltime, &timestamp), 3) << lines[i];
    EXPECT_EQ(kind, kinds[i]);
    EXPECT_NEAR(walltime, walltimes[i], 1e-6);
    if (i > 0) {
      EXPECT_GT(timestamp, previous) << lines[i];
    }
    previous = timestamp;
    EXPECT_TRUE(fs::is_regular_file(folder / lines[i])) << lines[i];
  }
  // Depth files: exactly the header fakenect skips, then 640·480 little-endian values.
  const std::string depth = test::readAll(folder / lines[1]);
  ASSERT_EQ(depth.size(), 17u + 640 * 480 * 2);
  EXPECT_EQ(depth.substr(0, 17), "P5 640 480 65535\n");
  const std::uint16_t first = pattern(0).raw[1];
  EXPECT_EQ(static_cast<std::uint8_t>(depth[19]), first & 0xff);
  EXPECT_EQ(static_cast<std::uint8_t>(depth[20]), first >> 8);
  EXPECT_EQ(test::readAll(folder / lines[0]).substr(0, 15), "P6 640 480 255\n");

  const FakenectRecording recording = FakenectRecording::open(folder);
  EXPECT_TRUE(recording.warnings().empty());
  ASSERT_EQ(recording.depthFrameCount(), 3u);
  ASSERT_EQ(recording.entries().size(), 5u);
  EXPECT_EQ(recording.entries()[3].kind, 'r');
  EXPECT_EQ(recording.entries()[3].line, 4);
  EXPECT_EQ(recording.entries()[3].file, lines[3]);
  for (int i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    const RawDepth raw = recording.rawDepthFrame(static_cast<std::size_t>(i));
    EXPECT_EQ(raw.raw, pattern(i).raw);
    const DepthFrame frame = recording.depthFrame(static_cast<std::size_t>(i));
    ASSERT_EQ(frame.width, 640);
    ASSERT_EQ(frame.height, 480);
    for (std::size_t p = 0; p < raw.raw.size(); ++p) {
      ASSERT_EQ(frame.depth[p], kinectRawToMetres(raw.raw[p])) << p;
    }
    EXPECT_EQ(frame.kind, DepthSourceKind::Fakenect);
    EXPECT_EQ(frame.source, folder.string());
    EXPECT_EQ(frame.frame, i);
    EXPECT_EQ(frame.label(), folder.string() + " frame " + std::to_string(i));
    EXPECT_EQ(frame.intrinsics, CameraIntrinsics::kinectV1());
    EXPECT_NEAR(frame.timestamp, walltimes[i == 0 ? 1 : i == 1 ? 2 : 4] - 100.01, 1e-6);
    // The latest RGB at or before the depth frame.
    EXPECT_EQ(frame.colour, rgbPattern(i < 2 ? 0 : 1));
  }
  EXPECT_THROW((void)recording.depthFrame(3), Error);
}

TEST(FakenectWriter, DepthInMetresIsQuantisedToRaw) {
  const test::TempDir dir;
  DepthFrame frame(640, 480);
  frame.at(0, 0) = 1.0f;
  frame.at(1, 0) = kinectRawToMetres(600);
  frame.at(2, 0) = -3.0f;
  {
    FakenectWriter writer(dir / "rec");
    writer.addDepth(frame, 5.0);
    writer.finish();
  }
  const RawDepth raw = FakenectRecording::open(dir / "rec").rawDepthFrame(0);
  EXPECT_EQ(raw.raw[0], metresToKinectRaw(1.0f));
  EXPECT_EQ(raw.raw[0], 759);
  EXPECT_EQ(raw.raw[1], 600);
  EXPECT_EQ(raw.raw[2], kKinectNoData);
  EXPECT_EQ(raw.raw[3], kKinectNoData);
}

TEST(FakenectWriter, RejectsOtherSizesAndDecreasingWalltimes) {
  const test::TempDir dir;
  const fs::path folder = dir / "rec";
  FakenectWriter writer(folder);
  std::string message = errorOf([&] { writer.addDepth(DepthFrame(320, 240), 1.0); });
  EXPECT_TRUE(contains(message, folder.string() + ": ")) << message;
  EXPECT_TRUE(contains(message, "320x240")) << message;
  EXPECT_TRUE(contains(errorOf([&] { writer.addRgb(Image(640, 480, 4, PixelType::U8), 1.0); }), "8-bit RGB"));
  writer.addRawDepth(pattern(0), 2.0);
  message = errorOf([&] { writer.addRawDepth(pattern(1), 1.5); });
  EXPECT_TRUE(contains(message, "before the previous frame")) << message;
  EXPECT_TRUE(contains(errorOf([&] { writer.addRawDepth(pattern(1), -1.0); }), "walltime"));
  writer.addRawDepth(pattern(1), 2.0); // equal walltimes are fine: timestamps still differ
  writer.finish();
  EXPECT_EQ(FakenectRecording::open(folder).depthFrameCount(), 2u);
  EXPECT_THROW(writer.addRawDepth(pattern(2), 3.0), Error);
  EXPECT_THROW(writer.finish(), Error);
}

TEST(FakenectWriter, UnfinishedOrFailedWritesLeaveNothingBehind) {
  const test::TempDir dir;
  {
    FakenectWriter writer(dir / "rec");
    writer.addRawDepth(pattern(0), 1.0);
  }
  EXPECT_TRUE(folderNames(dir.path()).empty());
  {
    FakenectWriter writer(dir / "rec");
    writer.addRgb(rgbPattern(0), 1.0);
    EXPECT_TRUE(contains(errorOf([&] { writer.finish(); }), "no depth frame"));
  }
  EXPECT_TRUE(folderNames(dir.path()).empty());
}

TEST(FakenectWriter, ReplacesAnExistingRecordingOnlyAtFinish) {
  const test::TempDir dir;
  const fs::path folder = dir / "rec";
  fs::create_directories(folder);
  writeFile(folder / "old.txt", "old");
  {
    FakenectWriter writer(folder);
    writer.addRawDepth(pattern(3), 1.0);
    EXPECT_TRUE(fs::exists(folder / "old.txt"));
  }
  EXPECT_TRUE(fs::exists(folder / "old.txt")); // abandoned: the old folder is untouched
  FakenectWriter writer(folder / "");          // a trailing separator names the same folder
  writer.addRawDepth(pattern(3), 1.0);
  writer.finish();
  EXPECT_FALSE(fs::exists(folder / "old.txt"));
  EXPECT_EQ(FakenectRecording::open(folder).rawDepthFrame(0).raw, pattern(3).raw);
  EXPECT_EQ(folderNames(dir.path()), std::vector<std::string>{"rec"});
}

/** A recording of `depthFrames` depth frames written by FakenectWriter. */
fs::path writeRecording(const fs::path& folder, int depthFrames) {
  FakenectWriter writer(folder);
  for (int i = 0; i < depthFrames; ++i) {
    writer.addRawDepth(pattern(i), 10.0 + i / 30.0);
  }
  writer.finish();
  return folder;
}

TEST(FakenectRecording, MissingFilesAreWarningsNamingTheFrame) {
  const test::TempDir dir;
  const fs::path folder = writeRecording(dir / "rec", 3);
  const std::vector<std::string> lines = indexLines(folder);
  fs::remove(folder / lines[1]);
  const FakenectRecording recording = FakenectRecording::open(folder);
  ASSERT_EQ(recording.depthFrameCount(), 2u);
  ASSERT_EQ(recording.warnings().size(), 1u);
  EXPECT_EQ(recording.warnings()[0],
            folder.string() + ": frame 1: " + lines[1] + " listed in INDEX.txt is missing");
  EXPECT_EQ(recording.rawDepthFrame(1).raw, pattern(2).raw);

  fs::remove(folder / lines[0]);
  fs::remove(folder / lines[2]);
  EXPECT_EQ(errorOf([&] { (void)FakenectRecording::open(folder); }),
            folder.string() + ": no depth frame: all 3 depth frames listed in INDEX.txt are missing");
}

TEST(FakenectRecording, WindowsLineEndingsAndEmptyLinesAreTolerated) {
  const test::TempDir dir;
  const fs::path folder = writeRecording(dir / "rec", 2);
  const std::vector<std::string> lines = indexLines(folder);
  writeFile(folder / "INDEX.txt", lines[0] + "\r\n\r\n" + lines[1] + "\r\n\n");
  const FakenectRecording recording = FakenectRecording::open(folder);
  ASSERT_EQ(recording.depthFrameCount(), 2u);
  EXPECT_EQ(recording.entries()[1].line, 3);
  EXPECT_EQ(recording.entries()[1].file, lines[1]);
  // fakenect itself stops at an empty line: that is worth a warning.
  ASSERT_EQ(recording.warnings().size(), 1u);
  EXPECT_TRUE(contains(recording.warnings()[0], "INDEX.txt:2: empty line")) << recording.warnings()[0];
  EXPECT_EQ(recording.rawDepthFrame(1).raw, pattern(1).raw);
}

TEST(FakenectRecording, MalformedIndexAndFoldersAreErrors) {
  const test::TempDir dir;
  const fs::path folder = writeRecording(dir / "rec", 1);
  const std::string first = indexLines(folder)[0];
  const std::string index = (folder / "INDEX.txt").string();
  const auto openError = [&](const std::string& text) {
    writeFile(folder / "INDEX.txt", text);
    return errorOf([&] { (void)FakenectRecording::open(folder); });
  };
  EXPECT_TRUE(
      contains(openError(first + "\nnonsense\n"), index + ":2: expected <kind>-<walltime>-<timestamp>"));
  EXPECT_TRUE(contains(openError("d-abc-1.pgm\n"), index + ":1: "));
  EXPECT_TRUE(contains(openError("d-1.5-99999999999.pgm\n"), "32-bit"));
  EXPECT_TRUE(contains(openError("d-1.5-3/../x.pgm\n"), "directory"));
  EXPECT_TRUE(contains(openError(""), "no depth frame (INDEX.txt lists none)"));
  EXPECT_EQ(openError("\n\n"), folder.string() + ": no depth frame (INDEX.txt lists none)");
  // Unknown kinds are skipped with a warning.
  writeFile(folder / "INDEX.txt", "x-1.0-1.bin\n" + first + "\n");
  const FakenectRecording recording = FakenectRecording::open(folder);
  EXPECT_EQ(recording.depthFrameCount(), 1u);
  ASSERT_EQ(recording.warnings().size(), 1u);
  EXPECT_TRUE(contains(recording.warnings()[0], "unknown entry kind 'x'"));

  fs::remove(folder / "INDEX.txt");
  EXPECT_EQ(errorOf([&] { (void)FakenectRecording::open(folder); }),
            folder.string() + ": INDEX.txt is missing (not a fakenect recording)");
  EXPECT_EQ(errorOf([&] { (void)FakenectRecording::open(dir / "nothing"); }),
            (dir / "nothing").string() + ": no such fakenect recording folder");
}

TEST(FakenectRecording, CorruptDepthFilesNameTheFileAndFrame) {
  const test::TempDir dir;
  const fs::path folder = writeRecording(dir / "rec", 2);
  const std::vector<std::string> lines = indexLines(folder);
  const std::string full = test::readAll(folder / lines[1]);
  writeFile(folder / lines[1], full.substr(0, 1000));
  const FakenectRecording recording = FakenectRecording::open(folder);
  EXPECT_NO_THROW((void)recording.depthFrame(0));
  const std::string message = errorOf([&] { (void)recording.depthFrame(1); });
  EXPECT_EQ(message, (folder / lines[1]).string() +
                         ": frame 1: truncated depth data: 983 of 614400 bytes for 640x480");
  writeFile(folder / lines[1], "P5 100000 100000 65535\n\x01\x02");
  EXPECT_TRUE(contains(errorOf([&] { (void)recording.depthFrame(1); }), "100000x100000 is out of range"));
}

TEST(FakenectRecording, UndecodableRgbIsSkipped) {
  const test::TempDir dir;
  const fs::path folder = dir / "rec";
  {
    FakenectWriter writer(folder);
    writer.addRgb(rgbPattern(4), 1.0);
    writer.addRgb(rgbPattern(5), 1.01);
    writer.addRawDepth(pattern(0), 1.02);
    writer.finish();
  }
  const std::vector<std::string> lines = indexLines(folder);
  writeFile(folder / lines[1], "P6 640 480 255\nshort");
  const DepthFrame frame = FakenectRecording::open(folder).depthFrame(0);
  EXPECT_EQ(frame.colour, rgbPattern(4)); // the broken later one is skipped
  fs::remove(folder / lines[0]);
  const FakenectRecording recording = FakenectRecording::open(folder);
  EXPECT_EQ(recording.warnings().size(), 1u);
  EXPECT_TRUE(contains(recording.warnings()[0], "rgb frame 0")) << recording.warnings()[0];
  EXPECT_TRUE(recording.depthFrame(0).colour.empty());
}

} // namespace
} // namespace sylva::capture
