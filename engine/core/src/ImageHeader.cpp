// Image sizes from file headers (PNG: ISO/IEC 15948 §11.2.2; JPEG: ITU T.81 §B.1–B.2; WebP: RFC 9649
// §2.5–2.7; TIFF 6.0 §2 and §8; BMP: the BITMAPCOREHEADER and BITMAPINFOHEADER layouts; OpenEXR: the
// file layout's header attributes; Netpbm's PBM/PGM/PPM/PAM/PFM pages; Sun raster; Radiance's RGBE header;
// JPEG 2000: ISO/IEC 15444-1 §A.5.1 and Annex I). These are the formats OpenCV's image readers decode, except
// DICOM (GDCM), which callers handing files to OpenCV refuse as unknown.
#include <sylva/core/ImageHeader.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <optional>
#include <sstream>
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

/** Reads the next token of a Netpbm header: skips whitespace and `#` comments to the end of their line, then
 * reads up to 63 non-space bytes. Empty when the file ends first. */
std::string pnmToken(std::ifstream& in) {
  std::string token;
  for (char c = 0; in.get(c);) {
    if (c == '#' && token.empty()) {
      while (in.get(c) && c != '\n' && c != '\r') {
      }
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f') {
      if (token.empty()) {
        continue;
      }
      break;
    }
    if (token.size() == 63) {
      return {};
    }
    token.push_back(c);
  }
  return token;
}

/** A header's decimal number (digits only), saturated at 2^31 − 1; nullopt for anything else. */
std::optional<int> decimal(const std::string& token) {
  if (token.empty() || token.size() > 20 ||
      !std::all_of(token.begin(), token.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  std::uint64_t v = 0;
  for (const char c : token) {
    v = std::min<std::uint64_t>(v * 10 + static_cast<std::uint64_t>(c - '0'), 0x7fffffffu);
  }
  return static_cast<int>(v);
}

std::optional<ImageHeader> netpbmHeader(std::ifstream& in, char kind) {
  // PBM/PGM/PPM (P1–P6) and PFM (PF, Pf): the magic, then width and height as decimal tokens, with comments
  // allowed between them (Netpbm's and OpenCV's readers accept them in PFM too). PAM (P7): "WIDTH n",
  // "HEIGHT n" among other lines before ENDHDR.
  in.seekg(2);
  if (kind != '7') {
    const std::optional<int> width = decimal(pnmToken(in));
    const std::optional<int> height = width ? decimal(pnmToken(in)) : std::nullopt;
    if (!height) {
      return std::nullopt;
    }
    return ImageHeader{kind == 'F' || kind == 'f' ? "PFM" : "PNM", *width, *height};
  }
  std::optional<int> width;
  std::optional<int> height;
  for (int token = 0; token < 256 && !(width && height); ++token) {
    const std::string key = pnmToken(in);
    if (key.empty() || key == "ENDHDR") {
      return std::nullopt;
    }
    if (key == "WIDTH") {
      width = decimal(pnmToken(in));
    } else if (key == "HEIGHT") {
      height = decimal(pnmToken(in));
    }
  }
  if (!width || !height) {
    return std::nullopt;
  }
  return ImageHeader{"PAM", *width, *height};
}

std::optional<ImageHeader> sunRasterHeader(std::ifstream& in) {
  // Magic (4), then width and height as big-endian 32-bit numbers.
  std::array<std::uint8_t, 8> size{};
  in.seekg(4);
  if (!readBytes(in, size)) {
    return std::nullopt;
  }
  return ImageHeader{"Sun raster", side(bigEndian(&size[0], 4)), side(bigEndian(&size[4], 4))};
}

std::optional<ImageHeader> radianceHeader(std::ifstream& in) {
  // "#?RADIANCE" or "#?RGBE", header lines up to an empty one, then the resolution line: two of "±Y n" and
  // "±X n" (the usual "-Y height +X width" or a transposed order).
  in.seekg(0);
  std::string line;
  bool blank = false;
  for (int lines = 0; lines < 1024 && std::getline(in, line); ++lines) {
    if (line.size() > 4096) {
      return std::nullopt;
    }
    if (!blank) {
      blank = line.empty();
      continue;
    }
    std::istringstream resolution(line);
    std::optional<int> sides[2];
    for (int i = 0; i < 2; ++i) {
      std::string axis;
      std::string value;
      resolution >> axis >> value;
      if (axis.size() != 2 || (axis[0] != '+' && axis[0] != '-') || (axis[1] != 'X' && axis[1] != 'Y')) {
        return std::nullopt;
      }
      sides[axis[1] == 'X' ? 0 : 1] = decimal(value);
    }
    if (!sides[0] || !sides[1]) {
      return std::nullopt;
    }
    return ImageHeader{"Radiance HDR", *sides[0], *sides[1]};
  }
  return std::nullopt;
}

std::optional<ImageHeader> jpeg2000Codestream(std::ifstream& in) {
  // SOC, then the SIZ marker segment (ISO/IEC 15444-1 §A.5.1): FF51, Lsiz (2), Rsiz (2), Xsiz, Ysiz, XOsiz,
  // YOsiz (4 each, big-endian): the image is (Xsiz − XOsiz) × (Ysiz − YOsiz).
  std::array<std::uint8_t, 24> siz{};
  if (!readBytes(in, siz) || siz[0] != 0xFF || siz[1] != 0x4F || siz[2] != 0xFF || siz[3] != 0x51) {
    return std::nullopt;
  }
  const auto at = [&siz](int offset) { return static_cast<std::int64_t>(bigEndian(&siz[offset], 4)); };
  const auto clampSide = [](std::int64_t v) {
    return static_cast<int>(std::clamp<std::int64_t>(v, 0, 0x7fffffff));
  };
  return ImageHeader{"JPEG 2000", clampSide(at(8) - at(16)), clampSide(at(12) - at(20))};
}

std::optional<ImageHeader> jp2Header(std::ifstream& in) {
  // JP2 boxes (ISO/IEC 15444-1 §I.4): length (4; 1 = an 8-byte length follows, 0 = to the end of the file)
  // and type (4). The contiguous codestream box "jp2c" holds what the decoder decodes.
  in.seekg(0);
  for (int box = 0; box < 1024; ++box) {
    std::array<std::uint8_t, 8> head{};
    if (!readBytes(in, head)) {
      return std::nullopt;
    }
    std::uint64_t length = bigEndian(&head[0], 4);
    std::uint64_t headerBytes = 8;
    if (length == 1) {
      std::array<std::uint8_t, 8> large{};
      if (!readBytes(in, large)) {
        return std::nullopt;
      }
      length = (static_cast<std::uint64_t>(bigEndian(&large[0], 4)) << 32) | bigEndian(&large[4], 4);
      headerBytes = 16;
    }
    if (hasTag(&head[4], "jp2c")) {
      return jpeg2000Codestream(in);
    }
    if (length < headerBytes || length - headerBytes > 0x7fffffffu) {
      return std::nullopt;
    }
    in.seekg(static_cast<std::streamoff>(length - headerBytes), std::ios::cur);
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
  if (n >= 2 && start[0] == 'P' &&
      ((start[1] >= '1' && start[1] <= '7') || start[1] == 'F' || start[1] == 'f')) {
    return netpbmHeader(in, static_cast<char>(start[1]));
  }
  if (n >= 4 && bigEndian(start.data(), 4) == 0x59a66a95u) {
    return sunRasterHeader(in);
  }
  const std::string text(reinterpret_cast<const char*>(start.data()), n);
  if (text.starts_with("#?RADIANCE") || text.starts_with("#?RGBE")) {
    return radianceHeader(in);
  }
  if (n >= 4 && bigEndian(start.data(), 4) == 0xFF4FFF51u) {
    in.seekg(0);
    return jpeg2000Codestream(in);
  }
  constexpr std::array<std::uint8_t, 12> kJp2 = {0, 0, 0, 12, 'j', 'P', ' ', ' ', '\r', '\n', 0x87, '\n'};
  if (n == kJp2.size() && std::equal(kJp2.begin(), kJp2.end(), start.begin())) {
    return jp2Header(in);
  }
  return std::nullopt;
}

} // namespace sylva
