// Kinect capture through the real libfreenect API: without a device it fails with one clear line; under the
// `fakenect` wrapper (libfreenect-bin) a recording written by FakenectWriter replays frame for frame as
// FakenectRecording reads it.
#include <sylva/capture/Fakenect.hpp>
#include <sylva/capture/Kinect.hpp>
#include <sylva/core/Error.hpp>

#include "CliRun.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sylva::capture {
namespace {

namespace fs = std::filesystem;

const fs::path kFakenect = "/usr/bin/fakenect";

/** Clears FAKENECT_PATH for the scope of a test, restoring it afterwards. */
class NoReplay {
public:
  NoReplay() {
    if (const char* value = std::getenv("FAKENECT_PATH")) {
      mSaved = value;
      mHad = true;
    }
    ::unsetenv("FAKENECT_PATH");
  }
  ~NoReplay() {
    if (mHad) {
      ::setenv("FAKENECT_PATH", mSaved.c_str(), 1);
    }
  }
  NoReplay(const NoReplay&) = delete;
  NoReplay& operator=(const NoReplay&) = delete;

private:
  std::string mSaved;
  bool mHad = false;
};

TEST(KinectCapture, WithoutADeviceFailsWithOneLine) {
  const NoReplay noReplay;
  EXPECT_FALSE(kinectReplayActive());
  int calls = 0;
  std::string message;
  try {
    captureKinect({}, [&](DepthFrame&&) { return ++calls < 1; });
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_EQ(calls, 0);
  ASSERT_FALSE(message.empty()) << "captureKinect returned without a device";
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  const bool noDevice = message.starts_with("no Kinect v1 found (libfreenect sees 0 devices)") &&
                        message.find("fakenect DIR") != std::string::npos;
  const bool noUsb = message.starts_with("libfreenect could not start (no USB access?)");
  EXPECT_TRUE(noDevice || noUsb) << message;
  // The device count agrees: 0 devices, or the same start-up error.
  try {
    EXPECT_EQ(kinectDeviceCount(), 0);
  } catch (const Error& e) {
    EXPECT_TRUE(std::string(e.what()).starts_with("libfreenect could not start")) << e.what();
  }
}

TEST(KinectCapture, OptionsAreValidatedFirst) {
  const NoReplay noReplay;
  const auto error = [](const KinectOptions& options) {
    try {
      captureKinect(options, [](DepthFrame&&) { return true; });
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  KinectOptions options;
  options.frames = -1;
  EXPECT_NE(error(options).find("frame count"), std::string::npos);
  options = {};
  options.timeoutSeconds = 0;
  EXPECT_NE(error(options).find("timeout"), std::string::npos);
  options = {};
  options.device = -2;
  EXPECT_NE(error(options).find("device index"), std::string::npos);
}

RawDepth replayDepth(int n) {
  RawDepth raw;
  raw.width = 640;
  raw.height = 480;
  raw.raw.resize(640 * 480);
  for (std::size_t i = 0; i < raw.raw.size(); ++i) {
    const std::size_t x = i % 640;
    raw.raw[i] = static_cast<std::uint16_t>(
        x % 61 == 0 ? 2047 : (i * 3 + static_cast<std::size_t>(n) * 211) % (x % 40 == 0 ? 2048 : 1085));
  }
  return raw;
}

Image replayRgb(int n) {
  Image image(640, 480, 3, PixelType::U8);
  auto v = image.values<std::uint8_t>();
  for (std::size_t i = 0; i < v.size(); ++i) {
    v[i] = static_cast<std::uint8_t>(i * 7 + static_cast<std::size_t>(n) * 29);
  }
  return image;
}

/** Four depth frames at 30 Hz, with RGB before the first and the third. */
void writeRecording(const fs::path& folder) {
  FakenectWriter writer(folder);
  const double start = 1700000000.25;
  writer.addRgb(replayRgb(0), start);
  for (int i = 0; i < 4; ++i) {
    if (i == 2) {
      writer.addRgb(replayRgb(1), start + i / 30.0);
    }
    writer.addRawDepth(replayDepth(i), start + i / 30.0 + 0.001);
  }
  writer.finish();
}

struct ProbeFrame {
  int frame = 0;
  int width = 0;
  int height = 0;
  double timestamp = 0;
  int colour = 0;
  std::string source;
};

struct Probe {
  test::RunResult run;
  std::vector<ProbeFrame> frames;
};

/** Runs the probe under fakenect on `recording`, its output in `out`. */
Probe runProbe(const fs::path& recording, const fs::path& out, int frames, bool colour) {
  fs::remove_all(out);
  fs::create_directories(out);
  Probe probe;
  probe.run =
      test::runProgram(kFakenect.string(), out,
                       test::quote(recording.string()) + " " + test::quote(SYLVA_KINECT_PROBE) + " " +
                           test::quote(out.string()) + " " + std::to_string(frames) + (colour ? " 1" : " 0"));
  std::istringstream list(test::readAll(out / "frames.txt"));
  for (std::string line; std::getline(list, line);) {
    std::istringstream fields(line);
    ProbeFrame f;
    fields >> f.frame >> f.width >> f.height >> f.timestamp >> f.colour >> f.source;
    probe.frames.push_back(f);
  }
  return probe;
}

std::vector<float> readFloats(const fs::path& path) {
  const std::string bytes = test::readAll(path);
  std::vector<float> values(bytes.size() / sizeof(float));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(float));
  return values;
}

class KinectReplay : public testing::Test {
protected:
  void SetUp() override {
    if (!fs::exists(kFakenect)) {
      GTEST_SKIP() << kFakenect
                   << " is missing (Debian package libfreenect-bin): cannot replay through libfreenect";
    }
    writeRecording(mDir / "rec");
  }
  fs::path recording() const { return mDir / "rec"; }
  fs::path out() const { return mDir / "out"; }

  test::TempDir mDir;
};

TEST_F(KinectReplay, EveryFrameArrivesIdenticalThroughLibfreenect) {
  const FakenectRecording reference = FakenectRecording::open(recording());
  ASSERT_EQ(reference.depthFrameCount(), 4u);
  const Probe probe = runProbe(recording(), out(), 0, false); // 0: the recording's frame count
  ASSERT_EQ(probe.run.status, 0) << probe.run.err << probe.run.out;
  ASSERT_EQ(probe.frames.size(), 4u) << probe.run.out;
  double previous = -1.0;
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    const ProbeFrame& f = probe.frames[i];
    EXPECT_EQ(f.frame, static_cast<int>(i));
    EXPECT_EQ(f.width, 640);
    EXPECT_EQ(f.height, 480);
    EXPECT_EQ(f.colour, 0);
    EXPECT_EQ(f.source, "fakenect:" + recording().string());
    EXPECT_GT(f.timestamp, previous);
    previous = f.timestamp;
    const std::vector<float> delivered = readFloats(out() / ("frame-" + std::to_string(i) + ".f32"));
    const DepthFrame expected = reference.depthFrame(i);
    ASSERT_EQ(delivered.size(), expected.depth.size());
    const RawDepth raw = reference.rawDepthFrame(i);
    ASSERT_EQ(raw.raw, replayDepth(static_cast<int>(i)).raw);
    for (std::size_t p = 0; p < delivered.size(); ++p) {
      ASSERT_EQ(delivered[p], expected.depth[p]) << "pixel " << p;
      if (raw.raw[p] <= 1084) {
        ASSERT_EQ(metresToKinectRaw(delivered[p]), raw.raw[p]) << "pixel " << p;
      } else {
        ASSERT_EQ(delivered[p], 0.0f) << "pixel " << p;
      }
    }
  }
  EXPECT_EQ(probe.frames.front().timestamp, 0.0);
  // fakenect sleeps by the recorded walltime differences: 3 frame gaps at 30 Hz, so the frames arrive at least
  // 0.1 s apart (less a little for its sleep's granularity). The timestamps are arrival times on the wall
  // clock: a loaded machine delivers them later, so there is no upper bound (it made this test flaky).
  EXPECT_GE(probe.frames.back().timestamp, 0.08);
}

TEST_F(KinectReplay, ColourIsTheLatestRgbBeforeEachFrame) {
  const FakenectRecording reference = FakenectRecording::open(recording());
  const Probe probe = runProbe(recording(), out(), 4, true);
  ASSERT_EQ(probe.run.status, 0) << probe.run.err << probe.run.out;
  ASSERT_EQ(probe.frames.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(probe.frames[i].colour, 1);
    const Image expected = reference.depthFrame(i).colour;
    ASSERT_EQ(expected, replayRgb(i < 2 ? 0 : 1));
    const std::string delivered = test::readAll(out() / ("frame-" + std::to_string(i) + ".rgb"));
    ASSERT_EQ(delivered.size(), expected.byteSize());
    EXPECT_EQ(std::memcmp(delivered.data(), expected.data(), delivered.size()), 0);
  }
}

TEST_F(KinectReplay, StopsAfterTheRequestedFramesOrAtTheEndOfTheRecording) {
  Probe probe = runProbe(recording(), out(), 2, false);
  ASSERT_EQ(probe.run.status, 0) << probe.run.err;
  EXPECT_EQ(probe.frames.size(), 2u);
  // Debian's fakenect 0.5.3 does not loop: asking for more frames than recorded ends cleanly with all of
  // them.
  probe = runProbe(recording(), out(), 10, false);
  ASSERT_EQ(probe.run.status, 0) << probe.run.err;
  EXPECT_EQ(probe.frames.size(), 4u);
  EXPECT_FALSE(fs::exists(out() / "frame-4.f32"));
}

TEST_F(KinectReplay, MissingFilesAreRefusedBeforeFakenectExits) {
  std::ifstream index(recording() / "INDEX.txt");
  std::string line;
  std::getline(index, line);
  std::getline(index, line); // the first depth frame
  fs::remove(recording() / line);
  const Probe probe = runProbe(recording(), out(), 0, false);
  EXPECT_EQ(probe.run.status, 2) << probe.run.err << probe.run.out; // ours, not fakenect's exit(1)
  EXPECT_NE(probe.run.err.find("frame 0: " + line + " listed in INDEX.txt is missing"), std::string::npos)
      << probe.run.err;
  EXPECT_TRUE(probe.frames.empty());
}

} // namespace
} // namespace sylva::capture
