// Image sizes from file headers (PNG: ISO/IEC 15948 §11.2.2; JPEG: ITU T.81 §B.1–B.2; WebP: RFC 9649
// §2.5–2.7).
#include <sylva/core/ImageHeader.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>

namespace sylva {

namespace {

/** Reads `n` bytes at the stream's position; false when the file ends first. */
template <std::size_t N>
bool readBytes(std::ifstream& in, std::array<std::uint8_t, N>& out, std::size_t n = N) {
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(n));
  return static_cast<std::size_t>(in.gcount()) == n;
}

std::uint32_t bigEndian(const std::uint8_t* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) {
    v = (v << 8) | p[i];
  }
  return v;
}

std::uint32_t littleEndian(const std::uint8_t* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) {
    v = (v << 8) | p[i];
  }
  return v;
}

/** Whether the four bytes at `p` spell `tag` (a RIFF or PNG chunk name). */
bool hasTag(const std::uint8_t* p, const char (&tag)[5]) {
  return std::equal(tag, tag + 4, p,
                    [](char t, std::uint8_t b) { return static_cast<std::uint8_t>(t) == b; });
}

/** The largest int for a stated size (PNG allows up to 2^31 − 1, so no stated size wraps negative). */
int side(std::uint32_t v) {
  return static_cast<int>(std::min<std::uint32_t>(v, 0x7fffffffu));
}

std::optional<ImageHeader> pngHeader(std::ifstream& in) {
  // Signature (8), IHDR length (4), "IHDR" (4), width (4), height (4).
  std::array<std::uint8_t, 16> rest{};
  if (!readBytes(in, rest) || !hasTag(&rest[4], "IHDR")) {
    return std::nullopt;
  }
  return ImageHeader{"PNG", side(bigEndian(&rest[8], 4)), side(bigEndian(&rest[12], 4))};
}

std::optional<ImageHeader> jpegHeader(std::ifstream& in) {
  // After SOI: segments, each 0xFF, fill bytes 0xFF, a marker byte, then (for all but RSTn/TEM) a 16-bit
  // big-endian length that counts itself. The first SOFn (0xC0–0xCF except DHT 0xC4, JPG 0xC8, DAC 0xCC)
  // holds precision (1), height (2), width (2). As libjpeg does, bytes before a 0xFF and a stuffed 0xFF00 are
  // skipped (it warns of "extraneous bytes" and goes on decoding), so no file it decodes hides its size here.
  for (;;) {
    std::array<std::uint8_t, 1> byte{};
    do {
      if (!readBytes(in, byte)) {
        return std::nullopt;
      }
    } while (byte[0] != 0xFF);
    do {
      if (!readBytes(in, byte)) {
        return std::nullopt;
      }
    } while (byte[0] == 0xFF);
    const std::uint8_t marker = byte[0];
    if (marker == 0x00 || marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {
      continue; // a stuffed zero, TEM, RSTn: no length
    }
    if (marker == 0xD8 || marker == 0xD9 || marker == 0xDA) {
      return std::nullopt; // a second SOI, EOI or a scan before any frame header
    }
    std::array<std::uint8_t, 2> length{};
    if (!readBytes(in, length)) {
      return std::nullopt;
    }
    const std::uint32_t n = bigEndian(length.data(), 2);
    if (n < 2) {
      return std::nullopt;
    }
    const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame) {
      std::array<std::uint8_t, 5> sof{};
      if (n < 2 + sof.size() || !readBytes(in, sof)) {
        return std::nullopt;
      }
      return ImageHeader{"JPEG", side(bigEndian(&sof[3], 2)), side(bigEndian(&sof[1], 2))};
    }
    in.seekg(n - 2, std::ios::cur);
    if (!in) {
      return std::nullopt;
    }
  }
}

std::optional<ImageHeader> webpHeader(std::ifstream& in) {
  // "RIFF" size "WEBP" (12 bytes, read), then the first chunk: fourcc (4), size (4), payload.
  std::array<std::uint8_t, 18> chunk{};
  if (!readBytes(in, chunk)) {
    return std::nullopt;
  }
  const std::uint8_t* p = &chunk[8];
  if (hasTag(chunk.data(), "VP8 ")) {
    // Lossy: a 3-byte frame tag, the start code 9d 01 2a, then 14-bit width and height (2 scale bits).
    if (p[3] != 0x9d || p[4] != 0x01 || p[5] != 0x2a) {
      return std::nullopt;
    }
    return ImageHeader{"WebP", side(littleEndian(&p[6], 2) & 0x3fff), side(littleEndian(&p[8], 2) & 0x3fff)};
  }
  if (hasTag(chunk.data(), "VP8L")) {
    // Lossless: signature 0x2f, then 14 bits width − 1 and 14 bits height − 1, least significant first.
    if (p[0] != 0x2f) {
      return std::nullopt;
    }
    const std::uint32_t bits = littleEndian(&p[1], 4);
    return ImageHeader{"WebP", side((bits & 0x3fff) + 1), side(((bits >> 14) & 0x3fff) + 1)};
  }
  if (hasTag(chunk.data(), "VP8X")) {
    // Extended: flags (4), then 24-bit canvas width − 1 and height − 1.
    return ImageHeader{"WebP", side(littleEndian(&p[4], 3) + 1), side(littleEndian(&p[7], 3) + 1)};
  }
  return std::nullopt;
}

} // namespace

std::optional<ImageHeader> readImageHeader(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("{}: cannot open the file", path.string());
  }
  std::array<std::uint8_t, 12> start{};
  in.read(reinterpret_cast<char*>(start.data()), start.size());
  const std::size_t n = static_cast<std::size_t>(in.gcount());
  in.clear();
  if (n >= 2 && start[0] == 0xFF && start[1] == 0xD8) {
    in.seekg(2);
    return jpegHeader(in);
  }
  constexpr std::array<std::uint8_t, 8> kPng = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (n >= kPng.size() && std::equal(kPng.begin(), kPng.end(), start.begin())) {
    in.seekg(static_cast<std::streamoff>(kPng.size()));
    return pngHeader(in);
  }
  if (n == start.size() && hasTag(&start[0], "RIFF") && hasTag(&start[8], "WEBP")) {
    return webpHeader(in);
  }
  return std::nullopt;
}

} // namespace sylva
