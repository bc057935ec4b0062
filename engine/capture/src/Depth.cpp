// Depth frames and their file formats: the Kinect v1 raw scale, 16-bit depth PNGs, Middlebury disparity maps,
// previews.
#include <sylva/capture/Depth.hpp>
#include "internal/Limits.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::capture {

namespace {

// OpenKinect wiki fit of the Kinect v1 raw disparity: z = 1 / (raw·kSlope + kOffset).
constexpr double kSlope = -0.0030711016;
constexpr double kOffset = 3.3309495161;
/** The largest raw value with a positive depth (533 m; 1085 and above give a negative denominator). */
constexpr int kMaxValidRaw = 1084;

using internal::kMaxPixels;
using internal::kMaxSide;

const char* channelName(int channels) {
  switch (channels) {
  case 1:
    return "grey";
  case 2:
    return "grey+alpha";
  case 3:
    return "RGB";
  default:
    return "RGBA";
  }
}

/** "8-bit RGB", "16-bit grey", … */
std::string imageKind(const Image& image) {
  return fmt::format("{} {}", pixelTypeName(image.type()), channelName(image.channels()));
}

bool finitePositive(double value) {
  return std::isfinite(value) && value > 0.0;
}

} // namespace

float kinectRawToMetres(std::uint16_t raw) {
  if (raw >= kKinectNoData) {
    return 0.0f;
  }
  const double denominator = static_cast<double>(raw) * kSlope + kOffset;
  if (denominator <= 0.0) {
    return 0.0f;
  }
  return static_cast<float>(1.0 / denominator);
}

std::uint16_t metresToKinectRaw(float metres) {
  if (!std::isfinite(metres) || metres <= 0.0f) {
    return kKinectNoData;
  }
  const double raw = (1.0 / static_cast<double>(metres) - kOffset) / kSlope;
  if (!std::isfinite(raw)) {
    return kKinectNoData;
  }
  return static_cast<std::uint16_t>(
      std::clamp(std::llround(std::clamp(raw, -1.0, 1.0e6)), 0LL, static_cast<long long>(kMaxValidRaw)));
}

const char* depthSourceName(DepthSourceKind kind) {
  switch (kind) {
  case DepthSourceKind::DepthPng:
    return "depth-png";
  case DepthSourceKind::Middlebury:
    return "middlebury";
  case DepthSourceKind::Fakenect:
    return "fakenect";
  case DepthSourceKind::Kinect:
    return "kinect";
  case DepthSourceKind::Synthetic:
    return "synthetic";
  }
  return "unknown";
}

DepthFrame::DepthFrame(int width_, int height_) {
  if (width_ <= 0 || height_ <= 0 || width_ > kMaxSide || height_ > kMaxSide ||
      static_cast<std::int64_t>(width_) * height_ > kMaxPixels) {
    fail("depth frame size {}x{} is out of range (1..{} per side, at most {} pixels)", width_, height_,
         kMaxSide, kMaxPixels);
  }
  width = width_;
  height = height_;
  depth.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_), 0.0f);
  intrinsics = CameraIntrinsics::kinectV1Scaled(width_, height_);
}

std::string DepthFrame::label() const {
  if (kind == DepthSourceKind::Fakenect || kind == DepthSourceKind::Kinect) {
    return fmt::format("{} frame {}", source, frame);
  }
  return source;
}

DepthFrame loadDepthPng(const std::filesystem::path& path, const DepthPngOptions& options) {
  const std::string name = path.string();
  if (!finitePositive(options.unitMetres)) {
    fail("{}: depth unit must be a positive number of metres, got {}", name, options.unitMetres);
  }
  const Image image = loadPng(path);
  if (image.channels() != 1 || image.type() != PixelType::U16) {
    fail("{}: expected a single-channel 16-bit depth PNG, got {}{}", name, imageKind(image),
         image.type() == PixelType::U8 ? " (for an 8-bit disparity map use --format middlebury)" : "");
  }
  DepthFrame frame(image.width(), image.height());
  const std::span<const std::uint16_t> values = image.values<std::uint16_t>();
  std::size_t valid = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] != 0) {
      frame.depth[i] = static_cast<float>(values[i] * options.unitMetres);
      ++valid;
    }
  }
  if (valid == 0) {
    fail("{}: no valid depth pixel (every value is 0)", name);
  }
  frame.intrinsics = options.intrinsics.fx > 0.0
                         ? options.intrinsics
                         : CameraIntrinsics::kinectV1Scaled(image.width(), image.height());
  frame.kind = DepthSourceKind::DepthPng;
  frame.source = name;
  return frame;
}

namespace {

/** Metres per unit of the depth PNGs this module writes. */
constexpr double kDepthPngUnitMetres = 0.001;

/** A depth (metres) as a depth PNG stores it: whole millimetres, 0 for no data, clamped to 65535. */
std::uint16_t depthPngValue(float z) {
  if (!std::isfinite(z) || z <= 0.0f) {
    return 0;
  }
  return static_cast<std::uint16_t>(
      std::min(std::lround(static_cast<double>(z) / kDepthPngUnitMetres), 65535L));
}

} // namespace

void saveDepthPng(const std::filesystem::path& path, const DepthFrame& frame) {
  if (lowerExtension(path) != ".png") {
    fail("{}: a depth PNG needs the .png extension", path.string());
  }
  if (frame.width <= 0 || frame.height <= 0 ||
      frame.depth.size() != static_cast<std::size_t>(frame.width) * static_cast<std::size_t>(frame.height)) {
    fail("{}: cannot save an empty or inconsistent depth frame ({}x{}, {} values)", path.string(),
         frame.width, frame.height, frame.depth.size());
  }
  Image image(frame.width, frame.height, 1, PixelType::U16);
  const std::span<std::uint16_t> values = image.values<std::uint16_t>();
  for (std::size_t i = 0; i < values.size(); ++i) {
    values[i] = depthPngValue(frame.depth[i]);
  }
  saveImage(path, image);
}

void roundToDepthPng(DepthFrame& frame) {
  for (float& z : frame.depth) {
    z = static_cast<float>(depthPngValue(z) * kDepthPngUnitMetres);
  }
}

DepthFrame loadMiddlebury(const std::filesystem::path& path, const MiddleburyOptions& options) {
  const std::string name = path.string();
  const auto check = [&](double value, const char* field) {
    if (!finitePositive(value)) {
      fail("{}: Middlebury {} must be a positive number, got {}", name, field, value);
    }
  };
  check(options.focalPx, "focal length (px)");
  check(options.baselineMetres, "baseline (m)");
  check(options.disparityScale, "disparity scale");
  if (!std::isfinite(options.doffsPx)) {
    fail("{}: Middlebury doffs (px) must be a finite number, got {}", name, options.doffsPx);
  }
  const Image image = loadPng(path);
  if (image.type() != PixelType::U8 || (image.channels() != 1 && image.channels() != 3)) {
    fail("{}: expected a single-channel 8-bit Middlebury disparity map, got {}{}", name, imageKind(image),
         image.type() == PixelType::U16 ? " (for a 16-bit depth PNG use --format depth-png)" : "");
  }
  const std::span<const std::uint8_t> values = image.values<std::uint8_t>();
  const std::size_t channels = static_cast<std::size_t>(image.channels());
  DepthFrame frame(image.width(), image.height());
  const double numerator = options.focalPx * options.baselineMetres;
  std::size_t valid = 0;
  for (std::size_t i = 0; i < frame.depth.size(); ++i) {
    const std::uint8_t d = values[i * channels];
    if (channels == 3 && (values[i * 3 + 1] != d || values[i * 3 + 2] != d)) {
      const std::size_t x = i % static_cast<std::size_t>(image.width());
      const std::size_t y = i / static_cast<std::size_t>(image.width());
      fail("{}: expected a grey disparity map, but pixel ({}, {}) has different RGB channels", name, x, y);
    }
    if (d == 0) {
      continue;
    }
    const double denominator = options.disparityScale * d + options.doffsPx;
    const double z = denominator > 0.0 ? numerator / denominator : 0.0;
    if (std::isfinite(z) && z > 0.0 && z <= std::numeric_limits<float>::max()) {
      frame.depth[i] = static_cast<float>(z);
      ++valid;
    }
  }
  if (valid == 0) {
    fail("{}: no known disparity pixel (every value is 0)", name);
  }
  frame.intrinsics = {options.focalPx, options.focalPx, (image.width() - 1) / 2.0,
                      (image.height() - 1) / 2.0};
  frame.kind = DepthSourceKind::Middlebury;
  frame.source = name;
  frame.relativeDepth = !options.calibrated;
  return frame;
}

Image depthPreview(const DepthFrame& frame, float nearMetres, float farMetres) {
  if (!std::isfinite(nearMetres) || !std::isfinite(farMetres) || !(nearMetres < farMetres)) {
    fail("{}: depth preview range must have near < far, got [{}, {}] m", frame.label(), nearMetres,
         farMetres);
  }
  Image image(frame.width, frame.height, 1, PixelType::U8);
  const std::span<std::uint8_t> values = image.values<std::uint8_t>();
  const double span = static_cast<double>(farMetres) - nearMetres;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float z = frame.depth[i];
    if (!std::isfinite(z) || z <= 0.0f) {
      continue;
    }
    // Near is white (255), far is dark grey (32) so that it stays apart from "no data" (black).
    const double t = std::clamp((static_cast<double>(z) - nearMetres) / span, 0.0, 1.0);
    values[i] = static_cast<std::uint8_t>(std::lround(255.0 - t * 223.0));
  }
  return image;
}

std::pair<float, float> depthRange(const DepthFrame& frame) {
  float lo = std::numeric_limits<float>::infinity();
  float hi = 0.0f;
  for (const float z : frame.depth) {
    if (std::isfinite(z) && z > 0.0f) {
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  }
  if (hi == 0.0f) {
    return {0.0f, 0.0f};
  }
  return {lo, hi};
}

} // namespace sylva::capture
