#pragma once
// Where `sylva capture` reads its depth frames: which kind of input is a path (a 16-bit depth PNG, an 8-bit
// Middlebury disparity map or a fakenect recording), how is it opened, and which frames of it are captured?

#include <sylva/capture/Depth.hpp>
#include <sylva/capture/Fakenect.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sylva::capture {

/** What to open and how its depth is read. */
struct DepthInputOptions {
  std::string input;            ///< a depth PNG, a Middlebury disparity PNG or a fakenect folder
  std::string format = "auto";  ///< "auto" (detectDepthFormat), "png", "middlebury" or "fakenect"
  bool kinect = false;          ///< capture from a Kinect v1 through libfreenect instead of `input`
  int kinectFrames = 0;         ///< with kinect: frames to capture (KinectOptions::frames)
  bool kinectColour = true;     ///< with kinect: also read the colour camera (KinectOptions::colour)
  DepthPngOptions png;          ///< for depth PNGs
  std::string colour;           ///< for depth PNGs: an RGB image of the same size (empty: none)
  MiddleburyOptions middlebury; ///< for Middlebury disparity maps
  /** The frames captured, inclusive and 0-based (none: all); `framesText` names them in errors. */
  std::optional<std::pair<int, int>> frames;
  /** The frame range as the user gave it (for errors). */
  std::string framesText;
};

/** The depth frames of an input, loaded lazily (recordings can be long). */
struct DepthInput {
  std::string label; ///< the input as named in reports ("kinect" for a live capture)
  std::string kind;  ///< "png", "middlebury", "fakenect" or "kinect"
  /** The recording (fakenect input only). */
  std::optional<FakenectRecording> recording;
  std::vector<DepthFrame> frames;    ///< single images and Kinect captures
  std::vector<std::string> warnings; ///< what opening skipped (a recording's unreadable frames)
  int first = 0;                     ///< the first frame captured
  int last = 0;                      ///< the last frame captured
  /** Frames captured. */
  int count() const { return last - first + 1; }
  /** Frame `i` of the input (first ≤ i ≤ last). */
  DepthFrame frame(int i) const;
};

/**
 * The kind of `input` from the file itself: a folder is a fakenect recording, a 16-bit PNG a depth image in
 * millimetres and an 8-bit PNG a Middlebury disparity map (bit depth from the PNG header; a file too short
 * to tell is left to the depth loader, whose error names the problem). Throws sylva::Error naming the file
 * when it does not exist or is not a PNG.
 */
std::string detectDepthFormat(const std::string& input);

/**
 * Opens the input `options` name and selects its frames. Throws sylva::Error with one line naming the file,
 * frame or option: no input, an input and a Kinect together, an unknown format, a colour image of another
 * size, frames beyond the input's.
 */
DepthInput openDepthInput(const DepthInputOptions& options);

/** A file-name stem for an input's outputs: its file or folder name without extension, ':' and '/' as '-'. */
std::string inputStem(const std::string& label);

} // namespace sylva::capture
