#pragma once

#include "sylva/core/Image.hpp"

#include <memory>
#include <string>

namespace sylva::folding::internal {

/**
 * A video file decoded through FFmpeg's own libraries (libavformat demuxes, libavcodec decodes, libswscale
 * converts to RGBA8): the first video stream, frame by frame in presentation order.
 *
 * Every frame is converted at the size and pixel format its decoder reports for that frame, never at what
 * the container's header states, so a file whose header and frames disagree cannot make a conversion read
 * or write past a buffer (the defect of OpenCV 4.6's FFmpeg capture this replaces, fuzz target
 * `flow_ffmpeg`). The decoder refuses frames over maxSide² pixels before it allocates for them.
 */
class VideoFile {
public:
  /**
   * Opens `path` and its first video stream. Throws sylva::Error with one line starting with `path`: not a
   * container FFmpeg reads, no video stream, no decoder for its codec, a header stating more than `maxSide`
   * pixels per side.
   */
  VideoFile(const std::string& path, int maxSide);
  ~VideoFile();
  VideoFile(const VideoFile&) = delete;
  VideoFile& operator=(const VideoFile&) = delete;

  /** The stream's nominal frame rate, frames/s (guessed from its time base and frame rates); 0 if none. */
  double fps() const;

  /**
   * Decodes the next frame into `rgba` (RGBA8, alpha 255 unless the codec carries alpha) and its
   * presentation time in seconds from the stream's start into `timeS` (NaN when the frame has none).
   * Returns false at the end of the stream. Packets the decoder rejects (corrupt data) are skipped, as a
   * player would; a frame over maxSide per side, or in a pixel format libswscale cannot convert, throws
   * sylva::Error naming the file.
   */
  bool read(Image& rgba, double& timeS);

private:
  struct State;
  std::unique_ptr<State> mState;
};

} // namespace sylva::folding::internal
