#include <sylva/media/Animation.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/media/Export.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace sylva::media {

namespace fs = std::filesystem;

std::size_t AnimationOutputs::fileCount(std::size_t frames) const {
  return (mp4.empty() ? 0 : 1) + (webm.empty() ? 0 : 1) + (sprites.empty() ? 0 : 2) + (gif.empty() ? 0 : 1) +
         (pngDir.empty() ? 0 : frames);
}

std::vector<std::string> writeAnimation(const AnimationOutputs& o, std::span<const Image> frames,
                                        const std::string& label) {
  const std::size_t count = frames.size();
  const int digits = std::max(4, static_cast<int>(std::to_string(count == 0 ? 0 : count - 1).size()));
  Progress writing("writing", std::max<std::size_t>(o.fileCount(count), 1));
  std::vector<fs::path> written;
  std::error_code ec;
  const bool pngDirExisted = !o.pngDir.empty() && fs::exists(o.pngDir, ec);
  const auto wrote = [&](const fs::path& path) {
    written.push_back(path);
    writing.advance();
    if (writing.cancelled()) {
      fail("{}: cancelled; the outputs written so far were removed", label);
    }
  };
  std::vector<std::string> report;
  try {
    for (const std::string& video : {o.mp4, o.webm}) {
      if (!video.empty()) {
        writeVideo(video, frames, o.fps);
        wrote(video);
        report.push_back(video);
      }
    }
    if (!o.sprites.empty()) {
      const fs::path json = fs::path(o.sprites).replace_extension(".json");
      writeSpriteSheet(o.sprites, json, frames, o.columns, o.fps);
      wrote(json);
      wrote(o.sprites);
      report.push_back(o.sprites);
      report.push_back(json.string());
    }
    if (!o.gif.empty()) {
      const int delay = std::max(2, static_cast<int>(std::lround(100.0 / o.fps)));
      writeGif(o.gif, frames, delay, true);
      wrote(o.gif);
      report.push_back(fmt::format("{} ({} frames, {} cs each)", o.gif, count, delay));
    }
    if (!o.pngDir.empty()) {
      for (std::size_t i = 0; i < count; ++i) {
        const fs::path frame = fs::path(o.pngDir) / fmt::format("frame_{:0{}}.png", i, digits);
        saveImage(frame, frames[i]);
        wrote(frame);
      }
      report.push_back(fmt::format("{} ({} frames)", o.pngDir, count));
    }
    // Everything is written: a Ctrl-C from here on must not turn finished files into a failed run (the
    // "writing" progress is still active, so nothing can slip in between).
    markOutputsComplete();
  } catch (...) {
    for (const fs::path& path : written) {
      fs::remove(path, ec);
    }
    if (!o.pngDir.empty() && !pngDirExisted && fs::is_empty(o.pngDir, ec)) {
      fs::remove(o.pngDir, ec);
    }
    throw;
  }
  return report;
}

} // namespace sylva::media
