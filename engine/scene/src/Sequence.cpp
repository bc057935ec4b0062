#include <sylva/scene/Sequence.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Process.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/media/Export.hpp>

#include <fmt/format.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <system_error>

namespace sylva::scene {

namespace {

namespace fs = std::filesystem;

constexpr int kMaxFrameNumber = 999'999; ///< frames are numbered 0 … 999999 (1e6 frames)
constexpr int kMaxShards = 4096;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) {
    s.remove_prefix(1);
  }
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) {
    s.remove_suffix(1);
  }
  return s;
}

/** A decimal number of at most 9 digits, nothing else; nullopt otherwise. */
std::optional<long long> parseNumber(std::string_view s) {
  s = trim(s);
  if (s.empty() || s.size() > 9 ||
      !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  long long v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

std::string showSpan(const std::pair<int, int>& s) {
  return s.first == s.second ? std::to_string(s.first) : fmt::format("{}-{}", s.first, s.second);
}

/** Whether `pid` names a running process (or one we may not signal, which also exists). */
bool processAlive(long long pid) {
  if (pid <= 0 || pid > 0x3fffffff) {
    return false;
  }
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

} // namespace

long long FrameRange::count() const {
  long long n = 0;
  for (const auto& [a, b] : spans) {
    n += static_cast<long long>(b) - a + 1;
  }
  return n;
}

std::vector<int> FrameRange::frames() const {
  std::vector<int> out;
  out.reserve(static_cast<std::size_t>(count()));
  for (const auto& [a, b] : spans) {
    for (int f = a; f <= b; ++f) {
      out.push_back(f);
    }
  }
  return out;
}

FrameRange parseFrames(std::string_view text) {
  if (trim(text).empty()) {
    fail("--frames: empty (expected N, A-B or a comma-separated list such as 0-99,200-299)");
  }
  std::vector<std::pair<int, int>> spans; // in input order
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string_view token = trim(text.substr(start, comma - start));
    start = comma + 1;
    if (spans.size() >= 100000) {
      fail("--frames: more than 100000 ranges");
    }
    const std::size_t dash = token.find('-');
    const auto a = parseNumber(token.substr(0, dash));
    const auto b = dash == std::string_view::npos ? a : parseNumber(token.substr(dash + 1));
    if (!a || !b) {
      fail("--frames: '{}' is not N or A-B (frame numbers 0 to {})", token, kMaxFrameNumber);
    }
    for (long long v : {*a, *b}) {
      if (v > kMaxFrameNumber) {
        fail("--frames: {} is more than {}", v, kMaxFrameNumber);
      }
    }
    if (*b < *a) {
      fail("--frames: {}-{} ends before it starts", *a, *b);
    }
    spans.emplace_back(static_cast<int>(*a), static_cast<int>(*b));
  }
  // Sort (keeping the input order to name the later of two overlapping ranges first), then any overlap shows
  // between a range and the one reaching furthest among those before it.
  std::vector<std::size_t> order(spans.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return spans[x].first < spans[y].first; });
  FrameRange range;
  std::size_t reach = order.front();
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::size_t i = order[k];
    if (k > 0) {
      if (spans[i].first <= spans[reach].second) {
        const std::size_t later = std::max(i, reach);
        const std::size_t earlier = std::min(i, reach);
        fail("--frames: {} overlaps {}", showSpan(spans[later]), showSpan(spans[earlier]));
      }
      reach = spans[i].second > spans[reach].second ? i : reach;
    }
    range.spans.push_back(spans[i]);
  }
  return range;
}

Shard parseShard(std::string_view text) {
  const std::string_view t = trim(text);
  const std::size_t slash = t.find('/');
  const auto i = slash == std::string_view::npos ? std::nullopt : parseNumber(t.substr(0, slash));
  const auto n = slash == std::string_view::npos ? std::nullopt : parseNumber(t.substr(slash + 1));
  if (!i || !n) {
    fail("--shard: '{}' is not i/n (e.g. 0/4: the first of four shards)", t);
  }
  if (*n < 1 || *n > kMaxShards) {
    fail("--shard: {} shards is outside [1, {}]", *n, kMaxShards);
  }
  if (*i >= *n) {
    fail("--shard: index {} is not below the shard count {} (shards are numbered from 0)", *i, *n);
  }
  return Shard{static_cast<int>(*i), static_cast<int>(*n)};
}

std::vector<int> framesOf(const FrameRange& range, const Shard& shard) {
  if (shard.count < 1 || shard.index < 0 || shard.index >= shard.count) {
    fail("--shard: {}/{} is not a shard", shard.index, shard.count);
  }
  std::vector<int> out;
  long long k = 0;
  for (const auto& [a, b] : range.spans) {
    for (int f = a; f <= b; ++f, ++k) {
      if (k % shard.count == shard.index) {
        out.push_back(f);
      }
    }
  }
  return out;
}

std::string frameName(int frame) {
  if (frame < 0) {
    fail("frame number {} is negative", frame);
  }
  return fmt::format("frame_{:05d}.png", frame);
}

bool frameComplete(const fs::path& path, int width, int height) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    return false;
  }
  try {
    const Image image = loadPng(path);
    return image.width() == width && image.height() == height;
  } catch (const std::exception&) {
    return false; // truncated, corrupt, unreadable: render it again
  }
}

void writeFrameAtomically(const fs::path& path, const Image& image) {
  std::error_code ec;
  if (path.has_parent_path()) {
    fs::create_directories(path.parent_path(), ec);
    if (ec) {
      fail("{}: cannot create the directory: {}", path.parent_path().string(), ec.message());
    }
  }
  fs::path tmp = path;
  tmp += ".tmp-" + std::to_string(::getpid());
  try {
    savePng(tmp, image);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    fail("{}: cannot rename the finished frame into place: {}", path.string(), ec.message());
  }
}

int removeStaleTemporaries(const fs::path& dir, bool all) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    return 0;
  }
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const std::size_t mark = name.rfind(".png.tmp-");
    if (name.rfind("frame_", 0) != 0 || mark == std::string::npos) {
      continue;
    }
    const auto pid = parseNumber(std::string_view(name).substr(mark + 9));
    if (!all && pid && processAlive(*pid)) {
      continue; // another run is writing it now
    }
    std::error_code rmError;
    if (fs::remove(entry.path(), rmError)) {
      ++removed;
    }
  }
  return removed;
}

} // namespace sylva::scene

namespace sylva::scene {

namespace {

/** The range's frames as MP4 through ffmpeg (H.264, yuv420p); the frames must all be there. */
void encodeMp4(const SequencePlan& plan, double fps, const std::string& out) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) {
    fail("--mp4 {}: ffmpeg is not installed (apt install ffmpeg; scripts/setup-debian.sh installs it)", out);
  }
  // ffmpeg reads numbered files from a start number on; a list file also covers ranges with gaps (--frames
  // 0-9,20-29) in order.
  const std::filesystem::path list = plan.out / "frames.ffconcat";
  {
    std::FILE* f = std::fopen(list.c_str(), "w");
    if (f == nullptr) {
      fail("--mp4: cannot write {}", list.string());
    }
    std::fprintf(f, "ffconcat version 1.0\n");
    for (int frame : plan.range.frames()) {
      std::fprintf(f, "file '%s'\nduration %.9f\n", frameName(frame).c_str(), 1.0 / fps);
    }
    std::fclose(f);
  }
  const std::filesystem::path parent = std::filesystem::path(out).parent_path();
  if (!parent.empty()) {
    std::filesystem::create_directories(parent);
  }
  const std::string temporary = out + ".tmp.mp4";
  const std::string command = fmt::format(
      "ffmpeg -loglevel error -y -f concat -safe 0 -i {} -r {} -c:v libx264 -pix_fmt yuv420p -crf 20 "
      "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -movflags +faststart {}",
      shellQuote(list.string()), fps, shellQuote(temporary));
  const int rc = std::system(command.c_str());
  std::filesystem::remove(list);
  if (rc != 0) {
    std::filesystem::remove(temporary);
    fail("--mp4 {}: ffmpeg failed (exit {})", out, rc);
  }
  std::filesystem::rename(temporary, out);
}

} // namespace

std::vector<int> faultFrames() {
  const char* text = std::getenv("SYLVA_FAULT_FRAMES");
  if (text == nullptr || *text == '\0') {
    return {};
  }
  try {
    return parseFrames(text).frames();
  } catch (const Error& e) {
    fail("SYLVA_FAULT_FRAMES: {}", e.what());
  }
}

std::filesystem::path SequencePlan::framePath(int frame) const {
  return sequence ? out / frameName(frame) : out;
}

SequencePlan planSequence(const SequenceJob& job) {
  SequencePlan p;
  p.job = job;
  p.desc = loadScene(job.file);
  const SceneDesc& desc = p.desc;
  p.width = job.width > 0 ? job.width : desc.output.width;
  p.height = job.height > 0 ? job.height : desc.output.height;
  p.camera = job.camera.empty() ? desc.output.camera : job.camera;
  if (!desc.cameras.contains(p.camera)) {
    fail("--camera {}: {} has no such camera", p.camera, job.file);
  }
  p.sequence = !job.frames.empty() || !job.gif.empty() || !job.mp4.empty();
  p.range = job.frames.empty()
                ? parseFrames(fmt::format("{}-{}", desc.output.firstFrame, desc.output.lastFrame))
                : parseFrames(job.frames);
  const Shard shard = parseShard(job.shard);
  if (!p.sequence && shard.count > 1) {
    fail("--shard {}: needs a sequence (--frames A-B)", job.shard);
  }
  p.frames = p.sequence ? framesOf(p.range, shard) : std::vector<int>{desc.output.firstFrame};
  p.out = !job.out.empty() ? std::filesystem::path(job.out)
                           : std::filesystem::path("out") / (p.sequence ? desc.name : desc.name + ".png");
  // Outputs checked before the scene is built and drawn.
  if (!p.sequence) {
    checkOutputFile(p.out, "--out");
  }
  if (!job.gif.empty()) {
    checkOutputFile(job.gif, "--gif", "anim.gif");
  }
  if (!job.mp4.empty()) {
    checkOutputFile(job.mp4, "--mp4", "anim.mp4");
  }
  if (p.sequence) {
    if (std::filesystem::exists(p.out) && !std::filesystem::is_directory(p.out)) {
      fail("--out {}: a sequence needs a directory, and this is a file", p.out.string());
    }
    std::filesystem::create_directories(p.out);
    const int stale = removeStaleTemporaries(p.out);
    if (stale > 0) {
      log::info("removed {} unfinished frame file(s) left by an interrupted run", stale);
    }
  }
  // Frames already complete are skipped (resumable); the simulation still steps through their times.
  for (int f : p.frames) {
    if (!p.sequence || job.overwrite || !frameComplete(p.framePath(f), p.width, p.height)) {
      p.todo.push_back(f);
    }
  }
  return p;
}

std::vector<std::string> finishSequence(const SequencePlan& plan) {
  if (!plan.sequence || (plan.job.gif.empty() && plan.job.mp4.empty())) {
    return {};
  }
  // Encoding needs the whole range (every shard done): say what is missing instead of a short video.
  int missing = 0;
  for (int f : plan.range.frames()) {
    if (!frameComplete(plan.framePath(f), plan.width, plan.height)) {
      ++missing;
    }
  }
  if (missing > 0) {
    log::warn("{} of {} frames of the range are not rendered yet (other shards?): not encoding; run again "
              "with the same --gif/--mp4 when they are",
              missing, plan.range.count());
    return {};
  }
  std::vector<std::string> written;
  const double fps = plan.desc.output.fps;
  if (!plan.job.gif.empty()) {
    std::vector<Image> images;
    for (int f : plan.range.frames()) {
      images.push_back(loadImage(plan.framePath(f)));
    }
    media::writeGif(plan.job.gif, images, std::max(1, static_cast<int>(std::lround(100.0 / fps))));
    written.push_back(plan.job.gif);
  }
  if (!plan.job.mp4.empty()) {
    encodeMp4(plan, fps, plan.job.mp4);
    written.push_back(plan.job.mp4);
  }
  return written;
}

} // namespace sylva::scene
