// Motion from a reference video: a generated clip with a known motion (a translating background and a disc
// that rotates and scales) goes through a real Motion-JPEG file and back; DIS and Farnebäck must recover the
// motion within stated endpoint errors; suggested anchors must lie in the zone and carry the known motion
// mapped to image pixels; accepting them is one edit that undoes byte for byte. A real clip (OpenCV's
// tree.avi, a swaying tree) checks the same path on camera footage.
#include <sylva/core/Error.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Field.hpp>
#include <sylva/folding/Flow.hpp>

#include "ExternalData.hpp"
#include "TempDir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <tuple>

// OpenCV decodes and computes flow on TBB worker threads whose synchronisation ThreadSanitizer cannot see (it
// reports races inside libopencv_*), so the tests that call into OpenCV skip in a ThreadSanitizer build and
// the binary runs clean there as a whole. The part of Flow.cpp on Sylva's own threads (syntheticVideo's
// parallelFor) still runs: SyntheticClipIsDeterministicAndMovesExactly.
#if defined(__SANITIZE_THREAD__)
#define SYLVA_SKIP_UNDER_TSAN() GTEST_SKIP() << "OpenCV's TBB threads are opaque to ThreadSanitizer"
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define SYLVA_SKIP_UNDER_TSAN() GTEST_SKIP() << "OpenCV's TBB threads are opaque to ThreadSanitizer"
#endif
#endif
#ifndef SYLVA_SKIP_UNDER_TSAN
#define SYLVA_SKIP_UNDER_TSAN() static_cast<void>(0)
#endif

namespace sylva::folding {
namespace {

namespace fs = std::filesystem;

constexpr glm::ivec2 kSize{256, 192};
constexpr int kFrames = 6;

/** The known motion: background (2.5, −1.25) px/frame; a disc turning 0.04 rad and growing 3 % per frame. */
SyntheticMotion knownMotion() {
  SyntheticMotion m;
  m.translation = Vec2(2.5, -1.25);
  m.centre = Vec2(176.0, 100.0);
  m.radius = 48.0;
  m.rotationRad = 0.04;
  m.scale = 1.03;
  return m;
}

/** The clip as a test gets it: generated, written as Motion-JPEG, read back (once per test binary). */
const VideoClip& loadedClip() {
  static const VideoClip clip = [] {
    const test::TempDir dir;
    saveVideo(dir / "known.avi", syntheticVideo(kSize, kFrames, knownMotion(), 3));
    return loadVideo(dir / "known.avi");
  }();
  return clip;
}

enum class Region { Background, Disc };

/** Texels well inside a region: 16 px from the frame border, 12 px from the disc's rim. */
bool inRegion(const SyntheticMotion& m, Region region, Vec2 p) {
  const double d = glm::length(p - m.centre);
  if (region == Region::Disc) {
    return d <= m.radius - 12.0;
  }
  return d >= m.radius + 12.0 && p.x >= 16.0 && p.y >= 16.0 && p.x <= kSize.x - 16.0 && p.y <= kSize.y - 16.0;
}

/** Mean and largest endpoint error of `flow` against the known motion over a region, frame pixels. */
struct Epe {
  double mean = 0.0;
  double max = 0.0;
  std::size_t texels = 0;
};
Epe endpointError(const FlowField& flow, Region region) {
  const SyntheticMotion m = knownMotion();
  Epe e;
  double sum = 0.0;
  for (int y = 0; y < flow.height; ++y) {
    for (int x = 0; x < flow.width; ++x) {
      const Vec2 p(x + 0.5, y + 0.5);
      if (!inRegion(m, region, p)) {
        continue;
      }
      const double err = glm::length(glm::dvec2(flow.at(x, y)) - m.flowAt(p));
      sum += err;
      e.max = std::max(e.max, err);
      ++e.texels;
    }
  }
  e.mean = sum / static_cast<double>(e.texels);
  return e;
}

Project projectWithZone(const Shape& shape) {
  Project p;
  p.images.push_back({"img", "img.png", true});
  Profile profile;
  profile.id = "p";
  p.profiles.push_back(profile);
  Zone zone;
  zone.id = "eye";
  zone.image = "img";
  zone.profile = "p";
  zone.shape = shape;
  p.zones.push_back(zone);
  return parseProject(toJson(p), "flow-test.json");
}

Shape rect(Vec2 lo, Vec2 hi) {
  Shape s;
  s.type = Shape::Type::Rect;
  s.min = lo;
  s.max = hi;
  return s;
}

// ---------------------------------------------------------------------------------------------------------
// Clips

TEST(FoldFlow, SyntheticClipSurvivesMotionJpegAndPngSequences) {
  SYLVA_SKIP_UNDER_TSAN();
  const VideoClip original = syntheticVideo(kSize, kFrames, knownMotion(), 3);
  const VideoClip& clip = loadedClip();
  ASSERT_EQ(clip.frames.size(), static_cast<std::size_t>(kFrames));
  EXPECT_EQ(clip.size, kSize);
  EXPECT_NEAR(clip.fps, 25.0, 0.01);
  EXPECT_FALSE(clip.truncated);
  ASSERT_EQ(clip.timesS.size(), clip.frames.size());
  for (std::size_t i = 0; i < clip.frames.size(); ++i) {
    EXPECT_NEAR(clip.timesS[i], static_cast<double>(i) / 25.0, 1e-3) << "frame " << i;
    const Image& f = clip.frames[i];
    ASSERT_EQ(f.channels(), 4);
    ASSERT_EQ(f.type(), PixelType::U8);
    // Motion-JPEG at quality 100 keeps every frame close to the generated one.
    double diff = 0.0;
    for (int y = 0; y < f.height(); ++y) {
      for (int x = 0; x < f.width(); ++x) {
        for (int c = 0; c < 3; ++c) {
          diff += std::abs(f.get(x, y, c) - original.frames[i].get(x, y, c));
        }
        EXPECT_EQ(f.get(x, y, 3), 1.0f);
      }
    }
    EXPECT_LT(diff / (f.width() * f.height() * 3), 2.0 / 255.0) << "frame " << i;
  }

  // A PNG sequence is lossless and numbered from 0; reading fewer frames reports the rest.
  const test::TempDir dir;
  saveVideo(dir / "seq/f%03d.png", original);
  EXPECT_TRUE(fs::exists(dir / "seq/f000.png"));
  const VideoClip seq = loadVideo(dir / "seq/f%03d.png", 4);
  ASSERT_EQ(seq.frames.size(), 4u);
  EXPECT_TRUE(seq.truncated);
  for (std::size_t i = 0; i < seq.frames.size(); ++i) {
    EXPECT_TRUE(seq.frames[i] == original.frames[i]) << "frame " << i;
  }
}

TEST(FoldFlow, ASequenceFrameClaimingAHugeSizeIsRefusedBeforeDecoding) {
  // The flow fuzz target's finding: a 2.6 KB progressive JPEG whose header claims 20000×20000 pixels made
  // libjpeg zero about 2 GB before reading a scan. Its header is read first, in any frame the clip would
  // decode (numbered from 0 or 1), and the clip is refused naming the frame; the pattern's own form is
  // checked too.
  SYLVA_SKIP_UNDER_TSAN();
  const test::TempDir dir;
  const fs::path huge = test::sourcePath("fuzz/regressions/flow/jpeg-progressive-claims-20000x20000.jpg");
  saveVideo(dir / "seq/%04d.png", syntheticVideo({32, 32}, 3, SyntheticMotion{}));
  fs::copy_file(huge, dir / "seq/0002.png", fs::copy_options::overwrite_existing);
  const std::string pattern = (dir / "seq/%04d.png").string();
  try {
    (void)loadVideo(pattern, 3);
    ADD_FAILURE() << "the third frame claims 20000×20000 pixels";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), pattern +
                                         ": frame file 0002.png is a JPEG of 20000×20000 pixels, over the " +
                                         std::to_string(kMaxVideoSide) + " per side this loader accepts");
  }
  // Reading two frames still decodes the third (it tells whether the clip was cut short); reading one does
  // not.
  EXPECT_THROW((void)loadVideo(pattern, 2), Error);
  const VideoClip first = loadVideo(pattern, 1);
  EXPECT_EQ(first.frames.size(), 1u);
  EXPECT_TRUE(first.truncated);
  fs::create_directories(dir / "one");
  fs::copy_file(huge, dir / "one/1.jpg");
  EXPECT_THROW((void)loadVideo(dir / "one/%d.jpg", 1), Error); // numbered from 1
  EXPECT_THROW((void)loadVideo(dir / "one/%s.jpg", 1), Error);
  // The same for the other formats OpenCV decodes: a 26-byte BMP and a 26-byte TIFF that claim 20000×20000.
  fs::create_directories(dir / "bmp");
  fs::create_directories(dir / "tif");
  const auto write = [](const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  };
  // BMP: file header, then a 40-byte info header's size, width and height (little-endian 20000 = 0x4e20).
  write(dir / "bmp/0.bmp",
        {'B', 'M', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 40, 0, 0, 0, 0x20, 0x4e, 0, 0, 0x20, 0x4e, 0, 0});
  // TIFF: "II", 42, the directory at 8: two LONG entries, ImageWidth and ImageLength.
  write(dir / "tif/0.tif", {'I', 'I',  42,   0, 8, 0, 0, 0, 2, 0, 0, 1, 4, 0,    1,    0, 0,
                            0,   0x20, 0x4e, 0, 0, 1, 1, 4, 0, 1, 0, 0, 0, 0x20, 0x4e, 0, 0});
  // Radiance HDR and PFM, 40 bytes or less, which OpenCV decodes to 3 floats a pixel: the flow fuzz target
  // found one that asked for 2.2 GB (fuzz/regressions/flow).
  fs::create_directories(dir / "hdr");
  fs::create_directories(dir / "pfm");
  fs::copy_file(test::sourcePath("fuzz/regressions/flow/radiance-claims-13000x13000.hdr"), dir / "hdr/0.hdr");
  fs::copy_file(test::sourcePath("fuzz/regressions/flow/pfm-claims-13000x13000.pfm"), dir / "pfm/0.pfm");
  for (const auto& [folder, format, side] :
       {std::tuple{"bmp", "BMP", 20000}, std::tuple{"tif", "TIFF", 20000},
        std::tuple{"hdr", "Radiance HDR", 13000}, std::tuple{"pfm", "PFM", 13000}}) {
    const std::string clip = (dir / folder / (std::string("%d.") + folder)).string();
    try {
      (void)loadVideo(clip, 1);
      ADD_FAILURE() << folder << ": the frame claims a huge size";
    } catch (const Error& e) {
      const std::string size = std::to_string(side) + "×" + std::to_string(side);
      EXPECT_EQ(std::string(e.what()), clip + ": frame file 0." + folder + " is a " + format + " of " + size +
                                           " pixels, over the " + std::to_string(kMaxVideoSide) +
                                           " per side this loader accepts");
    }
  }
  // A frame whose size no header gives (a format OpenCV reads unchecked, such as DICOM, or a cut header) is
  // refused before anything decodes, naming the frame.
  fs::create_directories(dir / "dcm");
  std::vector<std::uint8_t> dicom(132, 0);
  std::copy_n("DICM", 4, dicom.begin() + 128);
  write(dir / "dcm/0.dcm", dicom);
  const std::string dcm = (dir / "dcm/%d.dcm").string();
  try {
    (void)loadVideo(dcm, 1);
    ADD_FAILURE() << "a frame of unknown size was decoded";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith(dcm + ": frame file 0.dcm is not an image whose size can be "
                                                      "read before decoding"));
  }
}

/** A file's bytes. */
std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

/** Writes a little-endian 32-bit value at `offset`. */
void putU32(std::string& bytes, std::size_t offset, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) {
    bytes.at(offset + static_cast<std::size_t>(i)) = static_cast<char>((value >> (8 * i)) & 0xFFu);
  }
}

/** The JPEG pictures of a Motion-JPEG AVI: the payloads of its '00dc' chunks that start with a JPEG SOI. */
std::vector<std::string> jpegFrames(const std::string& avi) {
  std::vector<std::string> frames;
  for (std::size_t at = avi.find("00dc"); at != std::string::npos && at + 10 <= avi.size();
       at = avi.find("00dc", at + 4)) {
    std::uint32_t size = 0;
    for (int i = 3; i >= 0; --i) {
      size = (size << 8) | static_cast<unsigned char>(avi[at + 4 + static_cast<std::size_t>(i)]);
    }
    if (at + 8 + size <= avi.size() && avi.compare(at + 8, 2, "\xFF\xD8") == 0) {
      frames.push_back(avi.substr(at + 8, size));
    }
  }
  return frames;
}

TEST(FoldFlow, AContainerWhoseHeaderAndFramesDisagreeDecodesWhatTheFramesHold) {
  // OpenCV 4.6's FFmpeg capture sized its output from the stream header and its input from the decoder, so a
  // file whose header and frames disagree made it read past a heap buffer (the flow_ffmpeg fuzz target's
  // finding). Containers now decode through FFmpeg's libraries, each frame converted at the size its decoder
  // reports. The class: headers claiming larger and smaller frames than they carry, and a stream whose frames
  // change size (refused, naming the frame). Under AddressSanitizer any over-read fails the test.
  SYLVA_SKIP_UNDER_TSAN();
  const test::TempDir dir;
  saveVideo(dir / "big.avi", syntheticVideo({64, 48}, 3, knownMotion(), 5));
  saveVideo(dir / "small.avi", syntheticVideo({32, 24}, 3, knownMotion(), 6));
  const VideoClip truth = loadVideo(dir / "big.avi");
  ASSERT_EQ(truth.frames.size(), 3u);
  ASSERT_EQ(truth.size, glm::ivec2(64, 48));
  const std::string avi = readBytes(dir / "big.avi");
  const std::size_t avih = avi.find("avih");
  const std::size_t strf = avi.find("strf");
  ASSERT_NE(avih, std::string::npos);
  ASSERT_NE(strf, std::string::npos);
  // Headers claiming wider, taller, smaller and degenerate frames: the pictures (64×48) come out unchanged.
  // A header over 4/3 as tall as the pictures is FFmpeg's sign of interlaced Motion-JPEG (one field per
  // picture, woven in pairs), a reading of its own: the pictures' width survives and nothing is read out of
  // bounds.
  for (const glm::ivec2 claim : {glm::ivec2(640, 60), glm::ivec2(16, 8), glm::ivec2(1, 1), glm::ivec2(64, 4),
                                 glm::ivec2(0, 0), glm::ivec2(640, 480)}) {
    std::string lying = avi;
    putU32(lying, avih + 8 + 32, static_cast<std::uint32_t>(claim.x)); // MainAVIHeader dwWidth, dwHeight
    putU32(lying, avih + 8 + 36, static_cast<std::uint32_t>(claim.y));
    putU32(lying, strf + 8 + 4, static_cast<std::uint32_t>(claim.x)); // BITMAPINFOHEADER biWidth, biHeight
    putU32(lying, strf + 8 + 8, static_cast<std::uint32_t>(claim.y));
    const fs::path file = dir / "lying.avi";
    writeBytes(file, lying);
    const VideoClip clip = loadVideo(file);
    const std::string label = std::to_string(claim.x) + "×" + std::to_string(claim.y);
    if (claim.y * 3 > 48 * 4) {
      EXPECT_EQ(clip.size.x, 64) << label;
      continue;
    }
    ASSERT_EQ(clip.frames.size(), 3u) << label;
    EXPECT_EQ(clip.size, glm::ivec2(64, 48)) << label;
    for (std::size_t i = 0; i < clip.frames.size(); ++i) {
      EXPECT_TRUE(clip.frames[i] == truth.frames[i]) << "header " << label << ", frame " << i;
    }
  }

  // Raw Motion-JPEG (concatenated JPEGs, which FFmpeg reads as a stream) whose pictures change size.
  const std::vector<std::string> big = jpegFrames(avi);
  const std::vector<std::string> small = jpegFrames(readBytes(dir / "small.avi"));
  ASSERT_EQ(big.size(), 3u);
  ASSERT_EQ(small.size(), 3u);
  writeBytes(dir / "shrinks.mjpeg", big[0] + big[1] + small[2]);
  writeBytes(dir / "grows.mjpeg", small[0] + big[1] + big[2]);
  const std::string shrinks = (dir / "shrinks.mjpeg").string();
  try {
    (void)loadVideo(shrinks);
    ADD_FAILURE() << "the third picture is 32×24";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), shrinks + ": frame 2 is 32×24 pixels, frame 0 is 64×48");
  }
  EXPECT_THROW((void)loadVideo(dir / "grows.mjpeg"), Error);
  const VideoClip firstTwo = loadVideo(shrinks, 2);
  ASSERT_EQ(firstTwo.frames.size(), 2u);
  EXPECT_TRUE(firstTwo.truncated);
  EXPECT_TRUE(firstTwo.frames[1] == truth.frames[1]);
}

TEST(FoldFlow, SyntheticClipIsDeterministicAndMovesExactly) {
  // A whole-pixel translation makes the next frame an exact shift of this one (same texture coordinates).
  SyntheticMotion shift;
  shift.translation = Vec2(2.0, -1.0);
  const VideoClip clip = syntheticVideo({64, 48}, 3, shift, 9, 12.5);
  ASSERT_EQ(clip.frames.size(), 3u);
  EXPECT_EQ(clip.timesS, (std::vector<double>{0.0, 0.08, 0.16}));
  EXPECT_TRUE(clip.frames == syntheticVideo({64, 48}, 3, shift, 9, 12.5).frames);
  EXPECT_FALSE(clip.frames == syntheticVideo({64, 48}, 3, shift, 10, 12.5).frames) << "the seed matters";
  int moved = 0;
  for (int y = 0; y < 47; ++y) {
    for (int x = 2; x < 64; ++x) {
      for (int c = 0; c < 4; ++c) {
        ASSERT_EQ(clip.frames[1].get(x, y, c), clip.frames[0].get(x - 2, y + 1, c)) << x << ", " << y;
      }
      moved += clip.frames[1].get(x, y, 0) != clip.frames[0].get(x, y, 0);
    }
  }
  EXPECT_GT(moved, 47 * 62 / 2) << "the texture has structure at every pixel";
  // The known flow: the translation outside the disc, the disc's similarity inside.
  SyntheticMotion disc = knownMotion();
  EXPECT_EQ(disc.flowAt(Vec2(10, 10)), disc.translation);
  const Vec2 p = disc.centre + Vec2(10.0, 0.0);
  const Vec2 expected = disc.centre + 1.03 * Vec2(10.0 * std::cos(0.04), 10.0 * std::sin(0.04)) - p;
  EXPECT_NEAR(glm::length(disc.flowAt(p) - expected), 0.0, 1e-12);
  EXPECT_THROW((void)syntheticVideo({8, 8}, 2, shift), Error);
}

TEST(FoldFlow, LoaderErrorsAreOneLineNamingTheFile) {
  SYLVA_SKIP_UNDER_TSAN();
  const test::TempDir dir;
  auto message = [](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  const std::string missing = (dir / "none.avi").string();
  EXPECT_EQ(message([&] { (void)loadVideo(missing); }), missing + ": no such file");
  std::ofstream(dir / "junk.avi") << "RIFF this is not a video at all, just some text";
  const std::string junk = (dir / "junk.avi").string();
  EXPECT_THAT(message([&] { (void)loadVideo(junk); }),
              testing::StartsWith(junk + ": cannot decode: not a video FFmpeg can read"));
  std::ofstream(dir / "empty.mp4");
  EXPECT_THAT(message([&] { (void)loadVideo(dir / "empty.mp4"); }),
              testing::StartsWith((dir / "empty.mp4").string() + ": cannot decode"));
  EXPECT_THAT(message([&] { (void)loadVideo(dir.path()); }), testing::HasSubstr("is a directory"));
  EXPECT_THAT(message([&] { (void)loadVideo(dir / "nothing/%04d.png"); }),
              testing::HasSubstr("no such directory"));
  EXPECT_THAT(message([&] { (void)loadVideo(dir / "%04d.png"); }),
              testing::HasSubstr("no image matches the pattern"));
  EXPECT_THAT(message([&] { (void)loadVideo(junk, 0); }), testing::HasSubstr("at least one frame"));
  for (const std::string& m :
       {message([&] { (void)loadVideo(junk); }), message([&] { (void)loadVideo(missing); })}) {
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  EXPECT_THAT(message([&] { saveVideo(dir / "x.mp4", loadedClip()); }),
              testing::HasSubstr("Motion-JPEG .avi"));
  EXPECT_FALSE(fs::exists(dir / "x.mp4"));
  EXPECT_THAT(message([&] {
                (void)computeFlow(Image(32, 32, 4, PixelType::U8), Image(32, 16, 4, PixelType::U8),
                                  FlowMethod::Dis);
              }),
              testing::HasSubstr("differ in size"));
}

// ---------------------------------------------------------------------------------------------------------
// Flow accuracy

/**
 * Bounds on the endpoint error, frame pixels. Measured on frames 2 → 3 (Release, OpenCV 4.6): DIS background
 * mean 0.014 / max 0.115, disc mean 0.066 / max 0.261; Farnebäck 0.011 / 0.114 and 0.057 / 0.195. The bounds
 * leave about 3× on the means and 2× on the maxima for other OpenCV builds and thread counts.
 */
struct MethodCase {
  FlowMethod method;
  double backgroundMean;
  double discMean;
  double max; ///< over both regions
};

class FoldFlowAccuracy : public testing::TestWithParam<MethodCase> {};

TEST_P(FoldFlowAccuracy, RecoversTheKnownMotion) {
  SYLVA_SKIP_UNDER_TSAN();
  const VideoClip& clip = loadedClip();
  const FlowField flow = computeFlow(clip.frames[2], clip.frames[3], GetParam().method);
  ASSERT_EQ(flow.width, kSize.x);
  ASSERT_EQ(flow.height, kSize.y);
  const Epe bg = endpointError(flow, Region::Background);
  const Epe disc = endpointError(flow, Region::Disc);
  std::printf("%s: background EPE mean %.3f max %.3f px (%zu texels); disc EPE mean %.3f max %.3f px (%zu)\n",
              flowMethodName(GetParam().method), bg.mean, bg.max, bg.texels, disc.mean, disc.max,
              disc.texels);
  RecordProperty("background_epe_mean_px", std::to_string(bg.mean));
  RecordProperty("disc_epe_mean_px", std::to_string(disc.mean));
  EXPECT_LE(bg.mean, GetParam().backgroundMean);
  EXPECT_LE(disc.mean, GetParam().discMean);
  EXPECT_LE(bg.max, GetParam().max);
  EXPECT_LE(disc.max, GetParam().max);
  // The mean is a real measurement: the known motion shifted by a quarter pixel fails it.
  FlowField off = flow;
  for (glm::vec2& v : off.v) {
    v += glm::vec2(0.25f + static_cast<float>(GetParam().backgroundMean), 0.0f);
  }
  EXPECT_GT(endpointError(off, Region::Background).mean, GetParam().backgroundMean);
}

INSTANTIATE_TEST_SUITE_P(Methods, FoldFlowAccuracy,
                         testing::Values(MethodCase{FlowMethod::Dis, 0.05, 0.2, 0.5},
                                         MethodCase{FlowMethod::Farneback, 0.05, 0.2, 0.5}),
                         [](const auto& info) { return std::string(flowMethodName(info.param.method)); });

// ---------------------------------------------------------------------------------------------------------
// Suggestions

/** The known motion at frame point p, times the mapping's scale: what a pair's vector must be. */
Vec2 expectedVector(const FlowSuggestStats& stats, Vec2 framePoint) {
  return knownMotion().flowAt(framePoint) * stats.imagePerFramePx;
}

TEST(FoldFlow, SuggestionsCarryTheKnownMotionIntoTheZone) {
  SYLVA_SKIP_UNDER_TSAN();
  const VideoClip& clip = loadedClip();
  const FlowField forward = computeFlow(clip.frames[2], clip.frames[3], FlowMethod::Dis);
  const FlowField backward = computeFlow(clip.frames[3], clip.frames[2], FlowMethod::Dis);
  const glm::ivec2 imageSize(512, 384);

  // Mapping onto the zone's box: the frame (256×192) lands on a 128×96 eye zone, so vectors halve.
  const Shape zone = rect(Vec2(160, 120), Vec2(288, 216));
  FlowSuggestOptions options;
  options.spacingPx = 4.0;
  options.minMagnitudePx = 0.2;
  options.maxAnchors = 100000;
  FlowSuggestStats stats;
  const auto pairs = suggestAnchors(forward, zone, imageSize, options, &backward, &stats);
  EXPECT_EQ(stats.imagePerFramePx, glm::dvec2(0.5, 0.5));
  EXPECT_EQ(stats.samples, 32u * 24u);
  ASSERT_GT(pairs.size(), stats.samples / 2);
  EXPECT_GT(stats.irregular + stats.inconsistent, 0u) << "the disc's rim must be dropped";
  EXPECT_EQ(stats.samples, pairs.size() + stats.irregular + stats.inconsistent + stats.still + stats.thinned);
  std::size_t checked = 0;
  double worst = 0.0;
  for (const auto& [a, b] : pairs) {
    EXPECT_TRUE(insidePolygon(zone.outline(), a)) << a.x << ", " << a.y;
    const Vec2 p = (a - Vec2(160, 120)) / 0.5;
    // Samples whose window reaches across the rim average two motions; away from it, the known motion.
    const double d = glm::length(p - knownMotion().centre);
    if (std::abs(d - knownMotion().radius) < 12.0 || p.x < 16 || p.y < 16 || p.x > 240 || p.y > 176) {
      continue;
    }
    const double err = glm::length((b - a) - expectedVector(stats, p));
    worst = std::max(worst, err);
    ++checked;
  }
  std::printf("zone mapping: %zu pairs of %zu samples, %zu checked, worst error %.3f image px\n",
              pairs.size(), stats.samples, checked, worst);
  EXPECT_GT(checked, pairs.size() / 2);
  // Measured 0.117 image pixels (0.23 frame pixels at this mapping); the bound is the flow's 0.5 px maximum.
  EXPECT_LE(worst, 0.25);

  // Mapping onto the whole image and a triangular zone: vectors double and stay inside the triangle.
  Shape triangle;
  triangle.type = Shape::Type::Polygon;
  triangle.pts = {Vec2(40, 40), Vec2(480, 60), Vec2(100, 360)};
  options.mapping = FlowSuggestOptions::Mapping::Image;
  options.spacingPx = 12.0;
  const auto wide = suggestAnchors(forward, triangle, imageSize, options, &backward, &stats);
  EXPECT_EQ(stats.imagePerFramePx, glm::dvec2(2.0, 2.0));
  ASSERT_FALSE(wide.empty());
  for (const auto& [a, b] : wide) {
    EXPECT_TRUE(insidePolygon(triangle.pts, a));
    const Vec2 p = a / 2.0;
    if (glm::length(p - knownMotion().centre) < knownMotion().radius + 12.0 || p.x < 16 || p.y < 16) {
      continue;
    }
    EXPECT_NEAR(b.x - a.x, 5.0, 0.6);
    EXPECT_NEAR(b.y - a.y, -2.5, 0.6);
  }
}

TEST(FoldFlow, SuggestionOptionsScaleDropAndThinDeterministically) {
  SYLVA_SKIP_UNDER_TSAN();
  const VideoClip& clip = loadedClip();
  const FlowField forward = computeFlow(clip.frames[2], clip.frames[3], FlowMethod::Dis);
  const Shape zone = rect(Vec2(0, 0), Vec2(256, 192));
  FlowSuggestOptions options;
  options.spacingPx = 8.0;
  options.maxAnchors = 100000;
  options.minMagnitudePx = 0.0; // so scaling keeps the same samples
  FlowSuggestStats stats;
  const auto all = suggestAnchors(forward, zone, kSize, options, nullptr, &stats);
  ASSERT_GT(all.size(), 100u);
  EXPECT_EQ(stats.inconsistent, 0u) << "no backward flow, no consistency check";

  options.scale = 2.0;
  const auto doubled = suggestAnchors(forward, zone, kSize, options);
  ASSERT_EQ(doubled.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(doubled[i][0], all[i][0]);
    EXPECT_NEAR(glm::length((doubled[i][1] - doubled[i][0]) - 2.0 * (all[i][1] - all[i][0])), 0.0, 2e-3);
  }

  options.scale = 1.0;
  options.maxAnchors = 7;
  const auto thinned = suggestAnchors(forward, zone, kSize, options, nullptr, &stats);
  ASSERT_EQ(thinned.size(), 7u);
  EXPECT_EQ(stats.thinned, all.size() - 7);
  EXPECT_EQ(thinned, suggestAnchors(forward, zone, kSize, options));
  for (const auto& pair : thinned) {
    EXPECT_NE(std::find(all.begin(), all.end(), pair), all.end());
  }
  EXPECT_LT(thinned.front()[0].y, 40.0);
  EXPECT_GT(thinned.back()[0].y, 150.0) << "thinning keeps the whole zone covered";

  // Everything moves by at least ~1.6 px here; a 50 px minimum drops all of it as still.
  options.minMagnitudePx = 50.0;
  EXPECT_TRUE(suggestAnchors(forward, zone, kSize, options, nullptr, &stats).empty());
  EXPECT_EQ(stats.still + stats.irregular, stats.samples);

  options.minMagnitudePx = 0.5;
  options.spacingPx = 0.0;
  EXPECT_THROW((void)suggestAnchors(forward, zone, kSize, options), Error);
  options.spacingPx = 8.0;
  EXPECT_THROW((void)suggestAnchors(FlowField{}, zone, kSize, options), Error);
}

TEST(FoldFlow, AcceptingASuggestionIsOneEditThatUndoesByteForByte) {
  SYLVA_SKIP_UNDER_TSAN();
  const VideoClip& clip = loadedClip();
  const FlowField forward = computeFlow(clip.frames[0], clip.frames[1], FlowMethod::Dis);
  const Project start = projectWithZone(rect(Vec2(160, 120), Vec2(288, 216)));
  const auto pairs = suggestAnchors(forward, start.zones[0].shape, {512, 384}, FlowSuggestOptions{});
  ASSERT_FALSE(pairs.empty());

  EditHistory history(start);
  const std::string before = toJson(history.project()).dump();
  applyFlowSuggestion(history, 0, pairs);
  EXPECT_EQ(history.undoNames(), std::vector<std::string>{"motion from video"});
  ASSERT_EQ(history.project().zones[0].tools.size(), 1u);
  const auto* points = std::get_if<PointsTool>(&history.project().zones[0].tools[0]);
  ASSERT_NE(points, nullptr);
  EXPECT_EQ(points->pairs, pairs);
  const std::string after = toJson(history.project()).dump();
  EXPECT_NE(after, before);

  EXPECT_EQ(history.undo().name, "motion from video");
  EXPECT_EQ(toJson(history.project()).dump(), before);
  history.redo();
  EXPECT_EQ(toJson(history.project()).dump(), after);

  // Nothing to accept, or no such zone: an error, and the history is untouched.
  EXPECT_THROW(applyFlowSuggestion(history, 0, {}), Error);
  EXPECT_THROW(applyFlowSuggestion(history, 3, pairs), Error);
  EXPECT_EQ(history.undoNames().size(), 1u);
  EXPECT_EQ(toJson(history.project()).dump(), after);
}

TEST(FoldFlow, FlowPictureColoursDirectionAndMagnitude) {
  FlowField f;
  f.width = 4;
  f.height = 1;
  f.v = {glm::vec2(2, 0), glm::vec2(0, 2), glm::vec2(-1, 0), glm::vec2(0, 0)};
  const Image picture = flowPicture(f, 2.0);
  auto rgb = [&](int x) {
    return glm::ivec3(std::lround(picture.get(x, 0, 0) * 255), std::lround(picture.get(x, 0, 1) * 255),
                      std::lround(picture.get(x, 0, 2) * 255));
  };
  EXPECT_EQ(rgb(0), glm::ivec3(255, 0, 0)) << "right: red at full value";
  EXPECT_EQ(rgb(1), glm::ivec3(128, 255, 0)) << "down: a quarter turn, yellow-green";
  EXPECT_EQ(rgb(2), glm::ivec3(0, 128, 128)) << "left: cyan at half value";
  EXPECT_EQ(rgb(3), glm::ivec3(0, 0, 0)) << "still: black";
  EXPECT_EQ(picture.get(3, 0, 3), 1.0f);
}

// ---------------------------------------------------------------------------------------------------------
// A real clip

TEST(FoldFlow, RealClipOfASwayingTree) {
  SYLVA_SKIP_UNDER_TSAN();
  const fs::path file = test::externalData("tree.avi");
  SYLVA_REQUIRE_EXTERNAL_DATA(file);
  const VideoClip clip = loadVideo(file);
  // The AVI index lists 444 frames over 29.6 s, but only 68 carry pictures (the rest repeat the previous one,
  // as empty chunks); FFmpeg decodes those 68 at their real times, about 0.4 s apart.
  ASSERT_EQ(clip.frames.size(), 68u);
  EXPECT_EQ(clip.size, glm::ivec2(320, 240));
  EXPECT_NEAR(clip.fps, 15.0, 0.01);
  for (std::size_t i = 1; i < clip.timesS.size(); ++i) {
    ASSERT_GT(clip.timesS[i], clip.timesS[i - 1]);
  }
  // Frames 48 → 49: the crown sways in the wind (from frame 53 on, a hand enters the picture).
  const FlowField forward = computeFlow(clip.frames[48], clip.frames[49], FlowMethod::Dis);
  const FlowField backward = computeFlow(clip.frames[49], clip.frames[48], FlowMethod::Dis);
  for (const glm::vec2& v : forward.v) {
    ASSERT_TRUE(std::isfinite(v.x) && std::isfinite(v.y));
  }
  const double consistent = consistentFraction(forward, backward, 1.0);
  FlowSuggestOptions options;
  options.spacingPx = 8.0;
  options.minMagnitudePx = 0.25;
  options.mapping = FlowSuggestOptions::Mapping::Image;
  FlowSuggestStats stats;
  const Shape crown = rect(Vec2(60, 30), Vec2(240, 200));
  const auto pairs = suggestAnchors(forward, crown, clip.size, options, &backward, &stats);
  std::printf(
      "tree.avi: %zu frames, %.2f s apart (48 → 49); flow mean %.3f px, max %.3f px; %.1f %% consistent "
      "within 1 px; crown: %zu of %zu samples suggested\n",
      clip.frames.size(), clip.timesS[49] - clip.timesS[48], forward.meanMagnitude(), forward.maxMagnitude(),
      100.0 * consistent, pairs.size(), stats.samples);
  RecordProperty("mean_magnitude_px", std::to_string(forward.meanMagnitude()));
  RecordProperty("consistent_fraction", std::to_string(consistent));
  EXPECT_GT(consistent, 0.95);
  EXPECT_FALSE(pairs.empty());
}

} // namespace
} // namespace sylva::folding
