// Image sizes from file headers: real files (a PNG written by savePng, the JPEG seed of the flow fuzz target,
// the progressive JPEG that claims 20000×20000 pixels) and hand-built headers for each path through the JPEG
// marker walk, the three WebP chunk kinds, TIFF in both byte orders, BMP's two header kinds and OpenEXR (a
// real file from saveImage and a hand-built header); anything else and any header cut short is "unknown", not
// a size.
#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/ImageHeader.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <fstream>
#include <vector>

namespace sylva {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::optional<ImageHeader> headerOf(const test::TempDir& dir, const Bytes& bytes) {
  const std::filesystem::path path = dir / "image.bin";
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return readImageHeader(path);
}

/** SOI, an APP0 segment, fill bytes, a restart marker, then a frame header SOFn of width × height. */
Bytes jpeg(std::uint8_t sof, int width, int height) {
  Bytes b = {0xFF, 0xD8, 0xFF, 0xE0, 0x00, 0x06, 'J', 'F', 'I', 'F', 0xFF, 0xFF, 0xFF, 0xD3};
  const Bytes frame = {0xFF,
                       sof,
                       0x00,
                       0x0B,
                       0x08,
                       static_cast<std::uint8_t>(height >> 8),
                       static_cast<std::uint8_t>(height),
                       static_cast<std::uint8_t>(width >> 8),
                       static_cast<std::uint8_t>(width),
                       0x01,
                       0x01,
                       0x11,
                       0x00};
  b.insert(b.end(), frame.begin(), frame.end());
  return b;
}

Bytes webp(const char* fourcc, const Bytes& payload) {
  Bytes b = {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E', 'B', 'P'};
  b.insert(b.end(), fourcc, fourcc + 4);
  b.insert(b.end(), {static_cast<std::uint8_t>(payload.size()), 0, 0, 0});
  b.insert(b.end(), payload.begin(), payload.end());
  return b;
}

void expectSize(const std::optional<ImageHeader>& header, const char* format, int width, int height) {
  ASSERT_TRUE(header.has_value());
  EXPECT_EQ(header->format, format);
  EXPECT_EQ(header->width, width);
  EXPECT_EQ(header->height, height);
}

TEST(ImageHeader, ReadsTheSizeOfRealFiles) {
  test::TempDir dir;
  Image image(37, 19, 4, PixelType::U16);
  savePng(dir / "a.png", image);
  expectSize(readImageHeader(dir / "a.png"), "PNG", 37, 19);
  expectSize(readImageHeader(test::sourcePath("fuzz/corpus/flow/jpeg-16x16.jpg")), "JPEG", 16, 16);
  expectSize(
      readImageHeader(test::sourcePath("fuzz/regressions/flow/jpeg-progressive-claims-20000x20000.jpg")),
      "JPEG", 20000, 20000);
}

TEST(ImageHeader, WalksJpegSegmentsToTheFirstFrameHeader) {
  test::TempDir dir;
  expectSize(headerOf(dir, jpeg(0xC0, 640, 480)), "JPEG", 640, 480); // baseline
  expectSize(headerOf(dir, jpeg(0xC2, 65535, 3)), "JPEG", 65535, 3); // progressive
  expectSize(headerOf(dir, jpeg(0xCF, 1, 2)), "JPEG", 1, 2);         // lossless arithmetic
  // DHT, JPG and DAC share the SOFn range but are not frame headers: their 11 bytes are skipped.
  Bytes dht = jpeg(0xC4, 9999, 9999);
  const Bytes sof = jpeg(0xC0, 12, 34);
  dht.insert(dht.end(), sof.begin() + 2, sof.end());
  expectSize(headerOf(dir, dht), "JPEG", 12, 34);
  // libjpeg skips bytes that are not a marker ("extraneous bytes") and stuffed zeros, and decodes on: so does
  // the walk (the flow fuzz target's second finding hid a 28535×26220 frame header behind one such byte).
  Bytes junk = {0xFF, 0xD8, '(', '(', 0xFF, 0x00, 0x17};
  junk.insert(junk.end(), sof.begin() + 2, sof.end());
  expectSize(headerOf(dir, junk), "JPEG", 12, 34);
  expectSize(
      readImageHeader(test::sourcePath("fuzz/regressions/flow/jpeg-extraneous-bytes-hide-26220x28535.jpg")),
      "JPEG", 28535, 26220);
}

TEST(ImageHeader, ReadsEachWebPChunkKind) {
  test::TempDir dir;
  // Lossy: frame tag, start code, 14-bit sides (the top two bits are a scale and not part of the size).
  expectSize(headerOf(dir, webp("VP8 ", {0, 0, 0, 0x9d, 0x01, 0x2a, 0x40, 0xC1, 0xF0, 0x40})), "WebP", 320,
             240);
  // Lossless: 14 bits width − 1 then 14 bits height − 1: 100 × 50.
  const std::uint32_t bits = 99u | (49u << 14);
  expectSize(
      headerOf(dir, webp("VP8L", {0x2f, static_cast<std::uint8_t>(bits), static_cast<std::uint8_t>(bits >> 8),
                                  static_cast<std::uint8_t>(bits >> 16),
                                  static_cast<std::uint8_t>(bits >> 24), 0, 0, 0, 0, 0})),
      "WebP", 100, 50);
  // Extended: 24-bit canvas width − 1 and height − 1, beyond what a VP8 frame can hold.
  expectSize(headerOf(dir, webp("VP8X", {0, 0, 0, 0, 0x3F, 0x42, 0x0F, 0x01, 0x00, 0x00})), "WebP", 1000000,
             2);
}

/** A TIFF header in either byte order and one directory of (tag, type, value) entries, 3 = SHORT, 4 = LONG.
 */
Bytes tiff(bool little, const std::vector<std::array<std::uint32_t, 3>>& entries) {
  const auto put = [little](Bytes& b, std::uint32_t v, int bytes) {
    for (int i = 0; i < bytes; ++i) {
      const int shift = 8 * (little ? i : bytes - 1 - i);
      b.push_back(static_cast<std::uint8_t>(v >> shift));
    }
  };
  Bytes b = little ? Bytes{'I', 'I', 42, 0} : Bytes{'M', 'M', 0, 42};
  put(b, 8, 4);
  put(b, static_cast<std::uint32_t>(entries.size()), 2);
  for (const auto& [tag, type, value] : entries) {
    put(b, tag, 2);
    put(b, type, 2);
    put(b, 1, 4);
    put(b, value, type == 3 ? 2 : 4); // a SHORT sits at the start of its 4-byte field
    if (type == 3) {
      put(b, 0, 2);
    }
  }
  put(b, 0, 4); // no next directory
  return b;
}

/** Little-endian bytes of v. */
Bytes le(std::uint32_t v, int bytes) {
  Bytes b;
  for (int i = 0; i < bytes; ++i) {
    b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  return b;
}

Bytes operator+(Bytes a, const Bytes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

Bytes text(const char* s) {
  Bytes b(s, s + std::char_traits<char>::length(s));
  b.push_back(0);
  return b;
}

TEST(ImageHeader, ReadsTiffBmpAndOpenExrHeaders) {
  test::TempDir dir;
  // TIFF, both byte orders, SHORT and LONG sizes, other tags before them.
  expectSize(headerOf(dir, tiff(true, {{254, 4, 0}, {256, 3, 640}, {257, 4, 480}})), "TIFF", 640, 480);
  expectSize(headerOf(dir, tiff(false, {{256, 4, 20000}, {257, 3, 3}, {258, 3, 8}})), "TIFF", 20000, 3);
  // BMP: the OS/2 core header (16-bit sides), and the info header with a top-down (negative) height.
  const Bytes bmpFile = {'B', 'M', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  expectSize(headerOf(dir, bmpFile + le(12, 4) + le(300, 2) + le(200, 2) + le(1, 2) + le(24, 2)), "BMP", 300,
             200);
  expectSize(headerOf(dir, bmpFile + le(40, 4) + le(20000, 4) + le(static_cast<std::uint32_t>(-20000), 4)),
             "BMP", 20000, 20000);
  // OpenEXR: a real file, and a header whose data window starts off the origin after other attributes.
  Image image(37, 19, 4, PixelType::F32);
  saveImage(dir / "a.exr", image);
  expectSize(readImageHeader(dir / "a.exr"), "OpenEXR", 37, 19);
  const Bytes exr = Bytes{0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0} + text("compression") + text("compression") +
                    le(1, 4) + Bytes{0} + text("dataWindow") + text("box2i") + le(16, 4) +
                    le(static_cast<std::uint32_t>(-10), 4) + le(static_cast<std::uint32_t>(-5), 4) +
                    le(9, 4) + le(4, 4) + Bytes{0};
  expectSize(headerOf(dir, exr), "OpenEXR", 20, 10);
  // Cut short, or without the size: unknown.
  Bytes cutTiff = tiff(true, {{256, 3, 640}, {257, 4, 480}});
  cutTiff.resize(20);
  EXPECT_FALSE(headerOf(dir, cutTiff).has_value());
  EXPECT_FALSE(headerOf(dir, tiff(true, {{256, 3, 640}})).has_value()); // no ImageLength
  EXPECT_FALSE(
      headerOf(dir, {'I', 'I', 42, 0, 0xFF, 0xFF, 0xFF, 0x7F}).has_value()); // directory past the end
  EXPECT_FALSE(headerOf(dir, bmpFile + le(20, 4) + le(1, 4) + le(1, 4)).has_value()); // no such DIB header
  Bytes cutExr = exr;
  cutExr.resize(exr.size() - 10);
  EXPECT_FALSE(headerOf(dir, cutExr).has_value());
}

Bytes ascii(const char* s) {
  return Bytes(s, s + std::char_traits<char>::length(s));
}

Bytes be(std::uint32_t v) {
  return {static_cast<std::uint8_t>(v >> 24), static_cast<std::uint8_t>(v >> 16),
          static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)};
}

TEST(ImageHeader, ReadsTheOtherFormatsOpenCvDecodes) {
  test::TempDir dir;
  // Netpbm: PPM with a comment between the sides, PBM, PFM (OpenCV decodes it to 3 floats a pixel), PAM.
  expectSize(headerOf(dir, ascii("P6\n# made by hand\n640 # width\n480\n255\n")), "PNM", 640, 480);
  expectSize(headerOf(dir, ascii("P1 3 2 0 1 0 1 0 1")), "PNM", 3, 2);
  expectSize(headerOf(dir, ascii("Pf\n13000 7\n-1.0\n")), "PFM", 13000, 7);
  expectSize(
      headerOf(dir, ascii("P7\nDEPTH 4\nHEIGHT 20\nMAXVAL 255\nWIDTH 30\nTUPLTYPE RGB_ALPHA\nENDHDR\n")),
      "PAM", 30, 20);
  expectSize(headerOf(dir, ascii("P5 99999999999999 2 255")), "PNM", 0x7fffffff, 2); // saturated
  // Sun raster: magic, width, height (big-endian).
  expectSize(headerOf(dir, be(0x59a66a95) + be(20000) + be(3) + be(24)), "Sun raster", 20000, 3);
  // Radiance: header lines, a blank line, then the resolution line in either order.
  expectSize(headerOf(dir, ascii("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 480 +X 640\n")), "Radiance HDR",
             640, 480);
  expectSize(headerOf(dir, ascii("#?RGBE\n\n+X 7 -Y 9\n")), "Radiance HDR", 7, 9);
  expectSize(readImageHeader(test::sourcePath("fuzz/regressions/flow/radiance-claims-13000x13000.hdr")),
             "Radiance HDR", 13000, 13000);
  // JPEG 2000: a bare codestream's SIZ (the image offset is subtracted), and the same in a JP2 file after its
  // signature, file-type and header boxes.
  const Bytes siz = Bytes{0xFF, 0x4F, 0xFF, 0x51, 0, 41, 0, 0} + be(1100) + be(700) + be(100) + be(200) +
                    be(0) + be(0) + be(0) + be(0);
  expectSize(headerOf(dir, siz), "JPEG 2000", 1000, 500);
  const Bytes jp2 = Bytes{0, 0, 0, 12, 'j', 'P', ' ', ' ', '\r', '\n', 0x87, '\n'} + be(20) +
                    ascii("ftypjp2 ") + be(0) + ascii("jp2 ") + be(8) + ascii("jp2h") + be(0) +
                    ascii("jp2c") + siz;
  expectSize(headerOf(dir, jp2), "JPEG 2000", 1000, 500);
  // Cut short or malformed: unknown.
  EXPECT_FALSE(headerOf(dir, ascii("P6\n640")).has_value());
  EXPECT_FALSE(headerOf(dir, ascii("P6\n-640 480")).has_value());
  EXPECT_FALSE(headerOf(dir, ascii("P7\nWIDTH 3\nENDHDR\n")).has_value());
  EXPECT_FALSE(headerOf(dir, be(0x59a66a95) + be(20000)).has_value());
  EXPECT_FALSE(headerOf(dir, ascii("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n")).has_value());
  EXPECT_FALSE(headerOf(dir, ascii("#?RADIANCE\n\nY 480 X 640\n")).has_value());
  EXPECT_FALSE(headerOf(dir, Bytes(jp2.begin(), jp2.end() - 20)).has_value());
  EXPECT_FALSE(
      headerOf(dir, Bytes{0, 0, 0, 12, 'j', 'P', ' ', ' ', '\r', '\n', 0x87, '\n'} + be(3) + ascii("jp2h"))
          .has_value()); // a box shorter than its own header
}

TEST(ImageHeader, OtherFormatsAndCutHeadersAreUnknown) {
  test::TempDir dir;
  EXPECT_FALSE(headerOf(dir, {}).has_value());
  EXPECT_FALSE(headerOf(dir, {'B', 'M', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}).has_value());
  Bytes cut = jpeg(0xC0, 640, 480);
  cut.resize(cut.size() - 8); // inside the frame header
  EXPECT_FALSE(headerOf(dir, cut).has_value());
  EXPECT_FALSE(headerOf(dir, {0xFF, 0xD8, 0xFF, 0xDA, 0x00, 0x02}).has_value()); // a scan before any frame
  EXPECT_FALSE(headerOf(dir, {0xFF, 0xD8, 0xFF, 0xE1, 0xFF, 0xFF}).has_value()); // a segment past the end
  EXPECT_FALSE(
      headerOf(dir, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H'}).has_value());
  EXPECT_FALSE(headerOf(dir, webp("VP8 ", {0, 0, 0, 0, 0, 0, 1, 1, 1, 1})).has_value()); // no start code
  EXPECT_THROW((void)readImageHeader(dir / "missing.png"), Error);
}

} // namespace
} // namespace sylva
