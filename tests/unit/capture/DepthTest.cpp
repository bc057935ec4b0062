// Depth inputs: the Kinect v1 raw scale, 16-bit depth PNGs, Middlebury disparity maps, previews and ranges.
#include <sylva/capture/Depth.hpp>
#include <sylva/core/Error.hpp>

#include "TempDir.hpp"

#include "CaptureTestUtil.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

namespace sylva::capture {
namespace {

using testutil::contains;
using testutil::errorOf;

namespace fs = std::filesystem;

TEST(KinectRaw, KnownValuesAndNoData) {
  // z = 1 / (raw·(−0.0030711016) + 3.3309495161).
  EXPECT_NEAR(kinectRawToMetres(0), 1.0 / 3.3309495161, 1e-6);
  EXPECT_NEAR(kinectRawToMetres(759), 1.0 / (3.3309495161 - 759 * 0.0030711016), 1e-6);
  EXPECT_NEAR(kinectRawToMetres(759), 1.0, 1e-4);
  EXPECT_GT(kinectRawToMetres(1084), 500.0f); // the last raw with a positive denominator
  EXPECT_EQ(kinectRawToMetres(1085), 0.0f);
  EXPECT_EQ(kinectRawToMetres(2046), 0.0f);
  EXPECT_EQ(kinectRawToMetres(kKinectNoData), 0.0f);
  EXPECT_EQ(kinectRawToMetres(65535), 0.0f);
}

TEST(KinectRaw, EveryValidRawRoundTripsAndDepthIncreases) {
  float previous = 0.0f;
  for (int raw = 0; raw <= 1084; ++raw) {
    const float z = kinectRawToMetres(static_cast<std::uint16_t>(raw));
    ASSERT_GT(z, previous) << "raw " << raw;
    ASSERT_EQ(metresToKinectRaw(z), raw) << "z " << z;
    previous = z;
  }
}

TEST(KinectRaw, MetresToRawRoundsToTheNearestAndClamps) {
  const float a = kinectRawToMetres(700);
  const float b = kinectRawToMetres(701);
  // Nearest in the raw (inverse-depth) scale: a quarter of the way from a to b in 1/z is still raw 700.
  const float nearA = static_cast<float>(1.0 / (0.75 / a + 0.25 / b));
  const float nearB = static_cast<float>(1.0 / (0.25 / a + 0.75 / b));
  EXPECT_EQ(metresToKinectRaw(nearA), 700);
  EXPECT_EQ(metresToKinectRaw(nearB), 701);
  EXPECT_EQ(metresToKinectRaw(0.1f), 0);      // nearer than the sensor's range: raw 0
  EXPECT_EQ(metresToKinectRaw(1.0e4f), 1084); // further than raw 1084's 533 m: clamped
  EXPECT_EQ(metresToKinectRaw(0.0f), kKinectNoData);
  EXPECT_EQ(metresToKinectRaw(-1.0f), kKinectNoData);
  EXPECT_EQ(metresToKinectRaw(std::numeric_limits<float>::quiet_NaN()), kKinectNoData);
  EXPECT_EQ(metresToKinectRaw(std::numeric_limits<float>::infinity()), kKinectNoData);
}

TEST(KinectRaw, QuantisationStepGrowsWithTheSquareOfDepth) {
  // dz/draw = z²·0.0030711016: about 3.1 mm at 1 m, 12 mm at 2 m, 0.8 mm at 0.5 m.
  for (const float z : {0.5f, 1.0f, 2.0f, 4.0f}) {
    const std::uint16_t raw = metresToKinectRaw(z);
    const double step = kinectRawToMetres(raw + 1) - kinectRawToMetres(raw);
    const double zq = kinectRawToMetres(raw);
    EXPECT_NEAR(step, zq * zq * 0.0030711016, 0.02 * step) << "at " << z << " m";
  }
  const std::uint16_t one = metresToKinectRaw(1.0f);
  EXPECT_NEAR(kinectRawToMetres(one + 1) - kinectRawToMetres(one), 0.00309, 0.0001);
}

TEST(CameraIntrinsics, KinectV1ScalesWithTheImage) {
  EXPECT_EQ(CameraIntrinsics::kinectV1Scaled(640, 480), CameraIntrinsics::kinectV1());
  const CameraIntrinsics half = CameraIntrinsics::kinectV1Scaled(320, 240);
  EXPECT_DOUBLE_EQ(half.fx, 594.21 / 2);
  EXPECT_DOUBLE_EQ(half.fy, 591.04 / 2);
  EXPECT_DOUBLE_EQ(half.cx, 339.31 / 2);
  EXPECT_DOUBLE_EQ(half.cy, 242.74 / 2);
  const CameraIntrinsics wide = CameraIntrinsics::kinectV1Scaled(1280, 480);
  EXPECT_DOUBLE_EQ(wide.fx, 594.21 * 2);
  EXPECT_DOUBLE_EQ(wide.fy, 591.04);
  const glm::dvec3 p = CameraIntrinsics{500, 400, 320, 240}.unproject(420, 140, 2.0);
  EXPECT_DOUBLE_EQ(p.x, 0.4);
  EXPECT_DOUBLE_EQ(p.y, -0.5);
  EXPECT_DOUBLE_EQ(p.z, 2.0);
}

TEST(DepthFrame, SizesAreCheckedAndPixelsStartWithoutData) {
  const DepthFrame frame(3, 2);
  EXPECT_EQ(frame.depth.size(), 6u);
  for (const float z : frame.depth) {
    EXPECT_EQ(z, 0.0f);
  }
  EXPECT_EQ(frame.intrinsics, CameraIntrinsics::kinectV1Scaled(3, 2));
  EXPECT_THROW(DepthFrame(0, 1), Error);
  EXPECT_THROW(DepthFrame(1, -1), Error);
  EXPECT_THROW(DepthFrame(65537, 1), Error);
  // 2^32 pixels: refused before allocating 16 GiB.
  EXPECT_TRUE(contains(errorOf([] { DepthFrame(65536, 65536); }), "65536x65536"));
  EXPECT_NO_THROW(DepthFrame(65536, 1));
}

TEST(DepthFrame, LabelNamesTheFrameOfRecordings) {
  DepthFrame frame(1, 1);
  frame.source = "tuft.png";
  EXPECT_EQ(frame.label(), "tuft.png");
  frame.kind = DepthSourceKind::Fakenect;
  frame.source = "rec";
  frame.frame = 7;
  EXPECT_EQ(frame.label(), "rec frame 7");
  frame.kind = DepthSourceKind::Kinect;
  frame.source = "kinect";
  frame.frame = 0;
  EXPECT_EQ(frame.label(), "kinect frame 0");
}

TEST(DepthSource, Names) {
  EXPECT_STREQ(depthSourceName(DepthSourceKind::DepthPng), "depth-png");
  EXPECT_STREQ(depthSourceName(DepthSourceKind::Middlebury), "middlebury");
  EXPECT_STREQ(depthSourceName(DepthSourceKind::Fakenect), "fakenect");
  EXPECT_STREQ(depthSourceName(DepthSourceKind::Kinect), "kinect");
  EXPECT_STREQ(depthSourceName(DepthSourceKind::Synthetic), "synthetic");
}

Image u16Grey(int w, int h, std::initializer_list<std::uint16_t> values) {
  Image image(w, h, 1, PixelType::U16);
  std::size_t i = 0;
  for (const std::uint16_t v : values) {
    image.values<std::uint16_t>()[i++] = v;
  }
  return image;
}

TEST(DepthPng, LoadsMillimetresAsMetres) {
  const test::TempDir dir;
  savePng(dir / "d.png", u16Grey(3, 2, {0, 1000, 1234, 65535, 1, 0}));
  const DepthFrame frame = loadDepthPng(dir / "d.png");
  ASSERT_EQ(frame.width, 3);
  ASSERT_EQ(frame.height, 2);
  EXPECT_EQ(frame.at(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(frame.at(1, 0), 1.0f);
  EXPECT_FLOAT_EQ(frame.at(2, 0), 1.234f);
  EXPECT_FLOAT_EQ(frame.at(0, 1), 65.535f);
  EXPECT_FLOAT_EQ(frame.at(1, 1), 0.001f);
  EXPECT_EQ(frame.at(2, 1), 0.0f);
  EXPECT_EQ(frame.kind, DepthSourceKind::DepthPng);
  EXPECT_EQ(frame.source, (dir / "d.png").string());
  EXPECT_EQ(frame.label(), (dir / "d.png").string());
  EXPECT_EQ(frame.intrinsics, CameraIntrinsics::kinectV1Scaled(3, 2));
  EXPECT_FALSE(frame.relativeDepth);
  EXPECT_TRUE(frame.colour.empty());
}

TEST(DepthPng, UnitAndIntrinsicsOptions) {
  const test::TempDir dir;
  savePng(dir / "d.png", u16Grey(2, 1, {5000, 0}));
  DepthPngOptions options;
  options.unitMetres = 0.0001;
  options.intrinsics = {100, 110, 1, 0.5};
  const DepthFrame frame = loadDepthPng(dir / "d.png", options);
  EXPECT_FLOAT_EQ(frame.at(0, 0), 0.5f);
  EXPECT_EQ(frame.intrinsics, (CameraIntrinsics{100, 110, 1, 0.5}));
  options.unitMetres = 0.0;
  EXPECT_TRUE(contains(errorOf([&] { (void)loadDepthPng(dir / "d.png", options); }), "unit"));
}

TEST(DepthPng, WrongFormatsAreRejectedNamingTheFile) {
  const test::TempDir dir;
  const fs::path rgb8 = dir / "rgb8.png";
  savePng(rgb8, Image(2, 2, 3, PixelType::U8));
  std::string message = errorOf([&] { (void)loadDepthPng(rgb8); });
  EXPECT_TRUE(
      contains(message, rgb8.string() + ": expected a single-channel 16-bit depth PNG, got 8-bit RGB"))
      << message;
  EXPECT_TRUE(contains(message, "--format middlebury")) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);

  const fs::path grey8 = dir / "grey8.png";
  savePng(grey8, Image(2, 2, 1, PixelType::U8));
  EXPECT_TRUE(contains(errorOf([&] { (void)loadDepthPng(grey8); }), "got 8-bit grey"));

  const fs::path rgb16 = dir / "rgb16.png";
  savePng(rgb16, Image(2, 2, 3, PixelType::U16));
  message = errorOf([&] { (void)loadDepthPng(rgb16); });
  EXPECT_TRUE(contains(message, "got 16-bit RGB")) << message;
  EXPECT_FALSE(contains(message, "middlebury")) << message;

  const fs::path zeros = dir / "zeros.png";
  savePng(zeros, Image(4, 4, 1, PixelType::U16));
  EXPECT_EQ(errorOf([&] { (void)loadDepthPng(zeros); }),
            zeros.string() + ": no valid depth pixel (every value is 0)");

  const fs::path missing = dir / "missing.png";
  EXPECT_TRUE(contains(errorOf([&] { (void)loadDepthPng(missing); }), missing.string()));
}

TEST(DepthPng, SaveRoundsToMillimetresAndRoundTrips) {
  const test::TempDir dir;
  DepthFrame frame(4, 1);
  frame.depth = {1.2344f, 70.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()};
  saveDepthPng(dir / "out.png", frame);
  const Image image = loadPng(dir / "out.png");
  ASSERT_EQ(image.type(), PixelType::U16);
  ASSERT_EQ(image.channels(), 1);
  const auto values = image.values<std::uint16_t>();
  EXPECT_EQ(values[0], 1234);
  EXPECT_EQ(values[1], 65535); // clamped
  EXPECT_EQ(values[2], 0);     // no data
  EXPECT_EQ(values[3], 0);
  const DepthFrame back = loadDepthPng(dir / "out.png");
  EXPECT_FLOAT_EQ(back.at(0, 0), 1.234f);
  EXPECT_FLOAT_EQ(back.at(1, 0), 65.535f);
  EXPECT_EQ(back.at(2, 0), 0.0f);
  // Overwrite leaves no temporary behind.
  saveDepthPng(dir / "out.png", back);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir.path())) {
    ++files;
  }
  EXPECT_EQ(files, 1u);
  EXPECT_TRUE(contains(errorOf([&] { saveDepthPng(dir / "out.exr", frame); }), "out.exr"));
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
  EXPECT_THROW(saveDepthPng(dir / "empty.png", DepthFrame()), Error);
  EXPECT_FALSE(fs::exists(dir / "empty.png"));
}

Image u8(int w, int h, int channels, std::initializer_list<std::uint8_t> values) {
  Image image(w, h, channels, PixelType::U8);
  std::size_t i = 0;
  for (const std::uint8_t v : values) {
    image.values<std::uint8_t>()[i++] = v;
  }
  return image;
}

TEST(Middlebury, DisparityToDepth) {
  const test::TempDir dir;
  savePng(dir / "disp.png", u8(3, 2, 1, {0, 100, 200, 50, 255, 0}));
  const DepthFrame frame = loadMiddlebury(dir / "disp.png");
  const double fb = 3740.0 * 0.160;
  EXPECT_EQ(frame.at(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(frame.at(1, 0), static_cast<float>(fb / 100));
  EXPECT_FLOAT_EQ(frame.at(2, 0), static_cast<float>(fb / 200));
  EXPECT_FLOAT_EQ(frame.at(0, 1), static_cast<float>(fb / 50));
  EXPECT_FLOAT_EQ(frame.at(1, 1), static_cast<float>(fb / 255));
  EXPECT_EQ(frame.at(2, 1), 0.0f);
  EXPECT_EQ(frame.intrinsics, (CameraIntrinsics{3740.0, 3740.0, 1.0, 0.5}));
  EXPECT_EQ(frame.kind, DepthSourceKind::Middlebury);
  EXPECT_TRUE(frame.relativeDepth);
  EXPECT_EQ(frame.source, (dir / "disp.png").string());

  MiddleburyOptions options;
  options.focalPx = 1000;
  options.baselineMetres = 0.2;
  options.doffsPx = 10;
  options.disparityScale = 0.5;
  options.calibrated = true;
  const DepthFrame calibrated = loadMiddlebury(dir / "disp.png", options);
  EXPECT_FLOAT_EQ(calibrated.at(1, 0), static_cast<float>(200.0 / (0.5 * 100 + 10)));
  EXPECT_FALSE(calibrated.relativeDepth);
  EXPECT_EQ(calibrated.intrinsics.fx, 1000.0);

  // A negative doffs that makes the denominator non-positive gives no data, not negative depth.
  options.doffsPx = -60;
  const DepthFrame shifted = loadMiddlebury(dir / "disp.png", options);
  EXPECT_EQ(shifted.at(1, 0), 0.0f);                                               // 50 − 60 < 0
  EXPECT_FLOAT_EQ(shifted.at(2, 0), static_cast<float>(200.0 / (0.5 * 200 - 60))); // 40
}

TEST(Middlebury, GreyStoredAsRgbIsAccepted) {
  const test::TempDir dir;
  savePng(dir / "rgb.png", u8(2, 1, 3, {80, 80, 80, 0, 0, 0}));
  const DepthFrame frame = loadMiddlebury(dir / "rgb.png");
  EXPECT_FLOAT_EQ(frame.at(0, 0), static_cast<float>(3740.0 * 0.160 / 80));
  EXPECT_EQ(frame.at(1, 0), 0.0f);
  savePng(dir / "colour.png", u8(2, 1, 3, {80, 80, 80, 1, 2, 3}));
  const std::string message = errorOf([&] { (void)loadMiddlebury(dir / "colour.png"); });
  EXPECT_TRUE(contains(message, (dir / "colour.png").string() + ": ")) << message;
  EXPECT_TRUE(contains(message, "pixel (1, 0)")) << message;
}

TEST(Middlebury, WrongFormatsAndOptionsAreRejected) {
  const test::TempDir dir;
  savePng(dir / "d16.png", u16Grey(2, 1, {100, 0}));
  std::string message = errorOf([&] { (void)loadMiddlebury(dir / "d16.png"); });
  EXPECT_TRUE(contains(message, (dir / "d16.png").string() + ": expected a single-channel 8-bit")) << message;
  EXPECT_TRUE(contains(message, "got 16-bit grey")) << message;
  savePng(dir / "ga.png", Image(2, 1, 2, PixelType::U8));
  EXPECT_TRUE(contains(errorOf([&] { (void)loadMiddlebury(dir / "ga.png"); }), "got 8-bit grey+alpha"));
  savePng(dir / "zero.png", Image(2, 1, 1, PixelType::U8));
  EXPECT_TRUE(contains(errorOf([&] { (void)loadMiddlebury(dir / "zero.png"); }), "no known disparity pixel"));

  savePng(dir / "ok.png", u8(1, 1, 1, {9}));
  MiddleburyOptions options;
  options.focalPx = 0;
  EXPECT_TRUE(contains(errorOf([&] { (void)loadMiddlebury(dir / "ok.png", options); }), "focal"));
  options = {};
  options.baselineMetres = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(contains(errorOf([&] { (void)loadMiddlebury(dir / "ok.png", options); }), "baseline"));
  options = {};
  options.disparityScale = -1;
  EXPECT_TRUE(contains(errorOf([&] { (void)loadMiddlebury(dir / "ok.png", options); }), "disparity scale"));
  options = {};
  options.doffsPx = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(contains(errorOf([&] { (void)loadMiddlebury(dir / "ok.png", options); }), "doffs"));
}

TEST(DepthPreview, NearIsWhiteFarIsDarkNoDataIsBlack) {
  DepthFrame frame(5, 1);
  frame.depth = {0.5f, 1.0f, 1.5f, 3.0f, 0.0f};
  const Image preview = depthPreview(frame, 0.5f, 1.5f);
  ASSERT_EQ(preview.channels(), 1);
  ASSERT_EQ(preview.type(), PixelType::U8);
  const auto v = preview.values<std::uint8_t>();
  EXPECT_EQ(v[0], 255);
  EXPECT_GT(v[1], v[2]);
  EXPECT_LT(v[1], 255);
  EXPECT_GT(v[2], 0);
  EXPECT_EQ(v[3], v[2]); // beyond far: clamped, still distinct from no data
  EXPECT_EQ(v[4], 0);
  EXPECT_THROW((void)depthPreview(frame, 1.0f, 1.0f), Error);
  EXPECT_THROW((void)depthPreview(frame, 2.0f, 1.0f), Error);
}

TEST(DepthRange, ValidPixelsOnly) {
  DepthFrame frame(4, 1);
  EXPECT_EQ(depthRange(frame), (std::pair<float, float>{0.0f, 0.0f}));
  frame.depth = {0.0f, 2.5f, 0.7f, 1.0f};
  EXPECT_EQ(depthRange(frame), (std::pair<float, float>{0.7f, 2.5f}));
}

} // namespace
} // namespace sylva::capture
