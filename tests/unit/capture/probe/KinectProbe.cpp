// A tiny libfreenect client for KinectReplayTest, run under `fakenect DIR`: captureKinect, then each
// delivered frame's depth (float32 metres) and colour (RGB8, when present) as raw files in OUT, and one line
// per frame in OUT/frames.txt: "<frame> <width> <height> <timestamp> <has colour> <source>".
//   sylva_kinect_probe OUT FRAMES COLOUR(0|1)
// Exit status: 0 on success, 2 with the sylva::Error message on stderr.
#include <sylva/capture/Kinect.hpp>
#include <sylva/core/Error.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <string>

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: sylva_kinect_probe OUT FRAMES COLOUR\n");
    return 1;
  }
  const std::string out = argv[1];
  sylva::capture::KinectOptions options;
  options.frames = std::stoi(argv[2]);
  options.colour = std::string(argv[3]) == "1";
  std::ofstream list(out + "/frames.txt");
  try {
    sylva::capture::captureKinect(options, [&](sylva::capture::DepthFrame&& frame) {
      std::ofstream(fmt::format("{}/frame-{}.f32", out, frame.frame), std::ios::binary)
          .write(reinterpret_cast<const char*>(frame.depth.data()),
                 static_cast<std::streamsize>(frame.depth.size() * sizeof(float)));
      if (!frame.colour.empty()) {
        std::ofstream(fmt::format("{}/frame-{}.rgb", out, frame.frame), std::ios::binary)
            .write(reinterpret_cast<const char*>(frame.colour.data()),
                   static_cast<std::streamsize>(frame.colour.byteSize()));
      }
      list << fmt::format("{} {} {} {:.6f} {} {}\n", frame.frame, frame.width, frame.height, frame.timestamp,
                          frame.colour.empty() ? 0 : 1, frame.source);
      list.flush();
      return true;
    });
  } catch (const sylva::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
