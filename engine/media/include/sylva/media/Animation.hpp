#pragma once

// One animation written to every output a user asked for, all or none: videos, a sprite sheet, a GIF and a
// folder of numbered PNG frames.

#include <sylva/core/Image.hpp>

#include <span>
#include <string>
#include <vector>

namespace sylva::media {

/** Where an animation goes; an empty path is not written. */
struct AnimationOutputs {
  std::string mp4;     ///< H.264 video through ffmpeg (writeVideo)
  std::string webm;    ///< VP9 video through ffmpeg
  std::string sprites; ///< sprite sheet PNG; its JSON beside it with the extension .json (writeSpriteSheet)
  int columns = 1;     ///< sprite sheet columns
  std::string gif;     ///< animated GIF (writeGif), frame delay 100 / fps hundredths of a second (at least 2)
  std::string pngDir;  ///< a folder of frame_0000.png … (at least four digits), created when missing
  double fps = 25.0;   ///< frames per second of the videos, the GIF and the sprite sheet's times
  /** The number of files these outputs make for `frames` frames. */
  std::size_t fileCount(std::size_t frames) const;
};

/**
 * Writes `frames` (RGBA8, one size) to every output in `outputs`, all or none: a "writing" progress line
 * turns Ctrl-C into a request checked after each file, and a failure or a cancellation part way removes every
 * file this call wrote (and the PNG folder when this call created it), then throws sylva::Error (a
 * cancellation:
 * "`label`: cancelled; the outputs written so far were removed"). Videos go first: they are the outputs most
 * likely to fail (ffmpeg, codecs), and then nothing else is written. When every file is written it calls
 * markOutputsComplete() (a later Ctrl-C is ignored): call it as a command's last step. Returns one line per
 * output for a report.
 */
std::vector<std::string> writeAnimation(const AnimationOutputs& outputs, std::span<const Image> frames,
                                        const std::string& label);

} // namespace sylva::media
