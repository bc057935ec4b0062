#pragma once
// Depth frames and their sources: 16-bit depth PNGs in millimetres, Middlebury disparity maps and the Kinect
// v1 raw 11-bit scale. Every loader returns depth in metres with the camera intrinsics needed to unproject a
// pixel.

#include <sylva/blades/CameraIntrinsics.hpp>
#include <sylva/core/Image.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::capture {

/** Pinhole intrinsics of the depth camera: the model the blade-model format records (sylva/blades). */
using blades::CameraIntrinsics;

/** Kinect v1 raw depth value that means "no data". */
inline constexpr std::uint16_t kKinectNoData = 2047;

/**
 * Kinect v1 raw 11-bit disparity to metres: z = 1 / (raw·(−0.0030711016) + 3.3309495161) (OpenKinect wiki
 * fit). Returns 0 (no data) for raw ≥ 2047 and for raws whose formula gives no positive depth (raw ≥ 1085;
 * raw 1084 is 533 m, raw 0 is 0.30 m).
 */
float kinectRawToMetres(std::uint16_t raw);

/**
 * Inverse of kinectRawToMetres: the nearest raw value for a depth in metres, clamped to [0, 1084]; 2047 for
 * z ≤ 0 or non-finite z (no data). Depth quantisation of the sensor follows from rounding here.
 */
std::uint16_t metresToKinectRaw(float metres);

/** Where a frame came from (metadata for blade-model files and messages). */
enum class DepthSourceKind { DepthPng, Middlebury, Fakenect, Kinect, Synthetic };
/** Short name: "depth-png", "middlebury", "fakenect", "kinect", "synthetic". */
const char* depthSourceName(DepthSourceKind kind);

/**
 * One depth frame in metres. Row-major, row 0 at the top; 0 means no data (never NaN or negative after a
 * loader). `colour` is an optional RGB8 frame registered to the depth pixels (same size), empty when absent.
 */
struct DepthFrame {
  /** Pixels per row. */
  int width = 0;
  /** Rows. */
  int height = 0;
  /** Depth per pixel, metres, row-major (0: no data). */
  std::vector<float> depth;
  /** Registered RGB8 colour frame of the same size, or empty. */
  Image colour;
  /** The depth camera (pixels). */
  CameraIntrinsics intrinsics;
  /** Where the frame came from. */
  DepthSourceKind kind = DepthSourceKind::DepthPng;
  /** The file (or "kinect") the frame came from, for messages and metadata. */
  std::string source;
  /** Frame number within a recording (0 for single images). */
  int frame = 0;
  /** Seconds since the first frame of a recording (0 for single images). */
  double timestamp = 0.0;
  /** True when depth is only known up to scale (Middlebury without calibration): metres are then nominal. */
  bool relativeDepth = false;

  DepthFrame() = default;
  /** A frame of the given size with every pixel "no data". Throws sylva::Error for non-positive or absurd
   * sizes. */
  DepthFrame(int width, int height);
  /** Depth of pixel (x, y), metres (0: no data); no bounds checks. */
  float at(int x, int y) const { return depth[static_cast<std::size_t>(y) * width + x]; }
  /** Depth of pixel (x, y), metres, for writing; no bounds checks. */
  float& at(int x, int y) { return depth[static_cast<std::size_t>(y) * width + x]; }
  /** A name for messages: "<source>" or "<source> frame <n>" for recordings. */
  std::string label() const;
};

/** Options of a 16-bit depth PNG. */
struct DepthPngOptions {
  /** Metres per stored unit (0.001: millimetres, what RealSense and Kinect tools save). */
  double unitMetres = 0.001;
  /** Intrinsics; when unset (fx ≤ 0) the Kinect v1 intrinsics scaled to the image size. */
  CameraIntrinsics intrinsics{0, 0, 0, 0};
};

/**
 * Loads a single-channel 16-bit PNG of depth (0 = no data). Throws sylva::Error naming the file for a missing
 * or corrupt file, an 8-bit or float image ("expected a 16-bit depth PNG, got 8-bit"; use the Middlebury
 * loader for 8-bit disparity), more than one channel, or an image with no valid pixel.
 */
DepthFrame loadDepthPng(const std::filesystem::path& path, const DepthPngOptions& options = {});

/**
 * Writes a frame as a 16-bit PNG in millimetres (depth rounded to the nearest mm, clamped to 65535; no data
 * as 0), atomically.
 */
void saveDepthPng(const std::filesystem::path& path, const DepthFrame& frame);

/**
 * The depth a depth PNG holds (saveDepthPng then loadDepthPng): each value rounded to the nearest millimetre,
 * clamped to 65.535 m; no data (0, negative or not finite) as 0. Lets a frame captured in memory be captured
 * exactly as the file written from it will be.
 */
void roundToDepthPng(DepthFrame& frame);

/**
 * Middlebury calibration: depth z = focal·baseline / (disparityScale·d + doffs) for a stored value d > 0. The
 * defaults are the 2006 datasets' full-size values (focal 3740 px, baseline 160 mm, doffs 0), so depths are
 * nominal unless the dataset's doffs is known; the frame is marked relativeDepth unless `calibrated`.
 */
struct MiddleburyOptions {
  /** Focal length, pixels. */
  double focalPx = 3740.0;
  /** Distance between the two cameras, metres. */
  double baselineMetres = 0.160;
  /** Disparity offset between the two principal points, pixels. */
  double doffsPx = 0.0;
  /** Stored value to disparity in pixels at the image's resolution. */
  double disparityScale = 1.0;
  /** True when focal, baseline and doffs are the dataset's real calibration. */
  bool calibrated = false;
};

/**
 * Loads an 8-bit Middlebury disparity map (value = disparity in pixels, 0 = unknown). Intrinsics: fx = fy =
 * focal, principal point at the image centre. Throws sylva::Error naming the file for a missing or corrupt
 * file, a 16-bit image or more than one channel (or RGB whose channels differ), or no known pixel.
 */
DepthFrame loadMiddlebury(const std::filesystem::path& path, const MiddleburyOptions& options = {});

/** The frame's depth as an 8-bit grey image: near → white, far → dark, no data → black; range [near, far] m.
 */
Image depthPreview(const DepthFrame& frame, float nearMetres, float farMetres);

/** Valid (non-zero) depth range of a frame in metres as {min, max}; {0, 0} when no pixel is valid. */
std::pair<float, float> depthRange(const DepthFrame& frame);

} // namespace sylva::capture
