// Image sizes from file headers (PNG: ISO/IEC 15948 §11.2.2; JPEG: ITU T.81 §B.1–B.2; WebP: RFC 9649
// §2.5–2.7; TIFF 6.0 §2 and §8; BMP: the BITMAPCOREHEADER and BITMAPINFOHEADER layouts; OpenEXR: the
// file layout's header attributes).
#include <sylva/core/ImageHeader.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <string>

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

std::optional<ImageHeader> tiffHeader(std::ifstream& in, bool little) {
  // Header: byte order (2), 42 (2), offset of the first IFD (4). IFD: entry count (2), then 12-byte entries
  // of tag (2), type (2), count (4), value or offset (4); a SHORT or LONG value sits at the start of its
  // field. ImageWidth is tag 256, ImageLength 257. Entries are sorted by tag, so the walk stops past 257.
  const auto number = [little](const std::uint8_t* p, int bytes) {
    return little ? littleEndian(p, bytes) : bigEndian(p, bytes);
  };
  std::array<std::uint8_t, 4> offset{};
  in.seekg(4);
  if (!readBytes(in, offset)) {
    return std::nullopt;
  }
  in.seekg(static_cast<std::streamoff>(number(offset.data(), 4)));
  std::array<std::uint8_t, 2> count{};
  if (!in || !readBytes(in, count)) {
    return std::nullopt;
  }
  std::optional<std::uint32_t> width;
  std::optional<std::uint32_t> height;
  for (std::uint32_t i = 0, n = number(count.data(), 2); i < n && !(width && height); ++i) {
    std::array<std::uint8_t, 12> entry{};
    if (!readBytes(in, entry)) {
      return std::nullopt;
    }
    const std::uint32_t tag = number(&entry[0], 2);
    const std::uint32_t type = number(&entry[2], 2);
    if (tag > 257) {
      break;
    }
    if ((tag == 256 || tag == 257) && (type == 3 || type == 4)) {
      (tag == 256 ? width : height) = number(&entry[8], type == 3 ? 2 : 4);
    }
  }
  if (!width || !height) {
    return std::nullopt;
  }
  return ImageHeader{"TIFF", side(*width), side(*height)};
}

std::optional<ImageHeader> bmpHeader(std::ifstream& in) {
  // File header (14), then the DIB header's size (4): 12 for the OS/2 core header (16-bit width and height),
  // 40 or more for the Windows ones (signed 32-bit width and height; a negative height is a top-down bitmap).
  std::array<std::uint8_t, 12> dib{};
  in.seekg(14);
  if (!readBytes(in, dib)) {
    return std::nullopt;
  }
  const std::uint32_t size = littleEndian(&dib[0], 4);
  if (size == 12) {
    return ImageHeader{"BMP", side(littleEndian(&dib[4], 2)), side(littleEndian(&dib[6], 2))};
  }
  if (size < 40) {
    return std::nullopt;
  }
  const auto magnitude = [](std::uint32_t v) {
    return v & 0x80000000u ? ~v + 1u : v; // |int32|, without overflow for INT32_MIN
  };
  return ImageHeader{"BMP", side(magnitude(littleEndian(&dib[4], 4))),
                     side(magnitude(littleEndian(&dib[8], 4)))};
}

std::optional<ImageHeader> exrHeader(std::ifstream& in) {
  // Magic (4) and version (4), then attributes: name, type name (each NUL-terminated, at most 255 bytes),
  // size (int32), value; an empty name ends the header. The size is the data window, a box2i: xMin, yMin,
  // xMax, yMax (int32), inclusive.
  in.seekg(8);
  const auto text = [&in](std::string& out) {
    out.clear();
    for (char c = 0; in.get(c);) {
      if (c == '\0') {
        return true;
      }
      if (out.size() == 255) {
        return false;
      }
      out.push_back(c);
    }
    return false;
  };
  for (int attribute = 0; attribute < 4096; ++attribute) {
    std::string name;
    std::string type;
    if (!text(name) || name.empty() || !text(type)) {
      return std::nullopt;
    }
    std::array<std::uint8_t, 4> size{};
    if (!readBytes(in, size)) {
      return std::nullopt;
    }
    const std::uint32_t n = littleEndian(size.data(), 4);
    if (name == "dataWindow" && type == "box2i" && n == 16) {
      std::array<std::uint8_t, 16> box{};
      if (!readBytes(in, box)) {
        return std::nullopt;
      }
      const auto at = [&box](int i) {
        return static_cast<std::int64_t>(static_cast<std::int32_t>(littleEndian(&box[4 * i], 4)));
      };
      const std::int64_t w = at(2) - at(0) + 1;
      const std::int64_t h = at(3) - at(1) + 1;
      const auto clampSide = [](std::int64_t v) {
        return static_cast<int>(std::clamp<std::int64_t>(v, 0, 0x7fffffff));
      };
      return ImageHeader{"OpenEXR", clampSide(w), clampSide(h)};
    }
    in.seekg(static_cast<std::streamoff>(n), std::ios::cur);
    if (!in) {
      return std::nullopt;
    }
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
  if (n >= 4 && ((start[0] == 'I' && start[1] == 'I' && start[2] == 42 && start[3] == 0) ||
                 (start[0] == 'M' && start[1] == 'M' && start[2] == 0 && start[3] == 42))) {
    return tiffHeader(in, start[0] == 'I');
  }
  if (n >= 2 && start[0] == 'B' && start[1] == 'M') {
    return bmpHeader(in);
  }
  if (n >= 4 && start[0] == 0x76 && start[1] == 0x2f && start[2] == 0x31 && start[3] == 0x01) {
    return exrHeader(in);
  }
  return std::nullopt;
}

} // namespace sylva
