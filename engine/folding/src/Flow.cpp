// Motion from a reference video: decoding (OpenCV videoio over FFmpeg, or image sequences), dense optical
// flow (OpenCV's DIS and Farnebäck), and the step from a flow field to point anchors inside a zone.
#include <sylva/folding/Flow.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/ImageHeader.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Field.hpp>

#include "internal/VideoFile.hpp"

#include <fmt/format.h>

#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <opencv2/videoio.hpp>
#include <opencv2/videoio/registry.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <optional>
#include <string>

namespace sylva::folding {

namespace {

namespace fs = std::filesystem;

/** OpenCV messages can span lines; a sylva::Error is one line. */
std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  while (!text.empty() && text.back() == ' ') {
    text.pop_back();
  }
  return text;
}

/** OpenCV's own warnings would add lines to the CLI's one-line errors; failures are reported by us instead.
 */
void quietOpenCv() {
  static const bool once = [] {
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    return true;
  }();
  (void)once;
}

bool isPattern(const fs::path& path) {
  return path.string().find('%') != std::string::npos;
}

/** An image-sequence pattern: one printf integer conversion (%d, %4d, %04d), as OpenCV's reader expects. */
struct SequencePattern {
  std::string prefix;     ///< the name before the conversion
  std::string suffix;     ///< the name after it
  std::size_t digits = 0; ///< the field width (0: as many as the number needs)
  bool zeroPad = false;   ///< pad with zeros (%04d) rather than spaces (%4d)

  /** Parses `name`; throws sylva::Error naming it when it does not hold exactly one such conversion. */
  static SequencePattern parse(const std::string& name) {
    const std::size_t percent = name.find('%');
    const std::size_t end = name.find('d', percent);
    const std::string spec = end == std::string::npos ? "x" : name.substr(percent + 1, end - percent - 1);
    if (end == std::string::npos || name.find('%', percent + 1) != std::string::npos || spec.size() > 2 ||
        !std::all_of(spec.begin(), spec.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      fail("{}: expected one %d conversion, e.g. frames/%04d.png", name);
    }
    return {name.substr(0, percent), name.substr(end + 1),
            spec.empty() ? 0 : static_cast<std::size_t>(std::stoi(spec)), !spec.empty() && spec[0] == '0'};
  }

  /** The file name of frame `index`. */
  std::string frame(std::size_t index) const {
    std::string number = std::to_string(index);
    if (number.size() < digits) {
      number.insert(0, digits - number.size(), zeroPad ? '0' : ' ');
    }
    return prefix + number + suffix;
  }
};

/**
 * Refuses an image sequence whose frames (numbered from 0 or 1, as OpenCV reads them; up to maxFrames + 1,
 * the one past the last read telling whether the clip was cut short) state more than kMaxVideoSide pixels per
 * side in their headers, before OpenCV decodes, and allocates for, any of them: a 2.6 KB progressive JPEG
 * claiming 20000×20000 pixels made libjpeg zero about 2 GB (fuzz/regressions/flow). A frame whose size the
 * header does not give (a format readImageHeader does not read, such as DICOM, or a cut header) is refused
 * too: OpenCV would decode it unchecked. The flow fuzz target found such a file asking for 2.2 GB (12 bytes a
 * pixel: the 3 floats OpenCV decodes Radiance and PFM files to, formats read here since).
 */
void checkSequenceHeaders(const std::string& name, int maxFrames) {
  const SequencePattern pattern = SequencePattern::parse(name);
  std::error_code ec;
  const std::size_t first = fs::is_regular_file(pattern.frame(0), ec) ? 0 : 1;
  for (std::size_t i = first; i <= first + static_cast<std::size_t>(maxFrames); ++i) {
    const std::string file = pattern.frame(i);
    if (!fs::is_regular_file(file, ec)) {
      break;
    }
    const std::optional<ImageHeader> header = readImageHeader(file);
    if (!header) {
      fail("{}: frame file {} is not an image whose size can be read before decoding (PNG, JPEG, WebP, TIFF, "
           "BMP, OpenEXR, PNM/PAM/PFM, Sun raster, Radiance HDR or JPEG 2000), or its header is cut short",
           name, fs::path(file).filename().string());
    }
    if (header->width > kMaxVideoSide || header->height > kMaxVideoSide) {
      fail("{}: frame file {} is a {} of {}×{} pixels, over the {} per side this loader accepts", name,
           fs::path(file).filename().string(), header->format, header->width, header->height, kMaxVideoSide);
    }
  }
}

/** One decoded frame as RGBA8, whatever OpenCV handed back (BGR, grey, BGRA; 8 or 16 bits). */
Image toRgba(const cv::Mat& frame) {
  cv::Mat bytes = frame;
  if (frame.depth() != CV_8U) {
    const double scale = frame.depth() == CV_16U ? 1.0 / 257.0 : frame.depth() == CV_32F ? 255.0 : 1.0;
    frame.convertTo(bytes, CV_8U, scale);
  }
  cv::Mat rgba;
  switch (bytes.channels()) {
  case 1:
    cv::cvtColor(bytes, rgba, cv::COLOR_GRAY2RGBA);
    break;
  case 3:
    cv::cvtColor(bytes, rgba, cv::COLOR_BGR2RGBA);
    break;
  case 4:
    cv::cvtColor(bytes, rgba, cv::COLOR_BGRA2RGBA);
    break;
  default:
    fail("{} channels", bytes.channels());
  }
  Image image(rgba.cols, rgba.rows, 4, PixelType::U8);
  for (int y = 0; y < rgba.rows; ++y) {
    std::copy_n(reinterpret_cast<const std::byte*>(rgba.ptr(y)), image.rowBytes(),
                image.data() + static_cast<std::size_t>(y) * image.rowBytes());
  }
  return image;
}

/** An image as an 8-bit grey OpenCV matrix (Rec. 601 weights), owning its data. */
cv::Mat toGrey(const Image& image) {
  const Image bytes = image.type() == PixelType::U8 ? image : image.converted(PixelType::U8);
  const int type = CV_MAKETYPE(CV_8U, bytes.channels());
  const cv::Mat view(bytes.height(), bytes.width(), type, const_cast<std::byte*>(bytes.data()),
                     bytes.rowBytes());
  cv::Mat grey;
  switch (bytes.channels()) {
  case 1:
    grey = view.clone();
    break;
  case 2: {
    cv::extractChannel(view, grey, 0);
    break;
  }
  case 3:
    cv::cvtColor(view, grey, cv::COLOR_RGB2GRAY);
    break;
  default:
    cv::cvtColor(view, grey, cv::COLOR_RGBA2GRAY);
    break;
  }
  return grey;
}

cv::Mat toBgr(const Image& image) {
  const Image bytes = image.type() == PixelType::U8 ? image : image.converted(PixelType::U8);
  const cv::Mat view(bytes.height(), bytes.width(), CV_MAKETYPE(CV_8U, bytes.channels()),
                     const_cast<std::byte*>(bytes.data()), bytes.rowBytes());
  cv::Mat bgr;
  switch (bytes.channels()) {
  case 1:
    cv::cvtColor(view, bgr, cv::COLOR_GRAY2BGR);
    break;
  case 2: {
    cv::Mat grey;
    cv::extractChannel(view, grey, 0);
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    break;
  }
  case 3:
    cv::cvtColor(view, bgr, cv::COLOR_RGB2BGR);
    break;
  default:
    cv::cvtColor(view, bgr, cv::COLOR_RGBA2BGR);
    break;
  }
  return bgr;
}

bool finite(double v) {
  return std::isfinite(v);
}

/** Mean of `flow` over the (2r+1)² bilinear samples about p, and the RMS deviation from that mean. */
struct WindowFlow {
  glm::dvec2 mean{0.0};
  double deviation = 0.0;
};
WindowFlow windowFlow(const FlowField& flow, Vec2 p, int r) {
  glm::dvec2 sum(0.0);
  double sumSq = 0.0;
  const double n = static_cast<double>((2 * r + 1) * (2 * r + 1));
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const glm::dvec2 v(flow.sample(p + Vec2(dx, dy)));
      sum += v;
      sumSq += glm::dot(v, v);
    }
  }
  WindowFlow w;
  w.mean = sum / n;
  w.deviation = std::sqrt(std::max(0.0, sumSq / n - glm::dot(w.mean, w.mean)));
  return w;
}

double round3(double v) {
  return std::round(v * 1000.0) / 1000.0;
}

// ---------------------------------------------------------------------------------------------------------
// The synthetic clip's texture: a sum of seeded sinusoids (band-limited, so any sub-pixel shift is exact).

struct Wave {
  glm::dvec2 k{0.0}; ///< radians per pixel
  double phase = 0.0;
};

struct Texture {
  std::vector<Wave> luma;
  std::array<Wave, 2> tint{};

  explicit Texture(std::uint64_t seed) {
    Rng rng(seed);
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    for (int i = 0; i < 24; ++i) {
      // Wavelengths 6..48 px, log-uniform, so every scale has structure.
      const double wavelength = 6.0 * std::pow(8.0, static_cast<double>(rng.uniform()));
      const double angle = kTwoPi * rng.uniform();
      luma.push_back(
          {glm::dvec2(std::cos(angle), std::sin(angle)) * (kTwoPi / wavelength), kTwoPi * rng.uniform()});
    }
    for (Wave& w : tint) {
      const double angle = kTwoPi * rng.uniform();
      w = {glm::dvec2(std::cos(angle), std::sin(angle)) * (kTwoPi / 64.0), kTwoPi * rng.uniform()};
    }
  }

  /** RGB in [0, 1] at continuous pixel coordinates p. */
  glm::dvec3 at(Vec2 p) const {
    // 24 unit waves of random phase have an RMS of √12; scaled to an RMS of 0.15 about mid-grey.
    double l = 0.0;
    for (const Wave& w : luma) {
      l += std::cos(glm::dot(w.k, p) + w.phase);
    }
    l = 0.5 + l * (0.15 / std::sqrt(12.0));
    const double t0 = 0.08 * std::cos(glm::dot(tint[0].k, p) + tint[0].phase);
    const double t1 = 0.08 * std::cos(glm::dot(tint[1].k, p) + tint[1].phase);
    return glm::clamp(glm::dvec3(l + t0, l, l + t1), 0.0, 1.0);
  }
};

glm::dmat2 rotation(double radians) {
  const double c = std::cos(radians);
  const double s = std::sin(radians);
  // Column-major: the first column is the image of +x, turned towards +y for positive angles.
  return glm::dmat2(c, s, -s, c);
}

} // namespace

// ---------------------------------------------------------------------------------------------------------
// Loading and saving clips

VideoClip loadVideo(const std::filesystem::path& path, int maxFrames, Progress* progress) {
  const std::string name = path.string();
  if (maxFrames < 1) {
    fail("{}: at least one frame must be read (maxFrames {})", name, maxFrames);
  }
  const bool pattern = isPattern(path);
  if (pattern) {
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(dir)) {
      fail("{}: no such directory '{}'", name, dir.string());
    }
  } else if (!fs::exists(path)) {
    fail("{}: no such file", name);
  } else if (fs::is_directory(path)) {
    fail("{}: is a directory; expected a video file or an image-sequence pattern such as frames/%04d.png",
         name);
  }
  if (pattern) {
    checkSequenceHeaders(name, maxFrames);
  }

  VideoClip clip;
  // Takes one decoded frame: constant size, the memory cap, its presentation time, progress.
  const auto add = [&](Image rgba, double timeS) {
    const int index = static_cast<int>(clip.frames.size());
    if (index == 0) {
      clip.size = {rgba.width(), rgba.height()};
    } else if (rgba.width() != clip.size.x || rgba.height() != clip.size.y) {
      fail("{}: frame {} is {}×{} pixels, frame 0 is {}×{}", name, index, rgba.width(), rgba.height(),
           clip.size.x, clip.size.y);
    }
    if ((clip.frames.size() + 1) * rgba.byteSize() > kMaxVideoBytes) {
      fail("{}: {} frames of {}×{} pixels need more than {} GiB; read fewer frames", name, index + 1,
           rgba.width(), rgba.height(), kMaxVideoBytes >> 30);
    }
    clip.frames.push_back(std::move(rgba));
    // The container's presentation time when it has one that increases, else a step of the nominal rate.
    const double step = clip.fps > 0.0 ? 1.0 / clip.fps : 1.0;
    double t = finite(timeS) && timeS >= 0.0 ? timeS : 0.0;
    if (index > 0 && !(t > clip.timesS.back())) {
      t = clip.timesS.back() + step;
    }
    clip.timesS.push_back(t);
    if (progress) {
      progress->advance();
      if (progress->cancelled()) {
        fail("{}: loading cancelled", name);
      }
    }
  };
  const auto wanted = [&] { return static_cast<int>(clip.frames.size()) < maxFrames; };

  if (pattern) {
    // Image sequences: OpenCV's image readers (libpng, libjpeg, …), one file per frame.
    quietOpenCv();
    if (!cv::videoio_registry::hasBackend(cv::CAP_IMAGES)) {
      fail("{}: this OpenCV has no image-sequence backend to read it", name);
    }
    try {
      cv::VideoCapture capture;
      if (!capture.open(name, cv::CAP_IMAGES) || !capture.isOpened()) {
        fail("{}: no image matches the pattern (frames are numbered from 0 or 1)", name);
      }
      const double fps = capture.get(cv::CAP_PROP_FPS);
      clip.fps = finite(fps) && fps > 0.0 && fps < 1e4 ? fps : 0.0;
      cv::Mat frame;
      while (wanted() && capture.read(frame) && !frame.empty()) {
        const int index = static_cast<int>(clip.frames.size());
        if (frame.cols > kMaxVideoSide || frame.rows > kMaxVideoSide || frame.cols < 1 || frame.rows < 1) {
          fail("{}: frames of {}×{} pixels exceed the {} per side this loader accepts", name, frame.cols,
               frame.rows, kMaxVideoSide);
        }
        Image rgba = [&] {
          try {
            return toRgba(frame);
          } catch (const Error& e) {
            fail("{}: frame {} has {}", name, index, e.what());
          }
        }();
        add(std::move(rgba), capture.get(cv::CAP_PROP_POS_MSEC) / 1000.0);
      }
      clip.truncated = !wanted() && capture.grab();
    } catch (const cv::Exception& e) {
      fail("{}: cannot decode: {}", name, oneLine(e.err));
    }
  } else {
    // Containers: FFmpeg's libraries directly (internal/VideoFile.hpp says why not OpenCV's capture).
    internal::VideoFile video(name, kMaxVideoSide);
    clip.fps = video.fps();
    Image rgba;
    double timeS = 0.0;
    while (wanted() && video.read(rgba, timeS)) {
      add(std::move(rgba), timeS);
    }
    clip.truncated = !wanted() && video.read(rgba, timeS);
  }
  if (clip.frames.empty()) {
    fail("{}: no frame could be decoded", name);
  }
  return clip;
}

void saveVideo(const std::filesystem::path& path, const VideoClip& clip) {
  const std::string name = path.string();
  if (clip.frames.empty()) {
    fail("{}: a clip without frames cannot be written", name);
  }
  for (std::size_t i = 0; i < clip.frames.size(); ++i) {
    if (clip.frames[i].width() != clip.frames[0].width() ||
        clip.frames[i].height() != clip.frames[0].height()) {
      fail("{}: frame {} differs in size from frame 0", name, i);
    }
  }
  if (isPattern(path)) {
    const SequencePattern frames = SequencePattern::parse(name);
    if (lowerExtension(path) != ".png" || frames.suffix.find_first_of("/\\") != std::string::npos) {
      fail("{}: image sequences are written as PNG (.png)", name);
    }
    for (std::size_t i = 0; i < clip.frames.size(); ++i) {
      saveImage(frames.frame(i), clip.frames[i]);
    }
    return;
  }
  if (lowerExtension(path) != ".avi") {
    fail("{}: videos are written as Motion-JPEG .avi (or a PNG pattern such as frames/%04d.png)", name);
  }
  quietOpenCv();
  const int width = clip.frames[0].width();
  const int height = clip.frames[0].height();
  writeFileAtomically(path, [&](const fs::path& tmp) {
    // OpenCV picks the container from the extension, so the frames go to `<tmp>.avi`, renamed to the
    // temporary that writeFileAtomically then renames over `path`.
    const fs::path avi = tmp.string() + ".avi";
    try {
      cv::VideoWriter writer;
      const std::vector<int> params = {cv::VIDEOWRITER_PROP_QUALITY, 100};
      if (!writer.open(avi.string(), cv::CAP_OPENCV_MJPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'),
                       clip.fps > 0.0 ? clip.fps : 25.0, cv::Size(width, height), params)) {
        fail("{}: cannot open the Motion-JPEG writer", name);
      }
      for (const Image& frame : clip.frames) {
        writer.write(toBgr(frame));
      }
      writer.release();
      fs::rename(avi, tmp);
    } catch (const cv::Exception& e) {
      std::error_code ignored;
      fs::remove(avi, ignored);
      fail("{}: cannot write: {}", name, oneLine(e.err));
    } catch (...) {
      std::error_code ignored;
      fs::remove(avi, ignored);
      throw;
    }
  });
}

// ---------------------------------------------------------------------------------------------------------
// Flow

glm::vec2 FlowField::sample(Vec2 p) const {
  const double u = std::clamp(p.x - 0.5, 0.0, static_cast<double>(width - 1));
  const double w = std::clamp(p.y - 0.5, 0.0, static_cast<double>(height - 1));
  const int x0 = static_cast<int>(u);
  const int y0 = static_cast<int>(w);
  const int x1 = std::min(x0 + 1, width - 1);
  const int y1 = std::min(y0 + 1, height - 1);
  const float fx = static_cast<float>(u - x0);
  const float fy = static_cast<float>(w - y0);
  const glm::vec2 top = glm::mix(at(x0, y0), at(x1, y0), fx);
  const glm::vec2 bottom = glm::mix(at(x0, y1), at(x1, y1), fx);
  return glm::mix(top, bottom, fy);
}

double FlowField::meanMagnitude() const {
  double sum = 0.0;
  for (const glm::vec2& f : v) {
    sum += glm::length(glm::dvec2(f));
  }
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

double FlowField::maxMagnitude() const {
  double largest = 0.0;
  for (const glm::vec2& f : v) {
    largest = std::max(largest, glm::length(glm::dvec2(f)));
  }
  return largest;
}

const char* flowMethodName(FlowMethod method) {
  return method == FlowMethod::Dis ? "dis" : "farneback";
}

FlowField computeFlow(const Image& a, const Image& b, FlowMethod method) {
  if (a.width() != b.width() || a.height() != b.height()) {
    fail("optical flow: frames of {}×{} and {}×{} pixels differ in size", a.width(), a.height(), b.width(),
         b.height());
  }
  if (a.width() < 16 || a.height() < 16) {
    fail("optical flow: frames of {}×{} pixels are too small (at least 16×16)", a.width(), a.height());
  }
  quietOpenCv();
  cv::Mat flow;
  try {
    const cv::Mat ga = toGrey(a);
    const cv::Mat gb = toGrey(b);
    if (method == FlowMethod::Dis) {
      cv::Ptr<cv::DISOpticalFlow> dis = cv::DISOpticalFlow::create(cv::DISOpticalFlow::PRESET_MEDIUM);
      dis->calc(ga, gb, flow);
    } else {
      cv::calcOpticalFlowFarneback(ga, gb, flow, 0.5, 5, 15, 3, 5, 1.2, 0);
    }
  } catch (const cv::Exception& e) {
    fail("optical flow ({}): {}", flowMethodName(method), oneLine(e.err));
  }
  FlowField field;
  field.width = a.width();
  field.height = a.height();
  field.v.resize(static_cast<std::size_t>(field.width) * static_cast<std::size_t>(field.height));
  for (int y = 0; y < field.height; ++y) {
    const cv::Vec2f* row = flow.ptr<cv::Vec2f>(y);
    for (int x = 0; x < field.width; ++x) {
      field.v[static_cast<std::size_t>(y) * static_cast<std::size_t>(field.width) +
              static_cast<std::size_t>(x)] = glm::vec2(row[x][0], row[x][1]);
    }
  }
  return field;
}

double consistentFraction(const FlowField& forward, const FlowField& backward, double tolerancePx) {
  if (forward.empty() || forward.width != backward.width || forward.height != backward.height) {
    fail("optical flow: forward and backward flows differ in size");
  }
  std::size_t good = 0;
  for (int y = 0; y < forward.height; ++y) {
    for (int x = 0; x < forward.width; ++x) {
      const glm::dvec2 f(forward.at(x, y));
      const Vec2 q = Vec2(x + 0.5, y + 0.5) + f;
      if (q.x < 0.0 || q.y < 0.0 || q.x > forward.width || q.y > forward.height) {
        continue;
      }
      good += glm::length(f + glm::dvec2(backward.sample(q))) <= tolerancePx;
    }
  }
  return static_cast<double>(good) / static_cast<double>(forward.v.size());
}

Image flowPicture(const FlowField& flow, double maxMagnitude) {
  if (flow.empty()) {
    fail("flow picture: empty flow field");
  }
  const double top = maxMagnitude > 0.0 ? maxMagnitude : std::max(flow.maxMagnitude(), 1e-9);
  Image picture(flow.width, flow.height, 4, PixelType::U8);
  std::uint8_t* out = picture.values<std::uint8_t>().data();
  for (int y = 0; y < flow.height; ++y) {
    for (int x = 0; x < flow.width; ++x) {
      const glm::dvec2 f(flow.at(x, y));
      const double value = std::min(1.0, glm::length(f) / top);
      // Hue in sixths of a turn from +x (red), turning towards +y.
      double hue = std::atan2(f.y, f.x) / (2.0 * std::numbers::pi);
      hue = (hue - std::floor(hue)) * 6.0;
      const int sector = std::min(5, static_cast<int>(hue));
      const double frac = hue - sector;
      const double rising = value * frac;
      const double falling = value * (1.0 - frac);
      const std::array<glm::dvec3, 6> rgb = {glm::dvec3(value, rising, 0.0), glm::dvec3(falling, value, 0.0),
                                             glm::dvec3(0.0, value, rising), glm::dvec3(0.0, falling, value),
                                             glm::dvec3(rising, 0.0, value), glm::dvec3(value, 0.0, falling)};
      const glm::dvec3 c = rgb[static_cast<std::size_t>(sector)];
      std::uint8_t* px = out + (static_cast<std::size_t>(y) * static_cast<std::size_t>(flow.width) +
                                static_cast<std::size_t>(x)) *
                                   4;
      for (int ch = 0; ch < 3; ++ch) {
        px[ch] = static_cast<std::uint8_t>(std::lround(std::clamp(c[ch], 0.0, 1.0) * 255.0));
      }
      px[3] = 255;
    }
  }
  return picture;
}

// ---------------------------------------------------------------------------------------------------------
// Suggestions

std::vector<std::array<Vec2, 2>> suggestAnchors(const FlowField& forward, const Shape& zoneShape,
                                                glm::ivec2 imageSize, const FlowSuggestOptions& options,
                                                const FlowField* backward, FlowSuggestStats* stats) {
  if (forward.empty() || forward.v.size() != static_cast<std::size_t>(forward.width) *
                                                 static_cast<std::size_t>(forward.height)) {
    fail("motion from video: empty flow field");
  }
  if (backward && (backward->width != forward.width || backward->height != forward.height ||
                   backward->v.size() != forward.v.size())) {
    fail("motion from video: the backward flow is {}×{} pixels, the forward one {}×{}", backward->width,
         backward->height, forward.width, forward.height);
  }
  if (imageSize.x < 1 || imageSize.y < 1) {
    fail("motion from video: image size {}×{} pixels", imageSize.x, imageSize.y);
  }
  if (!finite(options.spacingPx) || options.spacingPx < 1.0 || options.spacingPx > 1e4) {
    fail("motion from video: spacing {} px is outside 1..10000", options.spacingPx);
  }
  if (!finite(options.minMagnitudePx) || options.minMagnitudePx < 0.0) {
    fail("motion from video: minimum magnitude {} px must be ≥ 0", options.minMagnitudePx);
  }
  if (!finite(options.scale) || std::abs(options.scale) > 100.0) {
    fail("motion from video: scale {} is outside -100..100", options.scale);
  }
  if (options.maxAnchors < 1 || options.maxAnchors > 100000) {
    fail("motion from video: max anchors {} is outside 1..100000", options.maxAnchors);
  }
  if (!finite(options.maxInconsistencyPx) || options.maxInconsistencyPx <= 0.0 ||
      !finite(options.maxDeviationPx) || options.maxDeviationPx <= 0.0) {
    fail("motion from video: the consistency and deviation limits must be > 0 pixels");
  }
  const std::vector<Vec2> outline = zoneShape.outline();
  Vec2 lo(1e300);
  Vec2 hi(-1e300);
  for (const Vec2& p : outline) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  if (outline.size() < 3 || !(hi.x - lo.x > 0.0) || !(hi.y - lo.y > 0.0)) {
    fail("motion from video: the zone has no area");
  }
  const double cells = (hi.x - lo.x) / options.spacingPx * ((hi.y - lo.y) / options.spacingPx);
  if (cells > 4e6) {
    fail("motion from video: {:.0f} grid points at {} px spacing; use a larger spacing", cells,
         options.spacingPx);
  }

  // Frame rectangle [0, w] × [0, h] onto the target rectangle, each axis on its own.
  const Vec2 targetMin = options.mapping == FlowSuggestOptions::Mapping::Zone ? lo : Vec2(0.0);
  const Vec2 targetMax = options.mapping == FlowSuggestOptions::Mapping::Zone ? hi : Vec2(imageSize);
  const Vec2 frameSize(forward.width, forward.height);
  const Vec2 s = (targetMax - targetMin) / frameSize;
  // Window: about one grid cell in frame pixels, 3×3 to 17×17 texels.
  const double cellFrame = std::min(options.spacingPx / s.x, options.spacingPx / s.y);
  const int radius = std::clamp(static_cast<int>(std::floor(0.5 * cellFrame)), 1, 8);

  FlowSuggestStats st;
  st.imagePerFramePx = s;
  std::vector<std::array<Vec2, 2>> pairs;
  for (double y = lo.y + 0.5 * options.spacingPx; y < hi.y; y += options.spacingPx) {
    for (double x = lo.x + 0.5 * options.spacingPx; x < hi.x; x += options.spacingPx) {
      const Vec2 a(x, y);
      if (!insidePolygon(outline, a) || a.x < targetMin.x || a.y < targetMin.y || a.x > targetMax.x ||
          a.y > targetMax.y) {
        continue;
      }
      ++st.samples;
      const Vec2 p = (a - targetMin) / s;
      const WindowFlow f = windowFlow(forward, p, radius);
      if (f.deviation > options.maxDeviationPx) {
        ++st.irregular;
        continue;
      }
      if (backward) {
        const Vec2 q = p + f.mean;
        if (q.x < 0.0 || q.y < 0.0 || q.x > frameSize.x || q.y > frameSize.y) {
          ++st.inconsistent;
          continue;
        }
        const WindowFlow g = windowFlow(*backward, q, radius);
        if (glm::length(f.mean + g.mean) > options.maxInconsistencyPx) {
          ++st.inconsistent;
          continue;
        }
      }
      const Vec2 v = f.mean * s * options.scale;
      if (glm::length(v) < options.minMagnitudePx || glm::length(v) == 0.0) {
        ++st.still;
        continue;
      }
      const Vec2 from(round3(a.x), round3(a.y));
      const Vec2 to(round3(a.x + v.x), round3(a.y + v.y));
      if (from == to) {
        ++st.still;
        continue;
      }
      pairs.push_back({from, to});
    }
  }
  const std::size_t keep = static_cast<std::size_t>(options.maxAnchors);
  if (pairs.size() > keep) {
    // Evenly spread in scan order, so the kept anchors still cover the whole zone.
    std::vector<std::array<Vec2, 2>> thinned;
    thinned.reserve(keep);
    for (std::size_t j = 0; j < keep; ++j) {
      thinned.push_back(pairs[(2 * j + 1) * pairs.size() / (2 * keep)]);
    }
    st.thinned = pairs.size() - keep;
    pairs = std::move(thinned);
  }
  if (stats) {
    *stats = st;
  }
  return pairs;
}

PointsTool pointsToolFromSuggestions(const std::vector<std::array<Vec2, 2>>& pairs) {
  if (pairs.empty()) {
    fail("motion from video: no anchors to apply (the flow is still in the zone, or every sample was "
         "dropped)");
  }
  if (pairs.size() > 100000) {
    fail("motion from video: {} anchors, more than the 100000 a points tool holds", pairs.size());
  }
  for (const auto& [a, b] : pairs) {
    if (!finite(a.x) || !finite(a.y) || !finite(b.x) || !finite(b.y)) {
      fail("motion from video: an anchor is not finite");
    }
  }
  PointsTool tool;
  tool.pairs = pairs;
  return tool;
}

void applyFlowSuggestion(EditHistory& history, int zone, const std::vector<std::array<Vec2, 2>>& pairs) {
  const PointsTool tool = pointsToolFromSuggestions(pairs);
  if (zone < 0 || zone >= static_cast<int>(history.project().zones.size())) {
    fail("motion from video: no zone {} (the project has {})", zone, history.project().zones.size());
  }
  history.apply("motion from video", zone,
                [&](Project& p) { p.zones[static_cast<std::size_t>(zone)].tools.push_back(tool); });
}

// ---------------------------------------------------------------------------------------------------------
// Synthetic clips

Vec2 SyntheticMotion::flowAt(Vec2 p) const {
  if (radius > 0.0 && glm::length(p - centre) < radius) {
    return centre + scale * (rotation(rotationRad) * (p - centre)) - p;
  }
  return translation;
}

VideoClip syntheticVideo(glm::ivec2 size, int frames, const SyntheticMotion& motion, std::uint64_t seed,
                         double fps) {
  if (size.x < 16 || size.y < 16 || size.x > kMaxVideoSide || size.y > kMaxVideoSide) {
    fail("synthetic video: {}×{} pixels is outside 16..{} per side", size.x, size.y, kMaxVideoSide);
  }
  if (frames < 1 || static_cast<std::size_t>(frames) * static_cast<std::size_t>(size.x) *
                            static_cast<std::size_t>(size.y) * 4 >
                        kMaxVideoBytes) {
    fail("synthetic video: {} frames of {}×{} pixels is not between 1 frame and {} GiB", frames, size.x,
         size.y, kMaxVideoBytes >> 30);
  }
  if (!(motion.scale > 0.0) || !finite(motion.scale) || !finite(motion.rotationRad) ||
      !finite(motion.radius) || !finite(motion.translation.x) || !finite(motion.translation.y) ||
      !(fps > 0.0) || !finite(fps)) {
    fail("synthetic video: motion parameters and fps must be finite, scale and fps > 0");
  }
  const Texture background(hash64(seed));
  const Texture disc(hash64(seed + 1));
  VideoClip clip;
  clip.size = size;
  clip.fps = fps;
  for (int k = 0; k < frames; ++k) {
    Image frame(size.x, size.y, 4, PixelType::U8);
    std::uint8_t* out = frame.values<std::uint8_t>().data();
    // Frame k shows the background moved by k·t, and inside the disc the second texture under S^k.
    const glm::dmat2 undo = rotation(-k * motion.rotationRad) / std::pow(motion.scale, k);
    parallelFor(
        static_cast<std::size_t>(size.y),
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t y = begin; y < end; ++y) {
            for (int x = 0; x < size.x; ++x) {
              const Vec2 p(x + 0.5, static_cast<double>(y) + 0.5);
              const bool inDisc = motion.radius > 0.0 && glm::length(p - motion.centre) < motion.radius;
              const glm::dvec3 c = inDisc ? disc.at(motion.centre + undo * (p - motion.centre))
                                          : background.at(p - static_cast<double>(k) * motion.translation);
              std::uint8_t* px =
                  out + (y * static_cast<std::size_t>(size.x) + static_cast<std::size_t>(x)) * 4;
              for (int ch = 0; ch < 3; ++ch) {
                px[ch] = static_cast<std::uint8_t>(std::lround(c[ch] * 255.0));
              }
              px[3] = 255;
            }
          }
        },
        8);
    clip.frames.push_back(std::move(frame));
    clip.timesS.push_back(k / fps);
  }
  return clip;
}

VideoFlow videoFlow(const std::filesystem::path& video, int a, int b, FlowMethod method) {
  const int needed = std::max(a, b) + 1;
  VideoFlow flow;
  {
    Progress progress("reading video", static_cast<std::size_t>(needed));
    flow.clip = loadVideo(video, needed, &progress);
  }
  const std::size_t frames = flow.clip.frames.size();
  if (static_cast<int>(frames) < needed) {
    fail("--frames: {} has {} frame{} (0..{}), no frame {}", video.string(), frames, frames == 1 ? "" : "s",
         frames - 1, needed - 1);
  }
  const Image& fa = flow.clip.frames[static_cast<std::size_t>(a)];
  const Image& fb = flow.clip.frames[static_cast<std::size_t>(b)];
  flow.forward = computeFlow(fa, fb, method);
  flow.backward = computeFlow(fb, fa, method);
  return flow;
}

std::string describeVideoFlow(const std::string& video, const VideoFlow& flow, int a, int b,
                              FlowMethod method) {
  const VideoClip& clip = flow.clip;
  return fmt::format("{}: {}x{}, {} frame{} read{}, {:g} fps; flow {} -> {} ({:.3f} s apart), {}\n"
                     "  flow: mean {:.3f} px, max {:.3f} px; {:.1f} % of texels consistent within 1 px\n",
                     video, clip.size.x, clip.size.y, clip.frames.size(), clip.frames.size() == 1 ? "" : "s",
                     clip.truncated ? " (more follow)" : "", clip.fps, a, b,
                     clip.timesS[static_cast<std::size_t>(b)] - clip.timesS[static_cast<std::size_t>(a)],
                     flowMethodName(method), flow.forward.meanMagnitude(), flow.forward.maxMagnitude(),
                     100.0 * consistentFraction(flow.forward, flow.backward, 1.0));
}

} // namespace sylva::folding
