// libfreenect recordings ("fakenect" folders): INDEX.txt parsing, the depth PGM and RGB PPM frame files, and
// a writer whose folders both FakenectRecording and libfreenect's fakenect replay.
#include <sylva/capture/Fakenect.hpp>
#include "internal/Limits.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Log.hpp>

#include <fmt/format.h>

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>
#include <system_error>

namespace sylva::capture {

namespace {

namespace fs = std::filesystem;

constexpr int kFrameWidth = 640;
constexpr int kFrameHeight = 480;
using internal::kMaxPixels;
using internal::kMaxSide;
/** A header line longer than this is not a fakenect header ("P5 65536 65536 65535\n" is 21 bytes). */
constexpr std::size_t kMaxHeaderBytes = 64;
/** Frame files above this size are refused before reading (a 640×480 depth frame is 600 KiB). */
constexpr std::uintmax_t kMaxFrameFileBytes = std::uintmax_t{256} << 20;

struct Header {
  int width = 0;
  int height = 0;
  std::size_t dataOffset = 0;
};

bool parseInt(std::string_view text, int& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size();
}

/** Parses "<magic> <width> <height> <maxval>\n" at the start of `bytes`. */
Header parseHeader(std::span<const std::byte> bytes, const std::string& name, std::string_view magic,
                   int maxval, const char* what) {
  const std::size_t limit = std::min(bytes.size(), kMaxHeaderBytes);
  std::size_t newline = 0;
  while (newline < limit && bytes[newline] != std::byte{'\n'}) {
    ++newline;
  }
  const std::string expected = fmt::format("\"{} <width> <height> {}\"", magic, maxval);
  if (newline == limit) {
    fail("{}: not a fakenect {} frame: expected a one-line {} header ending in a newline", name, what,
         expected);
  }
  const std::string_view line(reinterpret_cast<const char*>(bytes.data()), newline);
  std::vector<std::string_view> tokens;
  std::size_t pos = 0;
  while (pos < line.size()) {
    const std::size_t next = line.find(' ', pos);
    const std::size_t end = next == std::string_view::npos ? line.size() : next;
    if (end > pos) {
      tokens.push_back(line.substr(pos, end - pos));
    }
    pos = end + 1;
  }
  if (tokens.size() != 4 || tokens[0] != magic) {
    fail("{}: not a fakenect {} frame: expected a {} header", name, what, expected);
  }
  Header header;
  int headerMax = 0;
  if (!parseInt(tokens[1], header.width) || !parseInt(tokens[2], header.height) ||
      !parseInt(tokens[3], headerMax)) {
    fail("{}: malformed {} frame header: expected {}", name, what, expected);
  }
  if (headerMax != maxval) {
    fail("{}: {} frame maximum value must be {}, got {}", name, what, maxval, headerMax);
  }
  if (header.width <= 0 || header.height <= 0 || header.width > kMaxSide || header.height > kMaxSide ||
      static_cast<std::int64_t>(header.width) * header.height > kMaxPixels) {
    fail("{}: {} frame size {}x{} is out of range (1..{} per side, at most {} pixels)", name, what,
         header.width, header.height, kMaxSide, kMaxPixels);
  }
  header.dataOffset = newline + 1;
  return header;
}

void checkDataSize(std::span<const std::byte> bytes, const Header& header, std::size_t bytesPerPixel,
                   const std::string& name, const char* what) {
  const std::size_t expected =
      static_cast<std::size_t>(header.width) * static_cast<std::size_t>(header.height) * bytesPerPixel;
  const std::size_t available = bytes.size() - header.dataOffset;
  if (available < expected) {
    fail("{}: truncated {} data: {} of {} bytes for {}x{}", name, what, available, expected, header.width,
         header.height);
  }
  if (available > expected) {
    fail("{}: {} bytes after the {}x{} {} data (the header's size does not match the file)", name,
         available - expected, header.width, header.height, what);
  }
}

std::vector<std::byte> readFrameFile(const fs::path& path, const std::string& name) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) {
    fail("{}: cannot read: {}", name, ec.message());
  }
  if (size > kMaxFrameFileBytes) {
    fail("{}: {} bytes is too large for a fakenect frame (at most {})", name, size, kMaxFrameFileBytes);
  }
  std::vector<std::byte> bytes(static_cast<std::size_t>(size));
  std::ifstream in(path, std::ios::binary);
  if (!in || !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()))) {
    fail("{}: cannot read the file", name);
  }
  return bytes;
}

/** Parses `<kind>-<walltime>-<timestamp>…` the way fakenect does (sscanf "%c-%lf-%u"), but strictly. */
bool parseEntry(std::string_view line, FakenectEntry& entry, std::string& why) {
  if (line.size() < 2 || line[1] != '-') {
    why = "expected <kind>-<walltime>-<timestamp>.<ext>";
    return false;
  }
  entry.kind = line[0];
  const char* begin = line.data() + 2;
  const char* end = line.data() + line.size();
  const auto [afterTime, timeError] = std::from_chars(begin, end, entry.walltime);
  if (timeError != std::errc() || !std::isfinite(entry.walltime)) {
    why = "expected <kind>-<walltime>-<timestamp>.<ext> (the walltime is not a number)";
    return false;
  }
  if (afterTime == end || *afterTime != '-') {
    why = "expected <kind>-<walltime>-<timestamp>.<ext> (no '-' after the walltime)";
    return false;
  }
  const auto [afterStamp, stampError] = std::from_chars(afterTime + 1, end, entry.timestamp);
  if (stampError != std::errc()) {
    why = "expected <kind>-<walltime>-<timestamp>.<ext> (the timestamp is not a 32-bit unsigned number)";
    return false;
  }
  if (line.find_first_of("/\\") != std::string_view::npos || line.find('\0') != std::string_view::npos) {
    why = "frame file names must not contain a directory";
    return false;
  }
  entry.file = std::string(line);
  return true;
}

const char* kindName(char kind) {
  return kind == 'd' ? "frame" : kind == 'r' ? "rgb frame" : "accelerometer entry";
}

/** `folder` without a trailing separator, so that its file name is the folder's own name. */
fs::path withoutTrailingSeparator(const fs::path& folder) {
  fs::path p = folder.lexically_normal();
  if (p.has_parent_path() && !p.has_filename()) {
    p = p.parent_path();
  }
  return p;
}

void writeBytes(const fs::path& path, const std::string& header, const void* data, std::size_t size,
                const fs::path& folder) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    fail("{}: cannot write {}", folder.string(), path.filename().string());
  }
}

} // namespace

RawDepth decodeFakenectDepth(std::span<const std::byte> bytes, const std::string& name) {
  const Header header = parseHeader(bytes, name, "P5", 65535, "depth");
  checkDataSize(bytes, header, 2, name, "depth");
  RawDepth raw;
  raw.width = header.width;
  raw.height = header.height;
  raw.raw.resize(static_cast<std::size_t>(header.width) * static_cast<std::size_t>(header.height));
  const std::byte* data = bytes.data() + header.dataOffset;
  for (std::size_t i = 0; i < raw.raw.size(); ++i) {
    raw.raw[i] = static_cast<std::uint16_t>(std::to_integer<unsigned>(data[2 * i]) |
                                            (std::to_integer<unsigned>(data[2 * i + 1]) << 8));
  }
  return raw;
}

Image decodeFakenectRgb(std::span<const std::byte> bytes, const std::string& name) {
  const Header header = parseHeader(bytes, name, "P6", 255, "RGB");
  checkDataSize(bytes, header, 3, name, "RGB");
  Image image(header.width, header.height, 3, PixelType::U8);
  std::memcpy(image.data(), bytes.data() + header.dataOffset, image.byteSize());
  return image;
}

DepthFrame depthFromKinectRaw(const RawDepth& raw) {
  DepthFrame frame(raw.width, raw.height);
  if (raw.raw.size() != frame.depth.size()) {
    fail("raw depth frame {}x{} holds {} values", raw.width, raw.height, raw.raw.size());
  }
  for (std::size_t i = 0; i < raw.raw.size(); ++i) {
    frame.depth[i] = kinectRawToMetres(raw.raw[i]);
  }
  frame.intrinsics = CameraIntrinsics::kinectV1Scaled(raw.width, raw.height);
  frame.kind = DepthSourceKind::Kinect;
  frame.source = "kinect";
  return frame;
}

FakenectRecording FakenectRecording::open(const std::filesystem::path& folder) {
  FakenectRecording recording;
  recording.mFolder = folder;
  const std::string name = folder.string();
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    fail("{}: {}", name,
         fs::exists(folder, ec) ? "not a folder (a fakenect recording is a folder with INDEX.txt)"
                                : "no such fakenect recording folder");
  }
  const fs::path indexPath = folder / "INDEX.txt";
  if (!fs::is_regular_file(indexPath, ec)) {
    fail("{}: INDEX.txt is missing (not a fakenect recording)", name);
  }
  const std::string index = readTextFile(indexPath);
  const std::string indexName = indexPath.string();
  std::size_t counts[3] = {0, 0, 0}; // depth, RGB, accelerometer entries listed so far
  std::size_t listedDepth = 0;
  int emptyLine = 0;
  int lineNumber = 0;
  std::size_t pos = 0;
  while (pos < index.size()) {
    std::size_t end = index.find('\n', pos);
    if (end == std::string::npos) {
      end = index.size();
    }
    std::string_view line(index.data() + pos, end - pos);
    pos = end + 1;
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') {
      line.remove_suffix(1);
    }
    if (line.find_first_not_of(" \t") == std::string_view::npos) {
      if (emptyLine == 0) {
        emptyLine = lineNumber;
      }
      continue;
    }
    if (emptyLine != 0) {
      recording.mWarnings.push_back(fmt::format(
          "{}:{}: empty line (libfreenect's fakenect stops replaying there)", indexName, emptyLine));
      emptyLine = 0;
    }
    FakenectEntry entry;
    std::string why;
    if (!parseEntry(line, entry, why)) {
      fail("{}:{}: {}", indexName, lineNumber, why);
    }
    entry.line = lineNumber;
    const std::size_t slot = entry.kind == 'd' ? 0 : entry.kind == 'r' ? 1 : entry.kind == 'a' ? 2 : 3;
    if (slot == 3) {
      recording.mWarnings.push_back(fmt::format(
          "{}:{}: unknown entry kind '{}' (expected d, r or a); ignored", indexName, lineNumber, entry.kind));
      continue;
    }
    const std::size_t number = counts[slot]++;
    if (entry.kind == 'd') {
      ++listedDepth;
    }
    if (!fs::is_regular_file(folder / entry.file, ec)) {
      recording.mWarnings.push_back(fmt::format("{}: {} {}: {} listed in INDEX.txt is missing", name,
                                                kindName(entry.kind), number, entry.file));
      continue;
    }
    if (entry.kind == 'd') {
      recording.mDepth.push_back(recording.mEntries.size());
    }
    recording.mEntries.push_back(std::move(entry));
  }
  if (recording.mDepth.empty()) {
    if (listedDepth == 0) {
      fail("{}: no depth frame (INDEX.txt lists none)", name);
    }
    fail("{}: no depth frame: all {} depth frames listed in INDEX.txt are missing", name, listedDepth);
  }
  return recording;
}

RawDepth FakenectRecording::rawDepthFrame(std::size_t i) const {
  if (i >= mDepth.size()) {
    fail("{}: frame {} does not exist (the recording has {} depth frames)", mFolder.string(), i,
         mDepth.size());
  }
  const FakenectEntry& entry = mEntries[mDepth[i]];
  const std::string name = fmt::format("{}: frame {}", (mFolder / entry.file).string(), i);
  const std::vector<std::byte> bytes = readFrameFile(mFolder / entry.file, name);
  return decodeFakenectDepth(bytes, name);
}

DepthFrame FakenectRecording::depthFrame(std::size_t i) const {
  DepthFrame frame = depthFromKinectRaw(rawDepthFrame(i));
  const std::size_t at = mDepth[i];
  frame.kind = DepthSourceKind::Fakenect;
  frame.source = mFolder.string();
  frame.frame = static_cast<int>(i);
  frame.timestamp = mEntries[at].walltime - mEntries.front().walltime;
  for (std::size_t j = at; j-- > 0;) {
    const FakenectEntry& entry = mEntries[j];
    if (entry.kind != 'r') {
      continue;
    }
    const std::string name = (mFolder / entry.file).string();
    try {
      Image rgb = decodeFakenectRgb(readFrameFile(mFolder / entry.file, name), name);
      if (rgb.width() != frame.width || rgb.height() != frame.height) {
        log::warn("{}: RGB frame is {}x{}, the depth frame {}x{}; skipped", name, rgb.width(), rgb.height(),
                  frame.width, frame.height);
        continue;
      }
      frame.colour = std::move(rgb);
      break;
    } catch (const Error& e) {
      log::warn("{} (skipped)", e.what());
    }
  }
  return frame;
}

FakenectWriter::FakenectWriter(std::filesystem::path folder) : mFolder(withoutTrailingSeparator(folder)) {
  if (mFolder.empty() || !mFolder.has_filename() || mFolder.filename() == "." || mFolder.filename() == "..") {
    fail("{}: not a usable recording folder name", folder.string());
  }
  const fs::path parent = mFolder.has_parent_path() ? mFolder.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) {
    fail("{}: cannot create the parent folder: {}", mFolder.string(), ec.message());
  }
  mTemp = parent / fmt::format("{}.tmp.{}", mFolder.filename().string(), ::getpid());
  fs::remove_all(mTemp, ec);
  if (!fs::create_directory(mTemp, ec) || ec) {
    fail("{}: cannot create the temporary folder {}: {}", mFolder.string(), mTemp.string(),
         ec ? ec.message() : std::string("it exists"));
  }
}

FakenectWriter::~FakenectWriter() {
  if (!mFinished) {
    std::error_code ec;
    fs::remove_all(mTemp, ec);
  }
}

namespace {

/** Checks a frame's size and walltime (finite, not before the previous frame's) for a fakenect recording. */
void checkFrame(const fs::path& folder, bool finished, int width, int height, double walltime, double last,
                const char* what) {
  if (finished) {
    fail("{}: the recording is finished; no more frames can be added", folder.string());
  }
  if (width != kFrameWidth || height != kFrameHeight) {
    fail("{}: fakenect {} frames must be {}x{} (libfreenect's only mode), got {}x{}", folder.string(), what,
         kFrameWidth, kFrameHeight, width, height);
  }
  if (!std::isfinite(walltime) || walltime < 0.0 || walltime > 1.0e10) {
    fail("{}: frame walltime must be between 0 and 1e10 seconds, got {}", folder.string(), walltime);
  }
  if (walltime < last) {
    fail("{}: frame walltime {:.6f} s is before the previous frame's {:.6f} s", folder.string(), walltime,
         last);
  }
}

} // namespace

void FakenectWriter::addDepth(const DepthFrame& frame, double walltime) {
  checkFrame(mFolder, mFinished, frame.width, frame.height, walltime, mLastWalltime, "depth");
  if (frame.depth.size() != static_cast<std::size_t>(kFrameWidth) * kFrameHeight) {
    fail("{}: depth frame holds {} values, expected {}", mFolder.string(), frame.depth.size(),
         kFrameWidth * kFrameHeight);
  }
  RawDepth raw;
  raw.width = frame.width;
  raw.height = frame.height;
  raw.raw.resize(frame.depth.size());
  for (std::size_t i = 0; i < raw.raw.size(); ++i) {
    raw.raw[i] = metresToKinectRaw(frame.depth[i]);
  }
  addRawDepth(raw, walltime);
}

namespace {

/**
 * The device timestamp of the next entry: milliseconds elapsed since the previous entry's walltime, added to
 * the previous timestamp, and at least 1 more than it, so timestamps strictly increase (wrapping after 49
 * days).
 */
std::uint32_t nextTimestamp(bool first, std::uint32_t previous, double walltime, double last) {
  if (first) {
    return 0;
  }
  const double ms = std::min(std::round((walltime - last) * 1000.0), 4.0e9);
  return previous + static_cast<std::uint32_t>(std::max(ms, 1.0));
}

} // namespace

void FakenectWriter::addRawDepth(const RawDepth& raw, double walltime) {
  checkFrame(mFolder, mFinished, raw.width, raw.height, walltime, mLastWalltime, "depth");
  if (raw.raw.size() != static_cast<std::size_t>(kFrameWidth) * kFrameHeight) {
    fail("{}: raw depth frame holds {} values, expected {}", mFolder.string(), raw.raw.size(),
         kFrameWidth * kFrameHeight);
  }
  mTimestamp = nextTimestamp(mIndex.empty(), mTimestamp, walltime, mLastWalltime);
  const std::string file = fmt::format("d-{:.6f}-{}.pgm", walltime, mTimestamp);
  std::vector<std::uint8_t> data(raw.raw.size() * 2);
  for (std::size_t i = 0; i < raw.raw.size(); ++i) {
    data[2 * i] = static_cast<std::uint8_t>(raw.raw[i] & 0xff);
    data[2 * i + 1] = static_cast<std::uint8_t>(raw.raw[i] >> 8);
  }
  writeBytes(mTemp / file, fmt::format("P5 {} {} 65535\n", kFrameWidth, kFrameHeight), data.data(),
             data.size(), mFolder);
  mIndex.push_back(file);
  mLastWalltime = walltime;
}

void FakenectWriter::addRgb(const Image& rgb, double walltime) {
  checkFrame(mFolder, mFinished, rgb.width(), rgb.height(), walltime, mLastWalltime, "RGB");
  if (rgb.channels() != 3 || rgb.type() != PixelType::U8) {
    fail("{}: fakenect RGB frames must be 8-bit RGB, got {} with {} channels", mFolder.string(),
         pixelTypeName(rgb.type()), rgb.channels());
  }
  mTimestamp = nextTimestamp(mIndex.empty(), mTimestamp, walltime, mLastWalltime);
  const std::string file = fmt::format("r-{:.6f}-{}.ppm", walltime, mTimestamp);
  writeBytes(mTemp / file, fmt::format("P6 {} {} 255\n", kFrameWidth, kFrameHeight), rgb.data(),
             rgb.byteSize(), mFolder);
  mIndex.push_back(file);
  mLastWalltime = walltime;
}

void FakenectWriter::finish() {
  const std::string name = mFolder.string();
  if (mFinished) {
    fail("{}: the recording is already finished", name);
  }
  bool anyDepth = false;
  std::string index;
  for (const std::string& line : mIndex) {
    anyDepth = anyDepth || line.starts_with('d');
    index += line;
    index += '\n';
  }
  if (!anyDepth) {
    fail("{}: no depth frame was added; a fakenect recording needs at least one", name);
  }
  writeBytes(mTemp / "INDEX.txt", std::string(), index.data(), index.size(), mFolder);
  std::error_code ec;
  fs::path old;
  if (fs::exists(fs::symlink_status(mFolder, ec))) {
    if (!fs::is_directory(fs::symlink_status(mFolder, ec))) {
      fail("{}: exists and is not a folder; not replaced", name);
    }
    old = mFolder.parent_path() / fmt::format("{}.old.{}", mFolder.filename().string(), ::getpid());
    fs::remove_all(old, ec);
    fs::rename(mFolder, old, ec);
    if (ec) {
      fail("{}: cannot move the existing recording aside: {}", name, ec.message());
    }
  }
  fs::rename(mTemp, mFolder, ec);
  if (ec) {
    const std::string reason = ec.message();
    if (!old.empty()) {
      fs::rename(old, mFolder, ec);
    }
    fail("{}: cannot move the recording into place: {}", name, reason);
  }
  mFinished = true;
  if (!old.empty()) {
    fs::remove_all(old, ec);
  }
}

} // namespace sylva::capture
