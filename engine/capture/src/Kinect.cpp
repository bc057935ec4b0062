// Kinect v1 depth through libfreenect's C API: a live device, or a fakenect recording when the `fakenect`
// wrapper puts its replay library first (the same calls then read FAKENECT_PATH).
#include <sylva/capture/Kinect.hpp>

#include <sylva/capture/Fakenect.hpp>
#include <sylva/core/Error.hpp>

#include <libfreenect.h>

#include <sys/time.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

namespace sylva::capture {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/** Owns a libfreenect context, device and streams; stops and closes them on every path out. */
struct Session {
  freenect_context* context = nullptr;
  freenect_device* device = nullptr;
  bool depthStarted = false;
  bool videoStarted = false;

  Session() {
    if (freenect_init(&context, nullptr) < 0 || context == nullptr) {
      context = nullptr;
      fail("libfreenect could not start (no USB access?)");
    }
    freenect_set_log_level(context, FREENECT_LOG_FATAL);
    freenect_select_subdevices(context, FREENECT_DEVICE_CAMERA);
  }
  ~Session() {
    if (device != nullptr) {
      if (depthStarted) {
        freenect_stop_depth(device);
      }
      if (videoStarted) {
        freenect_stop_video(device);
      }
      freenect_close_device(device);
    }
    if (context != nullptr) {
      freenect_shutdown(context);
    }
  }
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  int deviceCount() const {
    const int count = freenect_num_devices(context);
    if (count < 0) {
      fail("libfreenect could not start (no USB access?): listing USB devices failed with error {}", count);
    }
    return count;
  }
};

/** What the callbacks hand over to the capture loop (they run inside freenect_process_events). */
struct Buffers {
  std::vector<std::uint16_t> depth;
  bool depthReady = false;
  Clock::time_point depthArrived;
  std::vector<std::uint8_t> rgb;
  bool rgbReady = false;
};

void onDepth(freenect_device* device, void* data, std::uint32_t /*timestamp*/) {
  auto* buffers = static_cast<Buffers*>(freenect_get_user(device));
  std::memcpy(buffers->depth.data(), data, buffers->depth.size() * sizeof(std::uint16_t));
  buffers->depthReady = true;
  buffers->depthArrived = Clock::now();
}

void onVideo(freenect_device* device, void* data, std::uint32_t /*timestamp*/) {
  auto* buffers = static_cast<Buffers*>(freenect_get_user(device));
  std::memcpy(buffers->rgb.data(), data, buffers->rgb.size());
  buffers->rgbReady = true;
}

std::string replayFolder() {
  const char* path = std::getenv("FAKENECT_PATH");
  return path != nullptr ? std::string(path) : std::string();
}

/**
 * Checks a recording before fakenect replays it: fakenect ends the process on a missing file and reads past a
 * short depth file, so both become errors here. Returns the number of depth frames.
 */
std::size_t checkReplay(const std::string& folder) {
  const FakenectRecording recording = FakenectRecording::open(folder);
  for (const std::string& warning : recording.warnings()) {
    if (warning.ends_with("listed in INDEX.txt is missing")) {
      fail("{} (fakenect cannot replay a recording with missing files)", warning);
    }
  }
  // "P5 640 480 65535\n" and 640×480 little-endian uint16 values: what fakenect copies into its depth buffer.
  constexpr std::uintmax_t kDepthFileBytes = 17 + 640 * 480 * 2;
  std::size_t frame = 0;
  for (const FakenectEntry& entry : recording.entries()) {
    if (entry.kind != 'd') {
      continue;
    }
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(fs::path(folder) / entry.file, ec);
    if (ec || size < kDepthFileBytes) {
      fail("{}: frame {}: a fakenect depth frame must be 640x480 ({} bytes), this file has {}",
           (fs::path(folder) / entry.file).string(), frame, kDepthFileBytes, ec ? 0 : size);
    }
    ++frame;
  }
  return recording.depthFrameCount();
}

} // namespace

bool kinectReplayActive() {
  const char* path = std::getenv("FAKENECT_PATH");
  return path != nullptr && path[0] != '\0';
}

int kinectDeviceCount() {
  const Session session;
  return session.deviceCount();
}

void captureKinect(const KinectOptions& options, const std::function<bool(DepthFrame&& frame)>& onFrame) {
  if (options.device < 0) {
    fail("kinect: device index must be >= 0, got {}", options.device);
  }
  if (options.frames < 0) {
    fail("kinect: frame count must be >= 0, got {}", options.frames);
  }
  if (!std::isfinite(options.timeoutSeconds) || options.timeoutSeconds <= 0.0) {
    fail("kinect: timeout must be a positive number of seconds, got {}", options.timeoutSeconds);
  }
  const bool replay = kinectReplayActive();
  const std::string folder = replay ? replayFolder() : std::string();
  const std::string source = replay ? "fakenect:" + folder : std::string("kinect");
  std::size_t target = static_cast<std::size_t>(options.frames);
  if (replay) {
    const std::size_t recorded = checkReplay(folder);
    if (target == 0) {
      target = recorded;
    }
  } else if (target == 0) {
    target = 1;
  }

  Session session;
  const int count = session.deviceCount();
  if (count == 0) {
    fail("no Kinect v1 found (libfreenect sees 0 devices): connect one, or replay a recording with `fakenect "
         "DIR "
         "sylva capture --kinect`");
  }
  if (options.device >= count) {
    fail("kinect: device {} does not exist (libfreenect sees {} device{})", options.device, count,
         count == 1 ? "" : "s");
  }
  if (freenect_open_device(session.context, &session.device, options.device) < 0) {
    session.device = nullptr;
    fail("kinect: cannot open device {} (in use by another program, or no permission: check the udev rules)",
         options.device);
  }

  const freenect_frame_mode depthMode =
      freenect_find_depth_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_DEPTH_11BIT);
  if (!depthMode.is_valid || depthMode.width <= 0 || depthMode.height <= 0) {
    fail("kinect: libfreenect has no 11-bit depth mode at 640x480");
  }
  Buffers buffers;
  buffers.depth.resize(static_cast<std::size_t>(depthMode.width) *
                       static_cast<std::size_t>(depthMode.height));
  freenect_set_user(session.device, &buffers);
  if (freenect_set_depth_mode(session.device, depthMode) < 0) {
    fail("kinect: cannot select the 11-bit depth mode");
  }
  freenect_set_depth_callback(session.device, onDepth);
  std::optional<freenect_frame_mode> videoMode;
  if (options.colour) {
    videoMode = freenect_find_video_mode(FREENECT_RESOLUTION_MEDIUM, FREENECT_VIDEO_RGB);
    if (!videoMode->is_valid || videoMode->width != depthMode.width ||
        videoMode->height != depthMode.height) {
      fail("kinect: libfreenect has no RGB mode matching the depth size");
    }
    buffers.rgb.resize(static_cast<std::size_t>(videoMode->width) *
                       static_cast<std::size_t>(videoMode->height) * 3);
    if (freenect_set_video_mode(session.device, *videoMode) < 0) {
      fail("kinect: cannot select the RGB video mode");
    }
    freenect_set_video_callback(session.device, onVideo);
    if (freenect_start_video(session.device) < 0) {
      fail("kinect: cannot start the RGB stream");
    }
    session.videoStarted = true;
  }
  if (freenect_start_depth(session.device) < 0) {
    fail("kinect: cannot start the depth stream");
  }
  session.depthStarted = true;

  const auto timeout = std::chrono::duration<double>(options.timeoutSeconds);
  Clock::time_point waitingSince = Clock::now();
  Clock::time_point first;
  std::size_t delivered = 0;
  while (delivered < target) {
    timeval tv{0, 100000};
    const int rc = freenect_process_events_timeout(session.context, &tv);
    if (rc < 0) {
      if (!replay) {
        fail("kinect: libfreenect stopped streaming (USB error {}) after {} frame{}", rc, delivered,
             delivered == 1 ? "" : "s");
      }
      if (delivered == 0) {
        fail("{}: the recording ended before any depth frame was replayed", folder);
      }
      break; // end of the recording
    }
    if (!buffers.depthReady) {
      if (Clock::now() - waitingSince > timeout) {
        fail("{}: no depth frame for {} s (after {} frame{})", source, options.timeoutSeconds, delivered,
             delivered == 1 ? "" : "s");
      }
      continue;
    }
    buffers.depthReady = false;
    waitingSince = Clock::now();
    if (delivered == 0) {
      first = buffers.depthArrived;
    }
    RawDepth raw;
    raw.width = depthMode.width;
    raw.height = depthMode.height;
    raw.raw = buffers.depth;
    DepthFrame frame = depthFromKinectRaw(raw);
    frame.kind = DepthSourceKind::Kinect;
    frame.source = source;
    frame.frame = static_cast<int>(delivered);
    frame.timestamp = std::chrono::duration<double>(buffers.depthArrived - first).count();
    if (buffers.rgbReady) {
      frame.colour = Image(videoMode->width, videoMode->height, 3, PixelType::U8);
      std::memcpy(frame.colour.data(), buffers.rgb.data(), frame.colour.byteSize());
    }
    ++delivered;
    if (!onFrame(std::move(frame))) {
      break;
    }
  }
}

} // namespace sylva::capture
