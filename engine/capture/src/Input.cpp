#include <sylva/capture/Input.hpp>

#include <sylva/capture/Kinect.hpp>
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <filesystem>
#include <fstream>
#include <string_view>

namespace sylva::capture {

namespace fs = std::filesystem;

DepthFrame DepthInput::frame(int i) const {
  if (recording) {
    return recording->depthFrame(static_cast<std::size_t>(i));
  }
  return frames[static_cast<std::size_t>(i)];
}

std::string detectDepthFormat(const std::string& input) {
  const fs::path path(input);
  if (fs::is_directory(path)) {
    return "fakenect";
  }
  if (!fs::exists(path)) {
    fail("{}: no such file or folder", input);
  }
  if (lowerExtension(path) != ".png") {
    fail("{}: expected a depth PNG, a Middlebury disparity PNG or a fakenect folder (use --format)", input);
  }
  // 16-bit: depth in millimetres; 8-bit: a disparity map. The bit depth is byte 24 of a PNG (signature, the
  // IHDR chunk's length and type, width, height, then bit depth).
  std::ifstream in(path, std::ios::binary);
  char header[25] = {};
  in.read(header, sizeof(header));
  const bool png = in.gcount() == static_cast<std::streamsize>(sizeof(header)) &&
                   std::string_view(header + 1, 3) == "PNG" && std::string_view(header + 12, 4) == "IHDR";
  return png && static_cast<unsigned char>(header[24]) == 8 ? "middlebury" : "png";
}

DepthInput openDepthInput(const DepthInputOptions& o) {
  DepthInput s;
  if (o.kinect) {
    if (!o.input.empty()) {
      fail("--kinect: give either an input or --kinect, not both");
    }
    KinectOptions k;
    k.frames = o.kinectFrames;
    k.colour = o.kinectColour;
    captureKinect(k, [&](DepthFrame&& frame) {
      s.frames.push_back(std::move(frame));
      return true;
    });
    s.label = kinectReplayActive() ? s.frames.front().source : "kinect";
    s.kind = "kinect";
  } else {
    if (o.input.empty()) {
      fail("capture: give an input (depth PNG, Middlebury PNG or fakenect folder) or --kinect");
    }
    const std::string format = o.format == "auto" ? detectDepthFormat(o.input) : o.format;
    s.label = o.input;
    s.kind = format;
    if (format == "fakenect") {
      s.recording = FakenectRecording::open(o.input);
      s.warnings = s.recording->warnings();
    } else if (format == "png") {
      DepthFrame frame = loadDepthPng(o.input, o.png);
      if (!o.colour.empty()) {
        Image colour = loadImage(o.colour);
        if (colour.width() != frame.width || colour.height() != frame.height || colour.channels() < 3) {
          fail("--colour {}: expected an RGB image of the depth's size {}x{}, got {}x{} with {} channels",
               o.colour, frame.width, frame.height, colour.width(), colour.height(), colour.channels());
        }
        frame.colour = colour.converted(PixelType::U8);
      }
      s.frames.push_back(std::move(frame));
    } else if (format == "middlebury") {
      s.frames.push_back(loadMiddlebury(o.input, o.middlebury));
    } else {
      fail("--format: unknown format '{}'", format);
    }
  }
  const int available =
      s.recording ? static_cast<int>(s.recording->depthFrameCount()) : static_cast<int>(s.frames.size());
  s.first = 0;
  s.last = available - 1;
  if (o.frames) {
    if (o.frames->second >= available) {
      fail("--frames {}: {} has {} depth frame{} (0..{})", o.framesText, s.label, available,
           available == 1 ? "" : "s", available - 1);
    }
    s.first = o.frames->first;
    s.last = o.frames->second;
  }
  return s;
}

std::string inputStem(const std::string& label) {
  std::string s = fs::path(label).filename().string();
  if (s.empty()) {
    s = fs::path(label).parent_path().filename().string();
  }
  const std::size_t dot = s.rfind('.');
  if (dot != std::string::npos && dot > 0) {
    s = s.substr(0, dot);
  }
  for (char& c : s) {
    if (c == ':' || c == '/') {
      c = '-';
    }
  }
  return s.empty() ? std::string("capture") : s;
}

} // namespace sylva::capture
