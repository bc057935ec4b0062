// Blade extraction from one depth frame (paper §4.1–4.3), on OpenCV's imgproc for the image operations (range
// mask, morphology, contour tracing, Canny, distance transform) and plain C++ for the signal processing along
// the contour (smoothing, prominence, symmetric matching), which the paper describes and OpenCV does not
// have.
#include <sylva/capture/Extract.hpp>

#include <sylva/core/Error.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <array>
#include <deque>
#include <limits>
#include <numeric>
#include <optional>

namespace sylva::capture {
namespace {

constexpr int kMatchSamples = 256;
/** Offsets between matched contour points below this many pixels are contour noise, not asymmetry. */
constexpr float kOffsetNoisePx = 3.0f;

void validate(const ExtractOptions& o) {
  auto finite = [](double v) { return std::isfinite(v); };
  if (!finite(o.nearMetres) || !finite(o.farMetres) || o.nearMetres < 0.0f || o.farMetres < 0.0f ||
      (o.nearMetres > 0.0f && o.farMetres > 0.0f && o.nearMetres >= o.farMetres)) {
    fail("--near/--far: need 0 ≤ near < far metres (0 for automatic), got {} and {}", o.nearMetres,
         o.farMetres);
  }
  if (o.roi[0] < 0 || o.roi[1] < 0 || o.roi[2] < 0 || o.roi[3] < 0) {
    fail("--roi: coordinates must be ≥ 0");
  }
  if (!finite(o.cannyLowMetres) || !finite(o.cannyHighMetres) || o.cannyLowMetres <= 0.0 ||
      o.cannyHighMetres < o.cannyLowMetres) {
    fail("--canny: need 0 < low ≤ high metres");
  }
  if (o.cleanRadiusPx < 0 || o.cleanRadiusPx > 32) {
    fail("--clean: radius {} outside 0..32 pixels", o.cleanRadiusPx);
  }
  if (o.fillHolesPx < 0 || o.minClusterAreaPx < 1) {
    fail("--fill-holes / --min-area: must be ≥ 0 and ≥ 1 pixels");
  }
  if (!finite(o.smoothSigmaPx) || o.smoothSigmaPx < 0.0 || o.smoothSigmaPx > 100.0) {
    fail("--smooth: sigma {} outside 0..100 pixels", o.smoothSigmaPx);
  }
  if (!finite(o.prominence) || o.prominence <= 0.0 || o.prominence >= 1.0) {
    fail("--prominence: {} outside (0, 1)", o.prominence);
  }
  if (!finite(o.notchProminence) || o.notchProminence < 0.0 || o.notchProminence >= 1.0) {
    fail("--notch-prominence: {} outside [0, 1)", o.notchProminence);
  }
  if (!finite(o.notchMinPx) || o.notchMinPx < 0.0 || o.notchMinPx > 1000.0) {
    fail("--notch-min: {} px outside 0..1000", o.notchMinPx);
  }
  if (!finite(o.notchSigmaPx) || o.notchSigmaPx < 0.0 || o.notchSigmaPx > 100.0) {
    fail("--notch-sigma: sigma {} outside 0..100 pixels", o.notchSigmaPx);
  }
  if (!finite(o.pointedTipFraction) || o.pointedTipFraction <= 0.0 || o.pointedTipFraction > 1.0) {
    fail("--pointed-tip: {} outside (0, 1]", o.pointedTipFraction);
  }
  if (!finite(o.depthSplitOuterShare) || o.depthSplitOuterShare < 0.0 || o.depthSplitOuterShare >= 1.0) {
    fail("--depth-split-outer: {} outside [0, 1)", o.depthSplitOuterShare);
  }
  if (!finite(o.tipSurfacesOuterShare) || o.tipSurfacesOuterShare < 0.0 || o.tipSurfacesOuterShare >= 1.0) {
    fail("--tip-surfaces: {} outside [0, 1)", o.tipSurfacesOuterShare);
  }
  if (!finite(o.minBladeLengthPx) || o.minBladeLengthPx < 0.0 || !finite(o.minElongation) ||
      o.minElongation < 0.0) {
    fail("--min-length / --min-elongation: must be finite and ≥ 0");
  }
  if (o.knots < 4 || o.knots > 4096) {
    fail("--knots: {} outside 4..4096", o.knots);
  }
  if (!finite(o.skeletonSmoothKnots) || o.skeletonSmoothKnots < 0.0 || o.skeletonSmoothKnots > 64.0) {
    fail("--skeleton-smooth: {} outside 0..64", o.skeletonSmoothKnots);
  }
  if (!finite(o.widthSmoothKnots) || o.widthSmoothKnots < 0.0 || o.widthSmoothKnots > 64.0) {
    fail("--width-smooth: {} outside 0..64", o.widthSmoothKnots);
  }
  if (!finite(o.symmetryRatio) || o.symmetryRatio < 1.0) {
    fail("--symmetry: ratio {} must be ≥ 1", o.symmetryRatio);
  }
  if (!finite(o.maxObliqueness) || o.maxObliqueness < 0.0) {
    fail("--max-oblique: {} must be ≥ 0", o.maxObliqueness);
  }
  if (o.centre == CentreMode::Manual && (!std::isfinite(o.centrePx.x) || !std::isfinite(o.centrePx.y))) {
    fail("--centre: not a finite pixel position");
  }
}

/** Otsu's threshold over valid depths (256 bins between min and max); returns the split depth. */
float otsuSplit(const std::vector<float>& values, float lo, float hi) {
  constexpr int kBins = 256;
  std::array<double, kBins> hist{};
  const float scale = (kBins - 1) / std::max(hi - lo, 1e-6f);
  for (float v : values) {
    hist[static_cast<std::size_t>(std::clamp(static_cast<int>((v - lo) * scale), 0, kBins - 1))] += 1.0;
  }
  const double total = static_cast<double>(values.size());
  double sumAll = 0.0;
  for (int i = 0; i < kBins; ++i) {
    sumAll += i * hist[i];
  }
  double wB = 0.0;
  double sumB = 0.0;
  double best = -1.0;
  int split = kBins / 2;
  for (int i = 0; i < kBins - 1; ++i) {
    wB += hist[i];
    if (wB == 0.0) {
      continue;
    }
    const double wF = total - wB;
    if (wF == 0.0) {
      break;
    }
    sumB += i * hist[i];
    const double mB = sumB / wB;
    const double mF = (sumAll - sumB) / wF;
    const double between = wB * wF * (mB - mF) * (mB - mF);
    if (between > best) {
      best = between;
      split = i;
    }
  }
  return lo + (static_cast<float>(split) + 1.0f) / scale;
}

/** Circular Gaussian smoothing of a closed signal (sigma in samples). */
std::vector<float> smoothCircular(const std::vector<float>& s, double sigma) {
  const int n = static_cast<int>(s.size());
  if (sigma <= 0.0 || n < 3) {
    return s;
  }
  const int radius = std::min(n / 2, static_cast<int>(std::ceil(3.0 * sigma)));
  std::vector<double> kernel(2 * radius + 1);
  double sum = 0.0;
  for (int k = -radius; k <= radius; ++k) {
    kernel[k + radius] = std::exp(-0.5 * k * k / (sigma * sigma));
    sum += kernel[k + radius];
  }
  std::vector<float> out(s.size());
  for (int i = 0; i < n; ++i) {
    double acc = 0.0;
    for (int k = -radius; k <= radius; ++k) {
      acc += kernel[k + radius] * s[((i + k) % n + n) % n];
    }
    out[i] = static_cast<float>(acc / sum);
  }
  return out;
}

/** Open-ended Gaussian smoothing of a polyline's values; the first and last values stay fixed. */
template <typename T> std::vector<T> smoothOpen(const std::vector<T>& s, double sigma, bool pinEnds) {
  const int n = static_cast<int>(s.size());
  if (sigma <= 0.0 || n < 3) {
    return s;
  }
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  std::vector<T> out(s.size());
  for (int i = 0; i < n; ++i) {
    T acc{};
    double sum = 0.0;
    for (int k = -radius; k <= radius; ++k) {
      const int j = std::clamp(i + k, 0, n - 1);
      const double w = std::exp(-0.5 * k * k / (sigma * sigma));
      acc += s[j] * static_cast<float>(w);
      sum += w;
    }
    out[i] = acc / static_cast<float>(sum);
  }
  if (pinEnds) {
    out.front() = s.front();
    out.back() = s.back();
  }
  return out;
}

/**
 * Junctions: local minima of the circular signal whose topographic prominence (the lower of the highest
 * points reached on each side before the signal drops below the minimum again) is at least `minProminence`.
 */
std::vector<int> prominentMinima(const std::vector<float>& s, float minProminence,
                                 std::vector<float>& prominence) {
  const int n = static_cast<int>(s.size());
  std::vector<int> out;
  prominence.clear();
  if (n < 3) {
    return out;
  }
  for (int i = 0; i < n; ++i) {
    const float v = s[i];
    const float prev = s[(i - 1 + n) % n];
    const float next = s[(i + 1) % n];
    // A plateau counts once, at its first sample.
    if (!(v < prev && v <= next)) {
      continue;
    }
    float leftPeak = v;
    float rightPeak = v;
    bool leftBlocked = false;
    bool rightBlocked = false;
    for (int k = 1; k < n; ++k) {
      const float u = s[(i - k + n) % n];
      if (u < v) {
        leftBlocked = true;
        break;
      }
      leftPeak = std::max(leftPeak, u);
    }
    for (int k = 1; k < n; ++k) {
      const float u = s[(i + k) % n];
      if (u < v) {
        rightBlocked = true;
        break;
      }
      rightPeak = std::max(rightPeak, u);
    }
    // The global minimum is never blocked: its prominence is the signal's range.
    float p;
    if (!leftBlocked && !rightBlocked) {
      p = *std::max_element(s.begin(), s.end()) - v;
    } else {
      p = std::min(leftPeak, rightPeak) - v;
    }
    if (p >= minProminence) {
      out.push_back(i);
      prominence.push_back(p);
    }
  }
  return out;
}

float polylineLength(const std::vector<glm::vec2>& line) {
  float len = 0.0f;
  for (std::size_t i = 1; i < line.size(); ++i) {
    len += glm::length(line[i] - line[i - 1]);
  }
  return len;
}

/** Resamples a polyline (and per-point values) to `count` points evenly spaced by arc length. */
std::vector<glm::vec2> resample(const std::vector<glm::vec2>& line, int count,
                                const std::vector<float>* values = nullptr,
                                std::vector<float>* valuesOut = nullptr) {
  std::vector<glm::vec2> out(static_cast<std::size_t>(count));
  if (valuesOut) {
    valuesOut->assign(static_cast<std::size_t>(count), 0.0f);
  }
  if (line.empty()) {
    return out;
  }
  std::vector<float> arc(line.size(), 0.0f);
  for (std::size_t i = 1; i < line.size(); ++i) {
    arc[i] = arc[i - 1] + glm::length(line[i] - line[i - 1]);
  }
  const float total = arc.back();
  std::size_t j = 0;
  for (int k = 0; k < count; ++k) {
    const float target = count == 1 ? 0.0f : total * static_cast<float>(k) / static_cast<float>(count - 1);
    while (j + 1 < line.size() - 1 && arc[j + 1] < target) {
      ++j;
    }
    if (line.size() == 1) {
      out[k] = line[0];
      if (valuesOut) {
        (*valuesOut)[k] = (*values)[0];
      }
      continue;
    }
    const float seg = arc[j + 1] - arc[j];
    const float t = seg > 0.0f ? std::clamp((target - arc[j]) / seg, 0.0f, 1.0f) : 0.0f;
    out[k] = line[j] + t * (line[j + 1] - line[j]);
    if (valuesOut) {
      (*valuesOut)[k] = (*values)[j] + t * ((*values)[j + 1] - (*values)[j]);
    }
  }
  return out;
}

bool insideMask(const cv::Mat& mask, const glm::vec2& p) {
  const int x = static_cast<int>(std::lround(p.x));
  const int y = static_cast<int>(std::lround(p.y));
  return x >= 0 && y >= 0 && x < mask.cols && y < mask.rows && mask.at<std::uint8_t>(y, x) != 0;
}

/** Zhang–Suen thinning of a binary image (0/1), in place. */
void thin(cv::Mat& img) {
  cv::Mat marker = cv::Mat::zeros(img.size(), CV_8U);
  bool changed = true;
  while (changed) {
    changed = false;
    for (int pass = 0; pass < 2; ++pass) {
      marker.setTo(0);
      for (int y = 1; y < img.rows - 1; ++y) {
        for (int x = 1; x < img.cols - 1; ++x) {
          if (img.at<std::uint8_t>(y, x) == 0) {
            continue;
          }
          const int p2 = img.at<std::uint8_t>(y - 1, x);
          const int p3 = img.at<std::uint8_t>(y - 1, x + 1);
          const int p4 = img.at<std::uint8_t>(y, x + 1);
          const int p5 = img.at<std::uint8_t>(y + 1, x + 1);
          const int p6 = img.at<std::uint8_t>(y + 1, x);
          const int p7 = img.at<std::uint8_t>(y + 1, x - 1);
          const int p8 = img.at<std::uint8_t>(y, x - 1);
          const int p9 = img.at<std::uint8_t>(y - 1, x - 1);
          const int b = p2 + p3 + p4 + p5 + p6 + p7 + p8 + p9;
          const int a = (p2 == 0 && p3 == 1) + (p3 == 0 && p4 == 1) + (p4 == 0 && p5 == 1) +
                        (p5 == 0 && p6 == 1) + (p6 == 0 && p7 == 1) + (p7 == 0 && p8 == 1) +
                        (p8 == 0 && p9 == 1) + (p9 == 0 && p2 == 1);
          const bool c =
              pass == 0 ? (p2 * p4 * p6 == 0 && p4 * p6 * p8 == 0) : (p2 * p4 * p8 == 0 && p2 * p6 * p8 == 0);
          if (b >= 2 && b <= 6 && a == 1 && c) {
            marker.at<std::uint8_t>(y, x) = 1;
          }
        }
      }
      if (cv::countNonZero(marker) > 0) {
        changed = true;
        img &= ~marker;
      }
    }
  }
}

/**
 * The medial axis of a blade region from the pixel nearest `base` to the pixel nearest `tip`: Zhang–Suen
 * thinning, then the shortest 8-connected path on the skeleton between the two. Widths are twice the distance
 * to the region's border. Returns false when the skeleton does not connect them.
 */
bool medialAxis(const cv::Mat& frameRegion, const glm::vec2& base, const glm::vec2& tip,
                std::vector<glm::vec2>& line, std::vector<float>& widths) {
  // Work in the region's bounding box grown by one background pixel (clamped to the frame): distances to the
  // border, the thinning and the path are exactly those of the whole frame, at a fraction of the cost.
  const cv::Rect box = cv::boundingRect(frameRegion);
  const cv::Rect roi = cv::Rect(box.x - 1, box.y - 1, box.width + 2, box.height + 2) &
                       cv::Rect(0, 0, frameRegion.cols, frameRegion.rows);
  if (box.empty() || roi.empty()) {
    return false;
  }
  const cv::Mat region = frameRegion(roi);
  cv::Mat skel;
  region.convertTo(skel, CV_8U, 1.0 / 255.0);
  cv::Mat dist;
  cv::distanceTransform(region, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  thin(skel);
  std::vector<cv::Point> pts;
  cv::findNonZero(skel, pts);
  if (pts.size() < 2) {
    return false;
  }
  auto nearest = [&](const glm::vec2& p) {
    std::size_t best = 0;
    float bestD = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const float d = glm::length(glm::vec2(pts[i].x + roi.x, pts[i].y + roi.y) - p);
      if (d < bestD) {
        bestD = d;
        best = i;
      }
    }
    return pts[best];
  };
  const cv::Point start = nearest(base);
  const cv::Point goal = nearest(tip);
  cv::Mat prev(skel.size(), CV_32S, cv::Scalar(-1));
  std::deque<cv::Point> queue{start};
  prev.at<int>(start) = start.y * skel.cols + start.x;
  while (!queue.empty()) {
    const cv::Point p = queue.front();
    queue.pop_front();
    if (p == goal) {
      break;
    }
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const cv::Point q(p.x + dx, p.y + dy);
        if ((dx == 0 && dy == 0) || q.x < 0 || q.y < 0 || q.x >= skel.cols || q.y >= skel.rows ||
            skel.at<std::uint8_t>(q) == 0 || prev.at<int>(q) >= 0) {
          continue;
        }
        prev.at<int>(q) = p.y * skel.cols + p.x;
        queue.push_back(q);
      }
    }
  }
  if (prev.at<int>(goal) < 0) {
    return false;
  }
  line.clear();
  widths.clear();
  for (cv::Point p = goal;;) {
    line.emplace_back(static_cast<float>(p.x + roi.x), static_cast<float>(p.y + roi.y));
    // Twice the distance from a pixel centre to the nearest outside pixel centre is the width plus one pixel.
    widths.push_back(std::max(2.0f * dist.at<float>(p) - 1.0f, 0.0f));
    const int code = prev.at<int>(p);
    const cv::Point q(code % skel.cols, code / skel.cols);
    if (q == p) {
      break;
    }
    p = q;
  }
  std::reverse(line.begin(), line.end());
  std::reverse(widths.begin(), widths.end());
  // Close the ends: from the base point and out to the tip.
  line.insert(line.begin(), base);
  widths.insert(widths.begin(), widths.front());
  line.push_back(tip);
  widths.push_back(0.0f);
  return line.size() >= 2;
}

struct Context {
  const DepthFrame& frame;
  const ExtractOptions& options;
  ExtractResult& result;
  cv::Mat depth;       ///< CV_32F metres, possibly colour-refined
  cv::Mat mask;        ///< CV_8U 0/255
  cv::Mat clusterDist; ///< CV_32F distance to the current cluster's border, pixels
  /** CV_8U: the pixels whose depth and colour belong to the current cluster (its own depth layer). */
  cv::Mat ownMask;
  /** The depth layer being partitioned (Cluster::layer, layerCount, layerDepthMetres). */
  int layer = -1;
  int layerCount = 1;
  float layerDepthMetres = 0.0f;
};

/**
 * Colour-guided refinement: pixels in a band around the depth mask's edge (and dropouts inside it) are
 * reclassified by colour, comparing each with the mean colours of sure foreground and sure background in a
 * local window (a joint-bilateral decision), so the silhouette follows the colour edge where depth is noisy
 * or missing; reclassified foreground pixels take the median depth of their sure neighbours.
 */
void refineWithColour(Context& c) {
  const Image& colour = c.frame.colour;
  const int w = c.mask.cols;
  const int h = c.mask.rows;
  cv::Mat rgb(h, w, CV_32FC3);
  if (colour.type() == PixelType::U8 && colour.channels() == 3) {
    // RGB8 (every frame source): the values Image::get gives, without a call per channel.
    const std::span<const std::uint8_t> src = colour.values<std::uint8_t>();
    float* dst = rgb.ptr<float>();
    for (std::size_t i = 0; i < src.size(); ++i) {
      dst[i] = static_cast<float>(src[i]) / 255.0f;
    }
  } else {
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        rgb.at<cv::Vec3f>(y, x) = {colour.get(x, y, 0), colour.get(x, y, 1), colour.get(x, y, 2)};
      }
    }
  }
  const int band = 2;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * band + 1, 2 * band + 1});
  cv::Mat sureFg;
  cv::Mat sureBg;
  cv::erode(c.mask, sureFg, kernel);
  cv::dilate(c.mask, sureBg, kernel);
  sureBg = 255 - sureBg;
  // Window sums of colour over sure foreground and sure background (box filters of masked colour).
  const int win = 2 * band + 3;
  cv::Mat fgF;
  cv::Mat bgF;
  sureFg.convertTo(fgF, CV_32F, 1.0 / 255.0);
  sureBg.convertTo(bgF, CV_32F, 1.0 / 255.0);
  cv::Mat fgCol;
  cv::Mat bgCol;
  cv::Mat fgCount;
  cv::Mat bgCount;
  cv::Mat fg3;
  cv::Mat bg3;
  cv::merge(std::vector<cv::Mat>{fgF, fgF, fgF}, fg3);
  cv::merge(std::vector<cv::Mat>{bgF, bgF, bgF}, bg3);
  cv::boxFilter(rgb.mul(fg3), fgCol, -1, {win, win}, {-1, -1}, false);
  cv::boxFilter(rgb.mul(bg3), bgCol, -1, {win, win}, {-1, -1}, false);
  cv::boxFilter(fgF, fgCount, -1, {win, win}, {-1, -1}, false);
  cv::boxFilter(bgF, bgCount, -1, {win, win}, {-1, -1}, false);
  cv::Mat refined = c.mask.clone();
  cv::Mat depth = c.depth.clone();
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (sureFg.at<std::uint8_t>(y, x) || sureBg.at<std::uint8_t>(y, x)) {
        continue;
      }
      const float nf = fgCount.at<float>(y, x);
      const float nb = bgCount.at<float>(y, x);
      if (nf < 1.0f || nb < 1.0f) {
        continue;
      }
      const cv::Vec3f p = rgb.at<cv::Vec3f>(y, x);
      const cv::Vec3f mf = fgCol.at<cv::Vec3f>(y, x) / nf;
      const cv::Vec3f mb = bgCol.at<cv::Vec3f>(y, x) / nb;
      const bool fg = cv::norm(p - mf) < cv::norm(p - mb);
      refined.at<std::uint8_t>(y, x) = fg ? 255 : 0;
      if (fg && (depth.at<float>(y, x) <= 0.0f || c.mask.at<std::uint8_t>(y, x) == 0)) {
        // Median depth of sure-foreground neighbours.
        std::vector<float> near;
        for (int dy = -band - 1; dy <= band + 1; ++dy) {
          for (int dx = -band - 1; dx <= band + 1; ++dx) {
            const int xx = x + dx;
            const int yy = y + dy;
            if (xx >= 0 && yy >= 0 && xx < w && yy < h && sureFg.at<std::uint8_t>(yy, xx) &&
                c.depth.at<float>(yy, xx) > 0.0f) {
              near.push_back(c.depth.at<float>(yy, xx));
            }
          }
        }
        if (!near.empty()) {
          std::nth_element(near.begin(), near.begin() + near.size() / 2, near.end());
          depth.at<float>(y, x) = near[near.size() / 2];
        }
      }
    }
  }
  c.mask = refined;
  c.depth = depth;
  c.result.colourRefined = true;
}

/** Canny on depth: Sobel gradients of depth in millimetres, hysteresis in Sobel units of the metre
 * thresholds. */
cv::Mat cannyMask(Context& c, const cv::Mat& rangeMask) {
  const ExtractOptions& o = c.options;
  cv::Mat mm(c.depth.size(), CV_16S);
  const float farFill = c.result.farMetres * 1.5f;
  for (int y = 0; y < mm.rows; ++y) {
    for (int x = 0; x < mm.cols; ++x) {
      float z = c.depth.at<float>(y, x);
      z = z > 0.0f ? z : farFill;
      mm.at<std::int16_t>(y, x) = static_cast<std::int16_t>(std::clamp(z * 1000.0f, 0.0f, 32000.0f));
    }
  }
  cv::Mat dx;
  cv::Mat dy;
  cv::Sobel(mm, dx, CV_16S, 1, 0, 3);
  cv::Sobel(mm, dy, CV_16S, 0, 1, 3);
  // A depth step of h mm between neighbours gives a 3×3 Sobel response of about 4h.
  cv::Mat edges;
  cv::Canny(dx, dy, edges, o.cannyLowMetres * 4000.0, o.cannyHighMetres * 4000.0, true);
  c.result.edges.assign(edges.datastart, edges.dataend);
  // Regions enclosed by depth edges (closed over one-pixel gaps) whose depth lies mostly in range, plus their
  // edge pixels.
  cv::Mat closedEdges;
  cv::dilate(edges, closedEdges, cv::Mat());
  cv::Mat regions = 255 - closedEdges;
  cv::Mat labels;
  const int count = cv::connectedComponents(regions, labels, 4, CV_32S);
  std::vector<int> inRange(count, 0);
  std::vector<int> total(count, 0);
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      const int l = labels.at<int>(y, x);
      if (l > 0) {
        ++total[l];
        inRange[l] += rangeMask.at<std::uint8_t>(y, x) ? 1 : 0;
      }
    }
  }
  cv::Mat out = cv::Mat::zeros(c.depth.size(), CV_8U);
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      const int l = labels.at<int>(y, x);
      if (l > 0 && 2 * inRange[l] > total[l]) {
        out.at<std::uint8_t>(y, x) = 255;
      }
    }
  }
  // The edge ring on the silhouette belongs to the region it encloses where depth is in range; edges inside
  // the range (one leaf in front of another) stay cut, which is what separates overlapping blades.
  cv::Mat grown;
  cv::dilate(out, grown, cv::Mat(), {-1, -1}, 2);
  cv::Mat silhouette;
  cv::dilate(255 - rangeMask, silhouette, cv::Mat(), {-1, -1}, 3);
  out |= grown & closedEdges & rangeMask & silhouette;
  return out;
}

/** Fills holes smaller than maxArea pixels. */
void fillHoles(cv::Mat& mask, int maxArea) {
  if (maxArea <= 0) {
    return;
  }
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(mask.clone(), contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  for (std::size_t i = 0; i < contours.size(); ++i) {
    if (hierarchy[i][3] >= 0 && cv::contourArea(contours[i]) <= maxArea) {
      cv::drawContours(mask, contours, static_cast<int>(i), cv::Scalar(255), cv::FILLED);
    }
  }
}

void buildMask(Context& c) {
  const DepthFrame& f = c.frame;
  const ExtractOptions& o = c.options;
  c.depth = cv::Mat(f.height, f.width, CV_32F, const_cast<float*>(f.depth.data())).clone();
  const bool wholeFrame = o.roi == std::array<int, 4>{0, 0, 0, 0};
  const int x0 = wholeFrame ? 0 : std::min(o.roi[0], f.width);
  const int y0 = wholeFrame ? 0 : std::min(o.roi[1], f.height);
  const int x1 = wholeFrame ? f.width : std::min(o.roi[2], f.width);
  const int y1 = wholeFrame ? f.height : std::min(o.roi[3], f.height);
  if (wholeFrame && (f.width < 2 || f.height < 2)) {
    fail("{}: the {}x{} frame is too small to hold blades (at least 2x2 pixels)", f.label(), f.width,
         f.height);
  }
  if (x1 - x0 < 2 || y1 - y0 < 2) {
    fail("--roi: region {},{},{},{} is empty within the {}x{} frame", o.roi[0], o.roi[1], o.roi[2], o.roi[3],
         f.width, f.height);
  }
  std::vector<float> valid;
  valid.reserve(static_cast<std::size_t>(x1 - x0) * (y1 - y0));
  float lo = std::numeric_limits<float>::max();
  float hi = 0.0f;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const float z = c.depth.at<float>(y, x);
      if (z > 0.0f && std::isfinite(z)) {
        valid.push_back(z);
        lo = std::min(lo, z);
        hi = std::max(hi, z);
      }
    }
  }
  c.mask = cv::Mat::zeros(f.height, f.width, CV_8U);
  if (valid.empty()) {
    c.result.warnings.push_back(f.label() + ": no valid depth pixel in the region of interest");
    return;
  }
  float nearM = o.nearMetres > 0.0f ? o.nearMetres : lo;
  float farM = o.farMetres;
  if (farM <= 0.0f) {
    farM = otsuSplit(valid, lo, hi);
    // One mode only (no background in view): everything valid is foreground.
    double sumN = 0.0;
    double sumF = 0.0;
    std::size_t nN = 0;
    std::size_t nF = 0;
    for (float z : valid) {
      if (z <= farM) {
        sumN += z;
        ++nN;
      } else {
        sumF += z;
        ++nF;
      }
    }
    if (nN == 0 || nF == 0 || (sumF / nF - sumN / nN) < 0.15 * (sumN / nN)) {
      farM = hi;
    }
  }
  c.result.nearMetres = nearM;
  c.result.farMetres = farM;
  cv::Mat range = cv::Mat::zeros(f.height, f.width, CV_8U);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const float z = c.depth.at<float>(y, x);
      range.at<std::uint8_t>(y, x) = (z >= nearM && z <= farM) ? 255 : 0;
    }
  }
  c.mask = o.contour == ContourMethod::Canny ? cannyMask(c, range) : range;
  if (o.cleanRadiusPx > 0) {
    const int r = o.cleanRadiusPx;
    const cv::Mat k = cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * r + 1, 2 * r + 1});
    cv::morphologyEx(c.mask, c.mask, cv::MORPH_CLOSE, k);
  }
  fillHoles(c.mask, o.fillHolesPx);
  if (o.colourRefine && !f.colour.empty() && f.colour.width() == f.width && f.colour.height() == f.height &&
      f.colour.channels() >= 3) {
    refineWithColour(c);
    fillHoles(c.mask, o.fillHolesPx);
  }
  // Nothing outside the region of interest.
  if (!wholeFrame) {
    cv::Mat roiMask = cv::Mat::zeros(c.mask.size(), CV_8U);
    roiMask(cv::Rect(x0, y0, x1 - x0, y1 - y0)).setTo(255);
    c.mask &= roiMask;
  }
  c.result.mask.assign(c.mask.datastart, c.mask.dataend);
  if (cv::countNonZero(c.mask) == 0) {
    c.result.warnings.push_back(fmt::format("{}: empty mask: no pixel in the depth range [{:.3f}, {:.3f}] m",
                                            f.label(), nearM, farM));
  }
}

struct CentreCandidate {
  glm::vec2 px;
  CentreMode mode;
};

/**
 * The centres to try, in order of preference: the requested one, or for Auto the core (deepest point), the
 * base (lowest point) and the centroid when it lies inside the blob. Empty (with a warning) when none is
 * usable.
 */
std::vector<CentreCandidate> centreCandidates(Context& c, const cv::Mat& clusterMask,
                                              const std::vector<cv::Point>& contour) {
  const cv::Mat& dist = c.clusterDist;
  double maxVal = 0.0;
  cv::Point maxLoc;
  cv::minMaxLoc(dist, nullptr, &maxVal, nullptr, &maxLoc);
  const cv::Moments m = cv::moments(clusterMask, true);
  const glm::vec2 centroid = m.m00 > 0 ? glm::vec2(m.m10 / m.m00, m.m01 / m.m00) : glm::vec2(0.0f);
  // The base: the middle of the lowest contour points.
  int lowest = 0;
  for (const cv::Point& p : contour) {
    lowest = std::max(lowest, p.y);
  }
  glm::vec2 base(0.0f);
  int nBase = 0;
  for (const cv::Point& p : contour) {
    if (p.y >= lowest - 1) {
      base += glm::vec2(p.x, p.y);
      ++nBase;
    }
  }
  base /= static_cast<float>(std::max(nBase, 1));
  const glm::vec2 core(static_cast<float>(maxLoc.x), static_cast<float>(maxLoc.y));
  const std::string label = c.frame.label();
  std::vector<CentreCandidate> out;
  switch (c.options.centre) {
  case CentreMode::Core:
    out.push_back({core, CentreMode::Core});
    break;
  case CentreMode::Centroid:
    out.push_back({centroid, CentreMode::Centroid});
    break;
  case CentreMode::Base:
    out.push_back({base, CentreMode::Base});
    break;
  case CentreMode::Manual:
    out.push_back({c.options.centrePx, CentreMode::Manual});
    break;
  case CentreMode::Auto:
    if (maxVal >= 1.5) {
      out.push_back({core, CentreMode::Core});
    }
    out.push_back({base, CentreMode::Base});
    if (insideMask(clusterMask, centroid)) {
      out.push_back({centroid, CentreMode::Centroid});
    }
    break;
  }
  if ((c.options.centre == CentreMode::Centroid || c.options.centre == CentreMode::Manual) &&
      !insideMask(clusterMask, out.front().px)) {
    // A centre outside the blob still defines a distance signal, but junctions then mean little.
    c.result.warnings.push_back(fmt::format("{}: the cluster centre ({:.0f}, {:.0f}) lies outside the blob",
                                            label, out.front().px.x, out.front().px.y));
  }
  return out;
}

/** Whether z is a valid depth inside the blades' range (pixels the colour refinement added may still carry
 * the background's). */
bool inBladeRange(const Context& c, float z) {
  return z > 0.0f && z >= c.result.nearMetres && z <= c.result.farMetres;
}

/** Median valid depth around (u, v) within the mask, radius r; 0 when none. */
float depthAround(const Context& c, const glm::vec2& p, int r) {
  std::vector<float> values;
  const int cx = static_cast<int>(std::lround(p.x));
  const int cy = static_cast<int>(std::lround(p.y));
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      const int x = cx + dx;
      const int y = cy + dy;
      if (x < 0 || y < 0 || x >= c.depth.cols || y >= c.depth.rows || !c.ownMask.at<std::uint8_t>(y, x)) {
        continue;
      }
      // Only depths in the blades' range: pixels the colour refinement added may still carry the
      // background's.
      const float z = c.depth.at<float>(y, x);
      if (inBladeRange(c, z)) {
        values.push_back(z);
      }
    }
  }
  if (values.empty()) {
    return 0.0f;
  }
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

glm::vec3 srgbToLinear(const glm::vec3& c) {
  glm::vec3 out;
  for (int i = 0; i < 3; ++i) {
    out[i] = c[i] <= 0.04045f ? c[i] / 12.92f : std::pow((c[i] + 0.055f) / 1.055f, 2.4f);
  }
  return out;
}

/** Converts a pixel skeleton to metres: depth per knot (median around it, interpolated and smoothed). */
void toMetres(const Context& c, CapturedBlade& blade) {
  const std::size_t n = blade.skeletonPx.size();
  std::vector<float> z(n, 0.0f);
  for (std::size_t k = 0; k < n; ++k) {
    const int r = std::clamp(static_cast<int>(blade.widthsPx[k] * 0.25f), 1, 4);
    z[k] = depthAround(c, blade.skeletonPx[k], r);
  }
  // Fill knots without depth from their nearest knots with depth.
  int last = -1;
  for (std::size_t k = 0; k < n; ++k) {
    if (z[k] > 0.0f) {
      if (last < 0) {
        std::fill(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(k), z[k]);
      } else {
        for (std::size_t j = static_cast<std::size_t>(last) + 1; j < k; ++j) {
          const float t = static_cast<float>(j - last) / static_cast<float>(k - last);
          z[j] = z[last] + t * (z[k] - z[last]);
        }
      }
      last = static_cast<int>(k);
    }
  }
  if (last < 0) {
    z.assign(n, c.result.nearMetres > 0.0f ? c.result.nearMetres : 1.0f);
  } else {
    std::fill(z.begin() + last + 1, z.end(), z[static_cast<std::size_t>(last)]);
  }
  z = smoothOpen(z, 4.0 * static_cast<double>(n) / 128.0, false);
  const CameraIntrinsics& k = c.frame.intrinsics;
  blade.knots.resize(n);
  blade.widths.resize(n);
  blade.sides.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec2 p = blade.skeletonPx[i];
    blade.knots[i] = glm::vec3(k.unproject(p.x, p.y, z[i]));
    blade.widths[i] = static_cast<float>(blade.widthsPx[i] * z[i] / k.fx);
    const glm::vec2 t = blade.skeletonPx[std::min(i + 1, n - 1)] - blade.skeletonPx[i > 0 ? i - 1 : 0];
    const glm::vec2 side2 =
        glm::length(t) > 0.0f ? glm::normalize(glm::vec2(-t.y, t.x)) : glm::vec2(1.0f, 0.0f);
    const glm::vec3 a(k.unproject(p.x, p.y, z[i]));
    const glm::vec3 b(k.unproject(p.x + side2.x, p.y + side2.y, z[i]));
    blade.sides[i] = glm::normalize(b - a);
  }
  blade.lengthMetres = 0.0f;
  for (std::size_t i = 1; i < n; ++i) {
    blade.lengthMetres += glm::length(blade.knots[i] - blade.knots[i - 1]);
  }
  if (!c.frame.colour.empty() && c.frame.colour.width() == c.frame.width &&
      c.frame.colour.height() == c.frame.height && c.frame.colour.channels() >= 3) {
    glm::vec3 sum(0.0f);
    int count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const int x = static_cast<int>(std::lround(blade.skeletonPx[i].x));
      const int y = static_cast<int>(std::lround(blade.skeletonPx[i].y));
      if (x >= 0 && y >= 0 && x < c.frame.width && y < c.frame.height && c.ownMask.at<std::uint8_t>(y, x)) {
        sum += srgbToLinear(
            {c.frame.colour.get(x, y, 0), c.frame.colour.get(x, y, 1), c.frame.colour.get(x, y, 2)});
        ++count;
      }
    }
    if (count > 0) {
      blade.hasColour = true;
      blade.colour = sum / static_cast<float>(count);
    }
  }
}

/**
 * Widths across a blade's axis (`line`, kMatchSamples points, pixels) in `region`: the distance between the
 * two places where a scan along the normal leaves the region (nearest-pixel classification puts them on the
 * edges, unbiased). The tip's width is 0.
 */
void widthsAcross(const cv::Mat& region, const std::vector<glm::vec2>& line, std::vector<float>& widths) {
  const int count = static_cast<int>(line.size());
  widths.resize(line.size());
  for (int k = 0; k < count; ++k) {
    const glm::vec2 t = line[std::min(k + 2, count - 1)] - line[std::max(k - 2, 0)];
    if (glm::length(t) <= 0.0f) {
      continue;
    }
    const glm::vec2 normal = glm::normalize(glm::vec2(-t.y, t.x));
    float across = 0.0f;
    for (const float sign : {-1.0f, 1.0f}) {
      float d = 0.0f;
      while (d < 200.0f && insideMask(region, line[k] + normal * (sign * (d + 0.25f)))) {
        d += 0.25f;
      }
      across += d + 0.125f;
    }
    widths[k] = across;
  }
  widths.back() = 0.0f;
}

/**
 * The common end of building a blade from its axis `line` (root end first, pixels) and `widths`: the
 * elongation test, smoothing, the extension to the cluster's centre, the knots, the border test and metres.
 * `blade` carries its outline and tip. Appends the blade to `out`, or returns false with `reason`.
 */
bool finishBlade(Context& c, const Cluster& cluster, const cv::Mat& clusterMask, std::vector<glm::vec2> line,
                 std::vector<float> widths, float maxWidth, CapturedBlade blade,
                 std::vector<CapturedBlade>& out, std::string& reason) {
  const ExtractOptions& o = c.options;
  // A blade reaches from the centre to its tip: a leaf mostly hidden behind its neighbours shows only a
  // short, wide end beyond its junctions, yet is as long as the others.
  const float lengthPx =
      polylineLength(line) + (o.extendToCentre ? glm::length(line.front() - cluster.centre) : 0.0f);
  // Elongation is judged beyond the blade's lowest tenth: where it meets its neighbours at its junctions (or,
  // split in depth, where the merged lower part is closed across its base) a blade's base is wider than the
  // blade.
  float bladeWidth = maxWidth;
  if (widths.size() >= 10) {
    bladeWidth =
        *std::max_element(widths.begin() + static_cast<std::ptrdiff_t>(widths.size() / 10), widths.end());
  }
  if (lengthPx < o.minElongation * std::max(bladeWidth, 1.0f)) {
    reason = fmt::format("not elongated ({:.0f} px long, {:.0f} px wide)", lengthPx, bladeWidth);
    return false;
  }
  // Smooth, extend to the centre, resample to the knot count.
  const double sigma = o.skeletonSmoothKnots * kMatchSamples / 128.0;
  line = smoothOpen(line, sigma, true);
  widths = smoothOpen(widths, sigma, false);
  widths.back() = 0.0f;
  float extension = 0.0f;
  if (o.extendToCentre) {
    const glm::vec2 base = line.front();
    const float d = glm::length(base - cluster.centre);
    if (d > 2.0f && insideMask(clusterMask, 0.5f * (base + cluster.centre))) {
      const int steps = std::max(2, static_cast<int>(d / 2.0f));
      // Where blades overlap the width cannot be measured; continue the trend of the blade's first captured
      // fifth (leaves that widen from a stalk narrow towards the root), within a quarter to all of its base
      // width.
      const std::size_t probe = std::max<std::size_t>(2, line.size() / 5);
      const float run =
          std::max(polylineLength(std::vector<glm::vec2>(line.begin(), line.begin() + probe)), 1.0f);
      const float slope = (widths[probe - 1] - widths.front()) / run;
      const float w0 = widths.front();
      std::vector<glm::vec2> ext;
      std::vector<float> extW;
      for (int s = 0; s < steps; ++s) {
        const float t = static_cast<float>(s) / static_cast<float>(steps);
        ext.push_back(cluster.centre + t * (base - cluster.centre));
        // ...and never wider than the cluster is there (a straight extension cuts the corner of a bent
        // blade).
        const glm::vec2 q = ext.back();
        const int qx = std::clamp(static_cast<int>(std::lround(q.x)), 0, c.clusterDist.cols - 1);
        const int qy = std::clamp(static_cast<int>(std::lround(q.y)), 0, c.clusterDist.rows - 1);
        const float room = std::max(2.0f * c.clusterDist.at<float>(qy, qx) - 1.0f, 1.0f);
        extW.push_back(std::min(std::clamp(w0 - slope * (1.0f - t) * d, 0.25f * w0, w0), room));
      }
      line.insert(line.begin(), ext.begin(), ext.end());
      widths.insert(widths.begin(), extW.begin(), extW.end());
      extension = d;
    }
  }
  blade.skeletonPx = resample(line, o.knots, &widths, &blade.widthsPx);
  blade.lengthPx = polylineLength(blade.skeletonPx);
  blade.extensionPx = extension;
  std::size_t onBorder = 0;
  for (const glm::vec2& p : blade.outline) {
    bool border = p.x <= 0.0f || p.y <= 0.0f || p.x >= c.frame.width - 1 || p.y >= c.frame.height - 1;
    if (c.options.roi != std::array<int, 4>{0, 0, 0, 0}) {
      border = border || p.x <= c.options.roi[0] + 1 || p.y <= c.options.roi[1] + 1 ||
               p.x >= c.options.roi[2] - 2 || p.y >= c.options.roi[3] - 2;
    }
    onBorder += border ? 1 : 0;
  }
  blade.touchesBorder = onBorder > 0;
  // A blade cut by the border crosses it once, over its width; a segment that runs along it is the cut
  // itself.
  if (onBorder * 10 > blade.outline.size() * 3) {
    reason = fmt::format("{:.0f} % of its outline is the border of the frame or region",
                         100.0 * onBorder / blade.outline.size());
    return false;
  }
  toMetres(c, blade);
  out.push_back(std::move(blade));
  return true;
}

/** A pointed tip is at most this many times as wide as high, 80 % of the way down from it. */
constexpr float kPointedTipTaper = 0.7f;

/**
 * Whether the tip at `tipOffset` of the contour segment of `len` points from `a`, standing `height` pixels
 * above its higher junction in `signal`, is pointed: where the signal has fallen 80 % of the way from the tip
 * to that junction the outline is at most kPointedTipTaper times as wide as the tip is high (and at least two
 * pixels, not a spike of single pixels). In a dense fan a blade's neighbours overlap it up to near its end,
 * so only a short, pointed tip shows beyond them; a ripple of a wide leaf's edge is blunt.
 */
bool pointedTip(const Cluster& cluster, const std::vector<float>& signal, int a, int len, int tipOffset,
                float height) {
  const int n = static_cast<int>(cluster.contour.size());
  const float level = signal[static_cast<std::size_t>((a + tipOffset) % n)] - 0.8f * height;
  int left = tipOffset;
  int right = tipOffset;
  while (left > 0 && signal[static_cast<std::size_t>((a + left) % n)] > level) {
    --left;
  }
  while (right < len && signal[static_cast<std::size_t>((a + right) % n)] > level) {
    ++right;
  }
  const float across = glm::length(cluster.contour[static_cast<std::size_t>((a + left) % n)] -
                                   cluster.contour[static_cast<std::size_t>((a + right) % n)]);
  return across >= 2.0f && across <= kPointedTipTaper * height;
}

/** Builds one blade from the contour segment [a, b] (indices, circular, a before b) around its tip. */
bool buildBlade(Context& c, const Cluster& cluster, const cv::Mat& clusterMask, int a, int b,
                int clusterIndex, std::vector<CapturedBlade>& out, std::string& reason,
                float minHeightPx = -1.0f, const std::vector<float>* heights = nullptr) {
  const ExtractOptions& o = c.options;
  // The signal the tip and its height are read from: the junctions' smoothed one, or (between notches) the
  // notches' own.
  const std::vector<float>& signal = heights != nullptr ? *heights : cluster.smoothed;
  const int n = static_cast<int>(cluster.contour.size());
  const int len = ((b - a) % n + n) % n;
  if (len < 4) {
    reason = "too few contour points";
    return false;
  }
  // Tip: the farthest point of the smoothed signal within the segment.
  int tipOffset = 0;
  float tipValue = -1.0f;
  for (int k = 0; k <= len; ++k) {
    const float v = signal[(a + k) % n];
    if (v > tipValue) {
      tipValue = v;
      tipOffset = k;
    }
  }
  const float ra = signal[a];
  const float rb = signal[b % n];
  const float level = std::max(ra, rb);
  const float height = tipValue - level;
  const float minHeight = minHeightPx >= 0.0f ? minHeightPx : static_cast<float>(o.minBladeLengthPx);
  if (height < minHeight && !(height >= static_cast<float>(o.pointedTipFraction) * minHeight &&
                              pointedTip(cluster, signal, a, len, tipOffset, height))) {
    reason = fmt::format("too short ({:.0f} px beyond its junctions)", height);
    return false;
  }
  CapturedBlade blade;
  blade.cluster = clusterIndex;
  for (int k = 0; k <= len; ++k) {
    blade.outline.push_back(cluster.contour[(a + k) % n]);
  }
  blade.tip = tipOffset;
  // Sides from their junction towards the tip, trimmed to the level of the higher junction.
  std::vector<glm::vec2> left;
  std::vector<glm::vec2> right;
  bool started = false;
  for (int k = 0; k <= tipOffset; ++k) {
    const int i = (a + k) % n;
    if (!started && signal[i] < level && k < tipOffset) {
      continue;
    }
    started = true;
    left.push_back(cluster.contour[i]);
  }
  started = false;
  for (int k = len; k >= tipOffset; --k) {
    const int i = (a + k) % n;
    if (!started && signal[i] < level && k > tipOffset) {
      continue;
    }
    started = true;
    right.push_back(cluster.contour[i]);
  }
  const float leftLen = polylineLength(left);
  const float rightLen = polylineLength(right);
  blade.sideRatio = std::max(leftLen, rightLen) / std::max(std::min(leftLen, rightLen), 1e-3f);
  // Symmetric matching: equal fractions of arc length from the junction level to the tip.
  // Arc length along a pixel staircase grows with its jaggedness, which differs between the sides: smooth
  // them first so equal fractions of arc length face each other.
  const std::vector<glm::vec2> ls = resample(smoothOpen(left, 2.0, true), kMatchSamples);
  const std::vector<glm::vec2> rs = resample(smoothOpen(right, 2.0, true), kMatchSamples);
  std::vector<glm::vec2> line(kMatchSamples);
  std::vector<float> widths(kMatchSamples);
  int outside = 0;
  for (int k = 0; k < kMatchSamples; ++k) {
    line[k] = 0.5f * (ls[k] + rs[k]);
    if (k > 2 && k < kMatchSamples - 3 && !insideMask(clusterMask, line[k])) {
      ++outside;
    }
  }
  // Width: the matched pair's separation across the skeleton (a pair matched a little obliquely must not
  // widen the blade), plus one pixel because the contour runs through boundary pixel centres, half a pixel
  // inside the edge on either side.
  const std::vector<glm::vec2> smoothLine = smoothOpen(line, 4.0, true);
  for (int k = 0; k < kMatchSamples; ++k) {
    const glm::vec2 t = smoothLine[std::min(k + 2, kMatchSamples - 1)] - smoothLine[std::max(k - 2, 0)];
    const glm::vec2 d = ls[k] - rs[k];
    const float across =
        glm::length(t) > 0.0f ? std::abs(t.x * d.y - t.y * d.x) / glm::length(t) : glm::length(d);
    widths[k] = across + 1.0f;
  }
  // The matched pair at the tip is the same point; nudge the tip width to 0 exactly.
  widths.back() = 0.0f;
  float maxWidth = *std::max_element(widths.begin(), widths.end());
  // Oblique pairs (a pair's chord far from the skeleton's normal) mean the sides do not mirror each other.
  // The offset along the skeleton is compared with the chord, above a floor of a few pixels of contour noise.
  float offsetSum = 0.0f;
  float chordSum = 0.0f;
  for (int k = 2; k < kMatchSamples - 2; ++k) {
    const glm::vec2 t = smoothLine[k + 2] - smoothLine[k - 2];
    const glm::vec2 d = ls[k] - rs[k];
    if (glm::length(t) > 0.0f) {
      offsetSum += std::abs(glm::dot(glm::normalize(t), d));
      chordSum += glm::length(d);
    }
  }
  blade.obliqueness = chordSum > 0.0f ? offsetSum / chordSum : 0.0f;
  const float meanOffset = offsetSum / static_cast<float>(kMatchSamples - 4);
  const float meanChord = chordSum / static_cast<float>(kMatchSamples - 4);
  const bool oblique =
      meanOffset > std::max(kOffsetNoisePx, static_cast<float>(o.maxObliqueness) * meanChord);
  const bool symmetric = blade.sideRatio <= o.symmetryRatio && outside <= kMatchSamples / 20 && !oblique;
  if (!symmetric) {
    // Medial axis of the blade region (outline closed across its base).
    cv::Mat region = cv::Mat::zeros(clusterMask.size(), CV_8U);
    std::vector<cv::Point> poly;
    for (const glm::vec2& p : left) {
      poly.emplace_back(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
    }
    for (auto it = right.rbegin(); it != right.rend(); ++it) {
      poly.emplace_back(static_cast<int>(std::lround(it->x)), static_cast<int>(std::lround(it->y)));
    }
    cv::fillPoly(region, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255));
    region &= clusterMask;
    std::vector<glm::vec2> axis;
    std::vector<float> axisWidths;
    const glm::vec2 basePoint = 0.5f * (left.front() + right.front());
    if (medialAxis(region, basePoint, cluster.contour[(a + tipOffset) % n], axis, axisWidths) &&
        axis.size() >= 3) {
      line = smoothOpen(resample(axis, kMatchSamples, &axisWidths, &widths), 2.0, true);
      widthsAcross(region, line, widths);
      blade.medialAxis = true;
      maxWidth = *std::max_element(widths.begin(), widths.end());
    }
  }
  return finishBlade(c, cluster, clusterMask, std::move(line), std::move(widths), maxWidth, std::move(blade),
                     out, reason);
}

/** A cluster partitioned around one centre: the cluster's signal and junctions, its blades, its warnings. */
struct Partition {
  Cluster cluster;
  std::vector<CapturedBlade> blades;
  std::vector<std::string> warnings;
  /** How well the blades explain the cluster's silhouette: IoU of their rasterisation with the cluster mask.
   */
  double coverage = 0.0;
};

/**
 * In the segment of `len` contour points from `a`: the point (offset from `a`) of the deepest dip of the
 * smoothed distance signal between its highest peak and another peak, when that dip (below the lower of the
 * two peaks) is at least `minDip` pixels; -1 when there is none. `depth` gets the dip.
 */
int deepestDip(const Cluster& cluster, int a, int len, float minDip, float& depth) {
  const int n = static_cast<int>(cluster.contour.size());
  auto at = [&](int k) { return cluster.smoothed[static_cast<std::size_t>((a + k) % n)]; };
  int best1 = -1;
  for (int k = 1; k < len; ++k) {
    if (at(k) > at(k - 1) && at(k) >= at(k + 1) && (best1 < 0 || at(k) > at(best1))) {
      best1 = k;
    }
  }
  int split = -1;
  depth = 0.0f;
  for (int k = 1; best1 >= 0 && k < len; ++k) {
    if (k == best1 || !(at(k) > at(k - 1) && at(k) >= at(k + 1))) {
      continue;
    }
    // The lowest point between this peak and the highest one.
    int lo = std::min(k, best1);
    const int hi = std::max(k, best1);
    int m = lo;
    for (; lo <= hi; ++lo) {
      m = at(lo) < at(m) ? lo : m;
    }
    const float dip = std::min(at(k), at(best1)) - at(m);
    if (dip >= minDip && dip > depth) {
      depth = dip;
      split = m;
    }
  }
  return split;
}

/** The widest point of a blade, pixels. */
float maxWidthPx(const CapturedBlade& blade) {
  return blade.widthsPx.empty() ? 0.0f : *std::max_element(blade.widthsPx.begin(), blade.widthsPx.end());
}

/** Blades wider than this many times their cluster's narrow blades (the lower quartile of its blades' widths)
 * are split where their outline allows (splitMerged). */
constexpr float kMergedWidthRatio = 1.4f;

/**
 * Second pass over a cluster's blades: one much wider than the cluster's narrow blades (kMergedWidthRatio;
 * clusters of three or more) is usually several that overlap up to near their tips, each valley between their
 * tips too shallow for the prominence test and the whole too elongated to fail as one blade. Its segment is
 * split at the deepest dip between two of its peaks down to a dip of a third of the narrow width, as long as
 * both halves make blades no wider than the whole; repeatedly, while a half is still too wide. `segments` are
 * the blades' contour segments; `splits` gets the junctions added.
 */
void splitMerged(Context& c, Cluster& cluster, const cv::Mat& clusterMask, int clusterIndex,
                 const std::vector<std::pair<int, int>>& segments, std::vector<CapturedBlade>& blades,
                 std::vector<Junction>& splits, float maxR) {
  if (blades.size() < 3) {
    return;
  }
  std::vector<float> widths;
  for (const CapturedBlade& blade : blades) {
    widths.push_back(maxWidthPx(blade));
  }
  // The reference is the cluster's narrow blades (the lower quartile of its widths), not the median: in a
  // dense fan half the blades may be merged pairs, and the median is then a pair's width.
  std::nth_element(widths.begin(), widths.begin() + static_cast<std::ptrdiff_t>(widths.size() / 4),
                   widths.end());
  const float narrow = widths[widths.size() / 4];
  if (!(narrow > 0.0f)) {
    return;
  }
  const int n = static_cast<int>(cluster.contour.size());
  std::vector<CapturedBlade> result;
  const auto split = [&](const auto& self, CapturedBlade blade, int a, int b, int depth) -> void {
    const int len = ((b - a) % n + n) % n;
    if (depth < 4 && maxWidthPx(blade) > kMergedWidthRatio * narrow && len > 8) {
      float dip = 0.0f;
      const int offset = deepestDip(cluster, a, len, narrow / 3.0f, dip);
      if (offset > 0) {
        const int index = (a + offset) % n;
        std::vector<CapturedBlade> halves;
        std::string reason;
        if (buildBlade(c, cluster, clusterMask, a, index, clusterIndex, halves, reason, narrow / 3.0f) &&
            buildBlade(c, cluster, clusterMask, index, b, clusterIndex, halves, reason, narrow / 3.0f) &&
            std::max(maxWidthPx(halves[0]), maxWidthPx(halves[1])) < maxWidthPx(blade)) {
          const glm::vec2 at = cluster.contour[static_cast<std::size_t>(index)];
          splits.push_back(
              {index, at, cluster.smoothed[static_cast<std::size_t>(index)], dip / std::max(maxR, 1e-3f)});
          cluster.split.push_back(fmt::format(
              "the blade {:.0f} px wide ({:.1f}× the cluster's narrow blades) was cut at ({:.0f}, {:.0f}) "
              "between two of its tips, where the outline dips {:.0f} px, into blades {:.0f} and {:.0f} px "
              "wide",
              maxWidthPx(blade), maxWidthPx(blade) / narrow, at.x, at.y, dip, maxWidthPx(halves[0]),
              maxWidthPx(halves[1])));
          self(self, std::move(halves[0]), a, index, depth + 1);
          self(self, std::move(halves[1]), index, b, depth + 1);
          return;
        }
      }
    }
    result.push_back(std::move(blade));
  };
  for (std::size_t i = 0; i < blades.size(); ++i) {
    split(split, std::move(blades[i]), segments[i].first, segments[i].second, 0);
  }
  blades = std::move(result);
}

/** Contour points on each side of a notch whose chord must pass outside the blob. */
constexpr int kNotchArm = 6;
/** A tip between notches that does not reach the centre must be this many times longer than wide. */
constexpr float kBumpElongation = 1.5f;
/** A blade from a notch narrower than this fraction of its cluster's median blade is a sliver. */
constexpr float kSliverWidthRatio = 0.25f;

/**
 * Junctions at notches (ExtractOptions::notchProminence): minima of `fine` (the distance signal smoothed only
 * by ExtractOptions::notchSigmaPx) too shallow for the prominence test, at least notchMinPx and
 * notchProminence of the largest distance `maxR` deep, where the outline turns inwards between two tips (the
 * chord from kNotchArm points before to kNotchArm after passes outside the blob) and no junction lies within
 * kNotchArm points. In a dense fan or where two fans cross, the tips of neighbouring blades part only over
 * their last few centimetres: the valley between them is shallow beside the cluster's longest blade, but it
 * is a notch, not noise along one blade's edge (which bulges as often as it dents). Adds them to `minima` and
 * `prominence` in contour order; returns them.
 */
std::vector<int> notchMinima(const ExtractOptions& o, const Cluster& cluster, const cv::Mat& clusterMask,
                             float maxR, const std::vector<float>& fine, std::vector<int>& minima,
                             std::vector<float>& prominence) {
  std::vector<int> notches;
  if (o.notchProminence <= 0.0) {
    return notches;
  }
  const int n = static_cast<int>(cluster.contour.size());
  std::vector<float> lowProminence;
  const std::vector<int> low = prominentMinima(
      fine, std::max(static_cast<float>(o.notchMinPx), static_cast<float>(o.notchProminence) * maxR),
      lowProminence);
  std::vector<std::pair<int, float>> all;
  for (std::size_t j = 0; j < minima.size(); ++j) {
    all.emplace_back(minima[j], prominence[j]);
  }
  for (std::size_t j = 0; j < low.size(); ++j) {
    const int v = low[j];
    bool near = false;
    for (const int m : minima) {
      near = near || std::min((m - v + n) % n, (v - m + n) % n) < kNotchArm;
    }
    const glm::vec2 before = cluster.contour[static_cast<std::size_t>((v - kNotchArm + n) % n)];
    const glm::vec2 after = cluster.contour[static_cast<std::size_t>((v + kNotchArm) % n)];
    if (!near && !insideMask(clusterMask, 0.5f * (before + after))) {
      notches.push_back(v);
      all.emplace_back(v, lowProminence[j]);
    }
  }
  std::sort(all.begin(), all.end());
  minima.clear();
  prominence.clear();
  for (const auto& [index, p] : all) {
    minima.push_back(index);
    prominence.push_back(p);
  }
  return notches;
}

Partition partition(Context& c, const std::vector<cv::Point>& contourPts, const cv::Mat& clusterMask,
                    const CentreCandidate& centre, int clusterIndex) {
  Partition out;
  Cluster& cluster = out.cluster;
  cluster.areaPx = cv::countNonZero(clusterMask);
  cluster.centre = centre.px;
  cluster.centreMode = centre.mode;
  // OpenCV traces outer contours clockwise on screen (y down); that order is kept.
  cluster.contour.reserve(contourPts.size());
  for (const cv::Point& p : contourPts) {
    cluster.contour.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
  }
  const int n = static_cast<int>(cluster.contour.size());
  cluster.signal.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    cluster.signal[i] = glm::length(cluster.contour[i] - cluster.centre);
  }
  cluster.smoothed = smoothCircular(cluster.signal, c.options.smoothSigmaPx);
  const float maxR = *std::max_element(cluster.smoothed.begin(), cluster.smoothed.end());
  std::vector<float> prominence;
  std::vector<int> minima =
      prominentMinima(cluster.smoothed, static_cast<float>(c.options.prominence) * maxR, prominence);
  // Shallower minima where the outline turns in between two tips (notches): junctions too.
  const std::vector<float> fine = c.options.notchSigmaPx == c.options.smoothSigmaPx
                                      ? cluster.smoothed
                                      : smoothCircular(cluster.signal, c.options.notchSigmaPx);
  const std::vector<int> notches =
      notchMinima(c.options, cluster, clusterMask, maxR, fine, minima, prominence);
  for (std::size_t j = 0; j < minima.size(); ++j) {
    Junction junction;
    junction.index = minima[j];
    junction.px = cluster.contour[minima[j]];
    junction.distancePx = cluster.smoothed[minima[j]];
    junction.prominence = prominence[j] / std::max(maxR, 1e-3f);
    cluster.junctions.push_back(junction);
  }
  const std::string label = c.frame.label();
  if (cluster.junctions.empty()) {
    out.warnings.push_back(
        fmt::format("{}: cluster at ({:.0f}, {:.0f}) has no junction: its distance signal has "
                    "no minimum of prominence ≥ {}",
                    label, cluster.centre.x, cluster.centre.y, c.options.prominence));
    return out;
  }
  const std::size_t jn = cluster.junctions.size();
  // A segment too wide for one blade is often two blades overlapping near their base (their valley is too
  // shallow for the prominence test): it is split at the deepest minimum between its two highest peaks when
  // both peaks rise a blade's minimum length above it.
  std::vector<Junction> splits;
  std::vector<std::pair<int, int>> segments; // each blade's contour segment
  // Whether the segment [a, b] ends at a notch.
  const auto atNotches = [&notches](int a, int b) {
    return std::find(notches.begin(), notches.end(), a) != notches.end() ||
           std::find(notches.begin(), notches.end(), b) != notches.end();
  };
  const auto take = [&](const auto& self, int a, int b, int depth) -> void {
    std::string reason;
    // A tip between notches stands only a little above them: it needs to reach notchMinPx, not a blade's
    // minimum length (the blade runs on, merged with its neighbours, down to the centre).
    const bool atNotch = atNotches(a, b);
    if (buildBlade(c, cluster, clusterMask, a, b, clusterIndex, out.blades, reason,
                   atNotch ? static_cast<float>(c.options.notchMinPx) : -1.0f, atNotch ? &fine : nullptr)) {
      const CapturedBlade& built = out.blades.back();
      if (atNotch && built.extensionPx <= 0.0f && built.lengthPx < kBumpElongation * maxWidthPx(built)) {
        // A bump between notches that cannot be followed to the centre and is hardly longer than wide is a
        // ripple of the outline, not a tip (a tip that cannot be followed is still a blade as long as it
        // shows).
        cluster.rejected.push_back(
            fmt::format("contour {}–{}: a bump between notches ({:.0f} px long, {:.0f} px "
                        "wide) that does not reach the centre",
                        a, b, built.lengthPx, maxWidthPx(built)));
        out.blades.pop_back();
        return;
      }
      cluster.blades.push_back(static_cast<int>(out.blades.size() - 1));
      segments.emplace_back(a, b);
      return;
    }
    const int len = ((b - a) % n + n) % n;
    if (depth < 4 && reason.rfind("not elongated", 0) == 0 && len > 8) {
      float splitDepth = 0.0f;
      const int split =
          deepestDip(cluster, a, len, static_cast<float>(c.options.minBladeLengthPx), splitDepth);
      if (split > 0) {
        const int index = (a + split) % n;
        splits.push_back(
            {index, cluster.contour[index], cluster.smoothed[index], splitDepth / std::max(maxR, 1e-3f)});
        self(self, a, index, depth + 1);
        self(self, index, b, depth + 1);
        return;
      }
    }
    cluster.rejected.push_back(fmt::format("contour {}–{}: {}", a, b, reason));
  };
  for (std::size_t j = 0; j < jn; ++j) {
    const int a = cluster.junctions[j].index;
    // One junction: the whole contour from it round to just before it is one blade.
    const int b = jn == 1 ? (a + n - 1) % n : cluster.junctions[(j + 1) % jn].index;
    take(take, a, b, 0);
  }
  {
    // A blade between a notch and another junction much narrower than the cluster's other blades is a sliver
    // of a wide leaf's edge, not a tip.
    std::vector<float> widths;
    std::vector<bool> notched(segments.size());
    for (std::size_t i = 0; i < segments.size(); ++i) {
      notched[i] = atNotches(segments[i].first, segments[i].second);
      if (!notched[i]) {
        widths.push_back(maxWidthPx(out.blades[i]));
      }
    }
    if (!widths.empty()) {
      std::nth_element(widths.begin(), widths.begin() + static_cast<std::ptrdiff_t>(widths.size() / 2),
                       widths.end());
      const float median = widths[widths.size() / 2];
      for (std::size_t i = segments.size(); i-- > 0;) {
        if (notched[i] && maxWidthPx(out.blades[i]) < kSliverWidthRatio * median) {
          cluster.rejected.push_back(
              fmt::format("contour {}–{}: a sliver {:.0f} px wide beside blades {:.0f} px wide",
                          segments[i].first, segments[i].second, maxWidthPx(out.blades[i]), median));
          out.blades.erase(out.blades.begin() + static_cast<std::ptrdiff_t>(i));
          segments.erase(segments.begin() + static_cast<std::ptrdiff_t>(i));
        }
      }
    }
  }
  splitMerged(c, cluster, clusterMask, clusterIndex, segments, out.blades, splits, maxR);
  cluster.blades.resize(out.blades.size());
  std::iota(cluster.blades.begin(), cluster.blades.end(), 0);
  cluster.junctions.insert(cluster.junctions.end(), splits.begin(), splits.end());
  if (out.blades.empty()) {
    out.warnings.push_back(fmt::format("{}: cluster at ({:.0f}, {:.0f}): no segment is a blade ({})", label,
                                       cluster.centre.x, cluster.centre.y,
                                       cluster.rejected.empty() ? "none" : cluster.rejected.front()));
  }
  return out;
}

/** One depth layer of a cluster: a region of continuous depth, and its silhouette as far as nearer ones hide
 * it. */
struct DepthLayer {
  /** CV_8U, frame-sized: the layer's own pixels (its depth is the layer's). */
  cv::Mat own;
  /** `own` plus the straight runs across nearer layers that joined it (the layer seen on both sides). */
  cv::Mat completed;
  /** Median depth of the layer's pixels, metres. */
  float depthMetres = 0.0f;
};

/**
 * Pixels a depth layer of a blob of `blobArea` pixels needs to be partitioned on its own: a quarter of a
 * cluster's (a blade in front of another is often narrower than a tuft), and 0.5 % of the blob (in a large
 * blob, small patches of a leaf's surface that the sensor's depth steps cut off are not blades).
 */
int minLayerArea(const ExtractOptions& o, int blobArea) {
  return std::max({1, o.minClusterAreaPx / 4, blobArea / 200});
}

/** Offsets (forward half of a radius-2 disc) over which pixels of one depth layer link. */
constexpr std::array<std::pair<int, int>, 12> kLayerLinks{
    {{1, 0}, {2, 0}, {-2, 1}, {-1, 1}, {0, 1}, {1, 1}, {2, 1}, {-1, 2}, {0, 2}, {1, 2}, {-2, 2}, {2, 2}}};

/** The widest occluder (pixels) a surface is followed across. */
constexpr int kMaxOccluderRunPx = 24;
/** Depth a surface may drift per pixel hidden behind an occluder, metres. */
constexpr float kOccludedSlopeMetresPerPx = 0.0005f;

/**
 * Depth step between nearby pixels, metres, above which they lie on different surfaces (at depth z, m): 5 mm
 * or 0.7 % of the depth, and never under 2.5 depth quanta of the sensor (8 mm and 1.2 % merged more crossing
 * fans through the contacts of their blades: 78.3 % of 1,000 sweep clusters exact against 79.0 %). `quantum`
 * is the sensor's depth resolution over z² (1/m): structured light and stereo resolve depth in disparity
 * steps, which grow with z² (a Kinect v1 about 2 mm at 0.8 m, the Middlebury Aloe's integer disparities 4 cm
 * at 5 m).
 */
float layerStepMetres(float z, float quantum) {
  return std::max({0.005f, 0.007f * z, 2.5f * quantum * z * z});
}

/**
 * The depth resolution of a cluster's pixels over z² (1/m): the lower quartile of the non-zero depth
 * differences between horizontal neighbours, each over z² (one disparity step where the sensor quantises).
 */
template <typename HasDepth> float depthQuantum(const cv::Mat& depth, const HasDepth& hasDepth) {
  std::vector<float> ratios;
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x + 1 < depth.cols; ++x) {
      if (hasDepth(x, y) && hasDepth(x + 1, y)) {
        const float z = depth.at<float>(y, x);
        const float d = std::abs(depth.at<float>(y, x + 1) - z);
        if (d > 0.0f) {
          ratios.push_back(d / (z * z));
        }
      }
    }
  }
  if (ratios.empty()) {
    return 0.0f;
  }
  const auto q = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 4);
  std::nth_element(ratios.begin(), q, ratios.end());
  return *q;
}

/**
 * Links each pixel with depth to those within two pixels (kLayerLinks) whose depth differs by at most
 * layerStepMetres, i.e. the same surface: `depth` is CV_32F metres, `hasDepth(x, y)` says which pixels take
 * part, `unite(a, b)` joins the sets of two pixels given as indices `y * depth.cols + x`. Neighbours up to
 * two pixels away: a narrow blade's pixels reach each other across the dropouts and the lateral jitter that
 * scatter a sensor's depth along its edges.
 */
template <typename HasDepth, typename Unite>
void linkSurfaces(const cv::Mat& depth, float quantum, const HasDepth& hasDepth, const Unite& unite) {
  const auto at = [&depth](int x, int y) { return static_cast<std::size_t>(y) * depth.cols + x; };
  for (int y = 0; y < depth.rows; ++y) {
    for (int x = 0; x < depth.cols; ++x) {
      if (!hasDepth(x, y)) {
        continue;
      }
      const float z = depth.at<float>(y, x);
      const float step = layerStepMetres(z, quantum);
      for (const auto& [dx, dy] : kLayerLinks) {
        if (hasDepth(x + dx, y + dy) && std::abs(depth.at<float>(y + dy, x + dx) - z) <= step) {
          unite(at(x, y), at(x + dx, y + dy));
        }
      }
    }
  }
}

/** The root of pixel `i`'s set in a union-find over pixels (`parent`; -1: a pixel that takes no part). */
std::size_t findRoot(std::vector<int>& parent, std::size_t i) {
  while (parent[i] != static_cast<int>(i)) {
    parent[i] = parent[static_cast<std::size_t>(parent[i])];
    i = static_cast<std::size_t>(parent[i]);
  }
  return i;
}

/**
 * Links the pixels of a box that take part (`parent` row-major over `depth`, CV_32F metres: ≥ 0 for a pixel
 * that takes part, each its own set at first) into the surfaces linkSurfaces finds.
 */
void linkBoxSurfaces(const cv::Mat& depth, std::vector<int>& parent) {
  const int w = depth.cols;
  const int h = depth.rows;
  const auto hasDepth = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && parent[static_cast<std::size_t>(y) * w + x] >= 0;
  };
  linkSurfaces(depth, depthQuantum(depth, hasDepth), hasDepth, [&](std::size_t a, std::size_t b) {
    a = findRoot(parent, a);
    b = findRoot(parent, b);
    if (a != b) {
      parent[std::max(a, b)] = static_cast<int>(std::min(a, b));
    }
  });
}

/**
 * Splits one cluster into depth layers. Pixels join when their depths differ by less than layerStepMetres
 * over a short distance (the same surface), and across a nearer occluder when the depth on its far side
 * continues the near side's (a blade seen on both sides of one that crosses in front of it). A blade in front
 * of another steps in depth all along its outline, even where the silhouettes merge, so it forms a layer of
 * its own; blades of one tuft meet at their root and form one. Layers smaller than minArea, and pixels
 * with no depth, join the nearest large layer. Each layer's completed silhouette adds the straight runs
 * across occluders that joined it. Returns the layers nearest first, or nothing when the cluster is one
 * layer.
 */
std::vector<DepthLayer> depthLayers(const Context& c, const cv::Mat& clusterMask, int minArea) {
  const cv::Rect box = cv::boundingRect(clusterMask);
  if (box.empty()) {
    return {};
  }
  const cv::Mat mask = clusterMask(box);
  const cv::Mat depth = c.depth(box);
  const int w = box.width;
  const int h = box.height;
  const auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
  // Union-find over the pixels with depth in range (-1: no depth).
  std::vector<int> parent(static_cast<std::size_t>(w) * h, -1);
  const auto find = [&](std::size_t i) {
    std::size_t r = i;
    while (parent[r] != static_cast<int>(r)) {
      r = static_cast<std::size_t>(parent[r]);
    }
    while (parent[i] != static_cast<int>(r)) {
      const std::size_t next = static_cast<std::size_t>(parent[i]);
      parent[i] = static_cast<int>(r);
      i = next;
    }
    return r;
  };
  const auto unite = [&](std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) {
      parent[std::max(a, b)] = static_cast<int>(std::min(a, b));
    }
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float z = depth.at<float>(y, x);
      if (mask.at<std::uint8_t>(y, x) != 0 && inBladeRange(c, z)) {
        parent[at(x, y)] = static_cast<int>(at(x, y));
      }
    }
  }
  const auto hasDepth = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && parent[at(x, y)] >= 0;
  };
  const float quantum = depthQuantum(depth, hasDepth);
  // Across occluders: from a pixel whose neighbour is nearer by more than a step, walk straight over nearer
  // pixels (and dropouts); where the walk lands on depth that continues this pixel's, the surface runs on
  // behind the occluder.
  struct Run {
    cv::Point from;
    cv::Point to;
  };
  std::vector<Run> runs;
  constexpr std::array<std::pair<int, int>, 8> kDirections{
      {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}}};
  const int maxRun = std::clamp(std::max(w, h) / 4, 8, kMaxOccluderRunPx);
  linkSurfaces(depth, quantum, hasDepth, unite);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!hasDepth(x, y)) {
        continue;
      }
      const float z = depth.at<float>(y, x);
      const float step = layerStepMetres(z, quantum);
      for (const auto& [dx, dy] : kDirections) {
        if (!hasDepth(x + dx, y + dy) || depth.at<float>(y + dy, x + dx) > z - step) {
          continue;
        }
        for (int k = 2; k <= maxRun; ++k) {
          const int qx = x + k * dx;
          const int qy = y + k * dy;
          if (qx < 0 || qy < 0 || qx >= w || qy >= h || mask.at<std::uint8_t>(qy, qx) == 0) {
            break;
          }
          if (!hasDepth(qx, qy)) {
            continue;
          }
          const float zq = depth.at<float>(qy, qx);
          if (zq < z - step) {
            continue; // still on the occluder
          }
          if (std::abs(zq - z) <= step + kOccludedSlopeMetresPerPx * static_cast<float>(k)) {
            unite(at(x, y), at(qx, qy));
            runs.push_back({{x, y}, {qx, qy}});
          }
          break;
        }
      }
    }
  }
  std::vector<int> size(parent.size(), 0);
  for (std::size_t i = 0; i < parent.size(); ++i) {
    if (parent[i] >= 0) {
      ++size[find(i)];
    }
  }
  std::vector<std::size_t> roots;
  for (std::size_t i = 0; i < parent.size(); ++i) {
    if (parent[i] == static_cast<int>(i) && size[i] >= minArea) {
      roots.push_back(i);
    }
  }
  if (roots.size() < 2) {
    return {};
  }
  // Each large layer's pixels, and for every other pixel of the cluster the nearest large layer.
  std::vector<int> layerOf(parent.size(), -1);
  for (std::size_t i = 0; i < parent.size(); ++i) {
    if (parent[i] >= 0) {
      const auto it = std::find(roots.begin(), roots.end(), find(i));
      layerOf[i] = it != roots.end() ? static_cast<int>(it - roots.begin()) : -1;
    }
  }
  std::vector<cv::Mat> distance(roots.size());
  for (std::size_t l = 0; l < roots.size(); ++l) {
    cv::Mat notLayer(h, w, CV_8U, cv::Scalar(255));
    for (std::size_t i = 0; i < parent.size(); ++i) {
      if (layerOf[i] == static_cast<int>(l)) {
        notLayer.data[i] = 0;
      }
    }
    cv::distanceTransform(notLayer, distance[l], cv::DIST_L2, cv::DIST_MASK_PRECISE);
  }
  std::vector<DepthLayer> layers(roots.size());
  std::vector<std::vector<float>> depths(roots.size());
  for (std::size_t l = 0; l < roots.size(); ++l) {
    layers[l].own = cv::Mat::zeros(clusterMask.size(), CV_8U);
  }
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (mask.at<std::uint8_t>(y, x) == 0) {
        continue;
      }
      int l = layerOf[at(x, y)];
      if (l >= 0) {
        depths[static_cast<std::size_t>(l)].push_back(depth.at<float>(y, x));
      } else {
        l = 0;
        for (std::size_t k = 1; k < roots.size(); ++k) {
          l = distance[k].at<float>(y, x) < distance[static_cast<std::size_t>(l)].at<float>(y, x)
                  ? static_cast<int>(k)
                  : l;
        }
      }
      layers[static_cast<std::size_t>(l)].own.at<std::uint8_t>(box.y + y, box.x + x) = 255;
    }
  }
  for (std::size_t l = 0; l < roots.size(); ++l) {
    std::vector<float>& zs = depths[l];
    std::nth_element(zs.begin(), zs.begin() + static_cast<std::ptrdiff_t>(zs.size() / 2), zs.end());
    layers[l].depthMetres = zs[zs.size() / 2];
    layers[l].completed = layers[l].own.clone();
  }
  // A layer runs on under the occluders its runs crossed.
  for (const Run& run : runs) {
    const int l = layerOf[at(run.from.x, run.from.y)];
    if (l >= 0) {
      cv::line(layers[static_cast<std::size_t>(l)].completed, run.from + box.tl(), run.to + box.tl(),
               cv::Scalar(255), 1, cv::LINE_8);
    }
  }
  std::sort(layers.begin(), layers.end(),
            [](const DepthLayer& a, const DepthLayer& b) { return a.depthMetres < b.depthMetres; });
  return layers;
}

/** The largest spread of a depth split's surfaces (their median depths) as a share of the nearer one's depth.
 */
constexpr float kSplitDepthSpread = 0.15f;

/**
 * The blades inside one captured blade that part in depth towards its outer end: within the blade's outline,
 * the pixels of its own depth beyond the middle of its visible length (from its junctions to its tip; with
 * `outerShare` > 0, beyond that share of its distance from the centre to its tip, measured from the tip,
 * when that reaches lower) are linked as depthLayers links them; each linked surface of at least a sixth of
 * those pixels that reaches the outer end becomes a blade along the medial axis of the blade's lower part and
 * that surface (its median depth, metres, to `surfaceDepths`). Returns nothing when fewer than two surfaces
 * reach it (one blade, however its depth runs), when their median depths spread by more than
 * kSplitDepthSpread, or when `outerShare` reaches no lower than the middle.
 */
std::vector<CapturedBlade> depthParts(Context& c, const Cluster& cluster, const cv::Mat& clusterMask,
                                      int clusterIndex, const CapturedBlade& blade,
                                      std::vector<float>& surfaceDepths, float outerShare = 0.0f) {
  const glm::vec2 centre = cluster.centre;
  const glm::vec2 tip = blade.outline[static_cast<std::size_t>(blade.tip)];
  const float rTip = glm::length(tip - centre);
  const float rBase =
      std::max(glm::length(blade.outline.front() - centre), glm::length(blade.outline.back() - centre));
  if (rTip - rBase < static_cast<float>(c.options.minBladeLengthPx)) {
    return {};
  }
  const float rMiddle = 0.5f * (rBase + rTip);
  const float rCut = outerShare > 0.0f ? (1.0f - outerShare) * rTip : rMiddle;
  if (outerShare > 0.0f && rCut >= rMiddle) {
    return {};
  }
  std::vector<cv::Point> poly;
  for (const glm::vec2& q : blade.outline) {
    poly.emplace_back(static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y)));
  }
  // The regions live in the outline's bounding box (grown by a pixel for the medial axis's border)...
  const cv::Rect rbox =
      (cv::boundingRect(poly) + cv::Size(1, 1)) & cv::Rect(0, 0, clusterMask.cols, clusterMask.rows);
  if (rbox.empty()) {
    return {};
  }
  cv::Mat region = cv::Mat::zeros(clusterMask.size(), CV_8U);
  cv::fillPoly(region(rbox), std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255), cv::LINE_8, 0,
               -rbox.tl());
  cv::Mat inBox = region(rbox);
  cv::bitwise_and(inBox, clusterMask(rbox), inBox);
  // ...the surfaces in the box of its outer part.
  std::vector<cv::Point> outerPoly;
  for (const cv::Point& q : poly) {
    if (glm::length(glm::vec2(q.x, q.y) - centre) >= rCut - 2.0f) {
      outerPoly.push_back(q);
    }
  }
  // (Grown: the circle at rCut dips below its ends across a wide blade.)
  const cv::Rect outerBox = cv::boundingRect(outerPoly);
  const cv::Rect box =
      cv::Rect(outerBox.x - 4, outerBox.y - 4, outerBox.width + 8, outerBox.height + 8) & rbox;
  if (box.empty()) {
    return {};
  }
  const int w = box.width;
  const int h = box.height;
  const auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
  const auto radius = [&](int x, int y) { return glm::length(glm::vec2(x + box.x, y + box.y) - centre); };
  std::vector<int> parent(static_cast<std::size_t>(w) * h, -1);
  const cv::Mat depth = c.depth(box);
  int outer = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (region.at<std::uint8_t>(box.y + y, box.x + x) != 0 &&
          c.ownMask.at<std::uint8_t>(box.y + y, box.x + x) != 0 && inBladeRange(c, depth.at<float>(y, x)) &&
          radius(x, y) >= rCut) {
        parent[at(x, y)] = static_cast<int>(at(x, y));
        ++outer;
      }
    }
  }
  const auto hasDepth = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && parent[at(x, y)] >= 0;
  };
  const auto find = [&](std::size_t i) { return findRoot(parent, i); };
  linkBoxSurfaces(depth, parent);
  struct Surface {
    int size = 0;
    float reach = 0.0f;
    cv::Point end;
  };
  std::vector<Surface> surfaces(parent.size());
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (hasDepth(x, y)) {
        Surface& s = surfaces[find(at(x, y))];
        ++s.size;
        const float r = radius(x, y);
        if (r > s.reach) {
          s.reach = r;
          s.end = cv::Point(x, y);
        }
      }
    }
  }
  // A surface counts when it holds a sixth of the outer pixels and runs at least half way out from the cut.
  std::vector<std::size_t> reaching;
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    if (surfaces[i].size >= std::max(outer / 6, 12) && surfaces[i].reach - rCut >= 0.5f * (rTip - rCut)) {
      reaching.push_back(i);
    }
  }
  if (reaching.size() < 2) {
    return {};
  }
  const glm::vec2 basePoint = 0.5f * (blade.outline.front() + blade.outline.back());
  std::vector<CapturedBlade> parts;
  // Each surface's median depth: a surface runs on behind the nearer ones, never in front of farther ones.
  std::vector<std::vector<float>> zs(reaching.size());
  std::vector<int> which(parent.size(), -1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (hasDepth(x, y)) {
        const auto it = std::find(reaching.begin(), reaching.end(), find(at(x, y)));
        if (it != reaching.end()) {
          which[at(x, y)] = static_cast<int>(it - reaching.begin());
          zs[static_cast<std::size_t>(it - reaching.begin())].push_back(depth.at<float>(y, x));
        }
      }
    }
  }
  std::vector<float> median(reaching.size());
  for (std::size_t k = 0; k < reaching.size(); ++k) {
    std::nth_element(zs[k].begin(), zs[k].begin() + static_cast<std::ptrdiff_t>(zs[k].size() / 2),
                     zs[k].end());
    median[k] = zs[k][zs[k].size() / 2];
  }
  // Surfaces farther apart in depth than kSplitDepthSpread of their distance are not blades of one tuft (the
  // leaves of the Middlebury Aloe, whose depth is nominal, part by 40 %; the sweep's neighbours by 1–8 cm at
  // 0.55–0.9 m).
  if (const auto [lo, hi] = std::minmax_element(median.begin(), median.end());
      *hi - *lo > kSplitDepthSpread * *lo) {
    return {};
  }
  for (std::size_t k = 0; k < reaching.size(); ++k) {
    const std::size_t root = reaching[k];
    // The blade's lower part and this surface, and the nearer surfaces that hide it.
    cv::Mat sub = cv::Mat::zeros(region.size(), CV_8U);
    region(rbox).copyTo(sub(rbox));
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const int o = which[at(x, y)];
        if (o >= 0 && o != static_cast<int>(k) && median[static_cast<std::size_t>(o)] > median[k]) {
          sub.at<std::uint8_t>(box.y + y, box.x + x) = 0;
        }
      }
    }
    cv::Mat closed;
    cv::morphologyEx(sub(rbox), closed, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(3, 3)));
    cv::bitwise_and(closed, region(rbox), closed);
    closed.copyTo(sub(rbox));
    const glm::vec2 end(static_cast<float>(surfaces[root].end.x + box.x),
                        static_cast<float>(surfaces[root].end.y + box.y));
    std::vector<glm::vec2> axis;
    std::vector<float> axisWidths;
    if (!medialAxis(sub, basePoint, end, axis, axisWidths) || axis.size() < 3) {
      continue;
    }
    std::vector<float> widths;
    std::vector<glm::vec2> line = smoothOpen(resample(axis, kMatchSamples, &axisWidths, &widths), 2.0, true);
    widthsAcross(sub, line, widths);
    CapturedBlade part;
    part.cluster = clusterIndex;
    part.outline = blade.outline;
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < part.outline.size(); ++i) {
      nearest = glm::length(part.outline[i] - end) < glm::length(part.outline[nearest] - end) ? i : nearest;
    }
    part.tip = static_cast<int>(nearest);
    part.medialAxis = true;
    part.sideRatio = blade.sideRatio;
    std::string reason;
    const float maxWidth = *std::max_element(widths.begin(), widths.end());
    if (finishBlade(c, cluster, clusterMask, std::move(line), std::move(widths), maxWidth, std::move(part),
                    parts, reason)) {
      surfaceDepths.push_back(median[k]);
    }
  }
  if (parts.size() < 2) {
    return {};
  }
  return parts;
}

/**
 * Third pass over a cluster's blades: each blade that holds several surfaces parting in depth towards its
 * outer end (depthParts) is replaced by them; `--explain` lists each such split.
 */
void splitByDepth(Context& c, Partition& p, const cv::Mat& clusterMask, int clusterIndex) {
  std::vector<CapturedBlade> result;
  for (CapturedBlade& blade : p.blades) {
    std::vector<float> surfaceDepths;
    std::vector<CapturedBlade> parts =
        depthParts(c, p.cluster, clusterMask, clusterIndex, blade, surfaceDepths);
    // Its neighbours may hide all but its last few pixels: look again over its outer part.
    const auto outerShare = static_cast<float>(c.options.depthSplitOuterShare);
    const bool outer = parts.empty() && outerShare > 0.0f;
    if (outer) {
      parts = depthParts(c, p.cluster, clusterMask, clusterIndex, blade, surfaceDepths, outerShare);
    }
    if (parts.empty()) {
      result.push_back(std::move(blade));
      continue;
    }
    const glm::vec2 tip = blade.outline[static_cast<std::size_t>(blade.tip)];
    std::string depths;
    for (const float z : surfaceDepths) {
      depths += fmt::format("{}{:.3f}", depths.empty() ? "" : ", ", z);
    }
    p.cluster.split.push_back(fmt::format(
        "the blade with its tip at ({:.0f}, {:.0f}) parts in depth towards its tip into {} "
        "surfaces that each reach out to it, at {} m: one blade each{}",
        tip.x, tip.y, parts.size(), depths,
        outer ? fmt::format(" (over the outer {:.0f} % of its length: its neighbours hide all but its end)",
                            100.0f * outerShare)
              : ""));
    for (CapturedBlade& part : parts) {
      result.push_back(std::move(part));
    }
  }
  p.blades = std::move(result);
  p.cluster.blades.resize(p.blades.size());
  std::iota(p.cluster.blades.begin(), p.cluster.blades.end(), 0);
}

/** Pixels a surface of a cluster's outer band needs to be taken as the end of a blade of its own. */
constexpr int kTipSurfaceMinPx = 30;
/** A captured blade whose tip lies within this many pixels of a surface's far end is that surface's blade. */
constexpr float kTipSurfaceGapPx = 5.0f;
/**
 * Around a surface's far end, within this many pixels and outwards from the centre (a cone of ±45°, cosine
 * kTipOccluderCone), a nearer surface means the surface runs on behind it: cut short, not a tip.
 */
constexpr int kTipOccluderReachPx = 3;
constexpr float kTipOccluderCone = 0.7f;
/** Pixels beyond a surface's far end, outwards from the centre (±30°), that must lie outside the cluster. */
constexpr int kTipClearancePx = 8;
/** Radial bins (pixels) a blade found from its surface is traced through. */
constexpr float kTipSurfaceBinPx = 3.0f;

/** One surface of a cluster's outer band (bandSurfaces), or a branch of one; positions are frame pixels. */
struct BandSurface {
  int size = 0;
  float low = std::numeric_limits<float>::max(); ///< nearest distance from the centre, pixels
  float reach = 0.0f;                            ///< farthest distance from the centre, pixels
  cv::Point end;                                 ///< the farthest pixel
  float depthMetres = 0.0f;                      ///< median depth
  bool claimed = false;                          ///< a captured blade's tip lies on it
  std::vector<cv::Point> pixels;                 ///< frame pixels
  std::vector<glm::vec2> tipsOn;                 ///< the captured tips that lie on it
};

/** Wraps an angle to [-π, π), radians. */
float wrapAngle(float a) {
  constexpr float kPi = 3.14159265f;
  while (a >= kPi) {
    a -= 2.0f * kPi;
  }
  while (a < -kPi) {
    a += 2.0f * kPi;
  }
  return a;
}

/**
 * Splits a band surface into its branches: where two blades' ends link into one surface (they touch at the
 * same depth lower down), its farthest distance from the centre, over the direction from the centre (bins 2
 * px wide at its far end), has a peak at each tip. Peaks at least `prominencePx` above the dip between them
 * and the next higher peak are branches; the surface is cut at the lowest point between neighbouring ones.
 * A captured tip on the surface claims the branch its direction falls in. Returns the surface itself when
 * it has one branch.
 */
std::vector<BandSurface> branches(const Context& c, const BandSurface& s, const glm::vec2& centre,
                                  float prominencePx) {
  glm::vec2 mean(0.0f);
  for (const cv::Point& q : s.pixels) {
    mean += glm::vec2(static_cast<float>(q.x), static_cast<float>(q.y)) - centre;
  }
  const float a0 = std::atan2(mean.y, mean.x);
  const auto angleOf = [&](const glm::vec2& v) {
    return wrapAngle(std::atan2(v.y - centre.y, v.x - centre.x) - a0);
  };
  float lo = std::numeric_limits<float>::max();
  float hi = std::numeric_limits<float>::lowest();
  for (const cv::Point& q : s.pixels) {
    const float a = angleOf(glm::vec2(q.x, q.y));
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  const float binRadians = 2.0f / std::max(s.reach, 1.0f);
  const int bins = static_cast<int>((hi - lo) / binRadians) + 1;
  if (bins < 3) {
    return {s};
  }
  const auto binOf = [&](const glm::vec2& v) {
    return std::clamp(static_cast<int>((angleOf(v) - lo) / binRadians), 0, bins - 1);
  };
  std::vector<float> profile(static_cast<std::size_t>(bins), s.low);
  for (const cv::Point& q : s.pixels) {
    const glm::vec2 v(q.x, q.y);
    float& r = profile[static_cast<std::size_t>(binOf(v))];
    r = std::max(r, glm::length(v - centre));
  }
  const auto at = [&profile](int b) { return profile[static_cast<std::size_t>(b)]; };
  // Each peak's prominence: its height over the higher of the lowest points between it and the nearest
  // higher peak on either side (over the surface's nearest point where none is higher).
  std::vector<int> peaks;
  for (int b = 0; b < bins; ++b) {
    const float h = at(b);
    if ((b > 0 && at(b - 1) >= h) || (b + 1 < bins && at(b + 1) > h)) {
      continue;
    }
    std::array<float, 2> dip{h, h};
    std::array<bool, 2> higher{false, false};
    for (std::size_t side = 0; side < 2; ++side) {
      const int dir = side == 0 ? -1 : 1;
      for (int k = b + dir; k >= 0 && k < bins && !higher[side]; k += dir) {
        dip[side] = std::min(dip[side], at(k));
        higher[side] = at(k) > h;
      }
    }
    float base = s.low;
    if (higher[0] && higher[1]) {
      base = std::max(dip[0], dip[1]);
    } else if (higher[0] || higher[1]) {
      base = higher[0] ? dip[0] : dip[1];
    }
    if (h - base >= prominencePx) {
      peaks.push_back(b);
    }
  }
  if (peaks.size() < 2) {
    return {s};
  }
  // Branch i holds the bins from cuts[i] up to cuts[i + 1].
  std::vector<int> cuts{0};
  for (std::size_t i = 0; i + 1 < peaks.size(); ++i) {
    int lowest = peaks[i];
    for (int k = peaks[i]; k <= peaks[i + 1]; ++k) {
      lowest = at(k) < at(lowest) ? k : lowest;
    }
    cuts.push_back(lowest);
  }
  const auto branchOf = [&](const glm::vec2& v) {
    const int b = binOf(v);
    std::size_t i = 0;
    while (i + 1 < peaks.size() && b >= cuts[i + 1]) {
      ++i;
    }
    return i;
  };
  std::vector<BandSurface> parts(peaks.size());
  std::vector<std::vector<float>> zs(peaks.size());
  for (const cv::Point& q : s.pixels) {
    const glm::vec2 v(q.x, q.y);
    const std::size_t i = branchOf(v);
    BandSurface& part = parts[i];
    const float r = glm::length(v - centre);
    ++part.size;
    part.low = std::min(part.low, r);
    if (r > part.reach) {
      part.reach = r;
      part.end = q;
    }
    part.pixels.push_back(q);
    zs[i].push_back(c.depth.at<float>(q));
  }
  for (const glm::vec2& t : s.tipsOn) {
    parts[branchOf(t)].claimed = true;
  }
  std::vector<BandSurface> kept;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    if (parts[i].size > 0) {
      std::nth_element(zs[i].begin(), zs[i].begin() + static_cast<std::ptrdiff_t>(zs[i].size() / 2),
                       zs[i].end());
      parts[i].depthMetres = zs[i][zs[i].size() / 2];
      kept.push_back(std::move(parts[i]));
    }
  }
  return kept;
}

/** Contour points on either side over which a free tip's distance signal is highest (freeTip). */
constexpr int kTipPeakPoints = 3;

/**
 * Whether the outline turns back at `end`: the raw distance signal peaks (is highest within kTipPeakPoints
 * on either side) at the contour point nearest to it (within 4 px) or at one of the two on either side. Along
 * a blade's side the distance rises towards its tip, where a jag of a jittered edge or a pixel lost to a
 * dropout can leave a surface's farthest pixel.
 */
bool outlineTurns(const Cluster& cluster, const cv::Point& end) {
  const int n = static_cast<int>(cluster.contour.size());
  int nearest = -1;
  float nearestDistance = 4.0f;
  for (int i = 0; i < n; ++i) {
    const float d = glm::length(cluster.contour[static_cast<std::size_t>(i)] - glm::vec2(end.x, end.y));
    if (d < nearestDistance) {
      nearestDistance = d;
      nearest = i;
    }
  }
  if (nearest < 0) {
    return false;
  }
  const auto signal = [&](int i) { return cluster.signal[static_cast<std::size_t>(((i % n) + n) % n)]; };
  for (int j = nearest - 2; j <= nearest + 2; ++j) {
    bool peak = true;
    for (int k = -kTipPeakPoints; k <= kTipPeakPoints && peak; ++k) {
      peak = signal(j + k) <= signal(j) + 0.01f;
    }
    if (peak) {
      return true;
    }
  }
  return false;
}

/**
 * Whether the far end of `s` is a blade's tip: the outline of `cluster` turns back at it (outlineTurns), the
 * cluster ends beyond it, not the frame (or the region of interest), and nothing nearer cuts it off.
 */
bool freeTip(const Context& c, const Cluster& cluster, const cv::Mat& clusterMask, const BandSurface& s) {
  if (!outlineTurns(cluster, s.end)) {
    return false;
  }
  const glm::vec2 centre = cluster.centre;
  const std::array<int, 4> roi = c.options.roi != std::array<int, 4>{0, 0, 0, 0}
                                     ? c.options.roi
                                     : std::array<int, 4>{0, 0, c.frame.width, c.frame.height};
  if (s.end.x <= roi[0] + 2 || s.end.y <= roi[1] + 2 || s.end.x >= roi[2] - 3 || s.end.y >= roi[3] - 3) {
    return false;
  }
  const glm::vec2 end(static_cast<float>(s.end.x), static_cast<float>(s.end.y));
  if (glm::length(end - centre) < 1.0f) {
    return false;
  }
  const glm::vec2 out = glm::normalize(end - centre);
  // Over ±30° (a ray straight out misses a thin blade that runs on past a break in its depth).
  for (const float degrees : {0.0f, -15.0f, 15.0f, -30.0f, 30.0f}) {
    const float a = degrees * 3.14159265f / 180.0f;
    const glm::vec2 dir(out.x * std::cos(a) - out.y * std::sin(a), out.x * std::sin(a) + out.y * std::cos(a));
    for (int k = 3; k <= kTipClearancePx; ++k) {
      if (insideMask(clusterMask, end + dir * static_cast<float>(k))) {
        return false;
      }
    }
  }
  const float z = c.depth.at<float>(s.end);
  const float step = layerStepMetres(z, 0.0f);
  for (int dy = -kTipOccluderReachPx; dy <= kTipOccluderReachPx; ++dy) {
    for (int dx = -kTipOccluderReachPx; dx <= kTipOccluderReachPx; ++dx) {
      const int x = s.end.x + dx;
      const int y = s.end.y + dy;
      if ((dx == 0 && dy == 0) || x < 0 || y < 0 || x >= c.depth.cols || y >= c.depth.rows ||
          glm::dot(glm::normalize(glm::vec2(dx, dy)), out) < kTipOccluderCone) {
        continue;
      }
      const float zq = c.depth.at<float>(y, x);
      if (inBladeRange(c, zq) && zq < z - step) {
        return false;
      }
    }
  }
  return true;
}

/**
 * The surfaces of a cluster's outer band: its own pixels with depth beyond `rCut` pixels from the centre,
 * linked as depthLayers links them, each of kTipSurfaceMinPx pixels or more split into its branches (one per
 * tip, `--notch-min` pixels above the dip between them); a branch on which a captured blade's tip (`tips`)
 * lies is claimed.
 */
std::vector<BandSurface> bandSurfaces(const Context& c, const cv::Mat& clusterMask, const glm::vec2& centre,
                                      float rCut, const std::vector<glm::vec2>& tips) {
  const cv::Rect box = cv::boundingRect(clusterMask);
  const int w = box.width;
  const int h = box.height;
  const auto at = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
  const auto radius = [&](int x, int y) { return glm::length(glm::vec2(x + box.x, y + box.y) - centre); };
  const cv::Mat depth = c.depth(box);
  std::vector<int> parent(static_cast<std::size_t>(w) * h, -1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (c.ownMask.at<std::uint8_t>(box.y + y, box.x + x) != 0 && inBladeRange(c, depth.at<float>(y, x)) &&
          radius(x, y) >= rCut) {
        parent[at(x, y)] = static_cast<int>(at(x, y));
      }
    }
  }
  const auto hasDepth = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < w && y < h && parent[at(x, y)] >= 0;
  };
  const auto find = [&](std::size_t i) { return findRoot(parent, i); };
  linkBoxSurfaces(depth, parent);
  std::vector<int> index(parent.size(), -1);
  std::vector<BandSurface> surfaces;
  std::vector<std::vector<float>> zs;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!hasDepth(x, y)) {
        continue;
      }
      int& k = index[find(at(x, y))];
      if (k < 0) {
        k = static_cast<int>(surfaces.size());
        surfaces.emplace_back();
        zs.emplace_back();
      }
      BandSurface& s = surfaces[static_cast<std::size_t>(k)];
      const float r = radius(x, y);
      ++s.size;
      s.low = std::min(s.low, r);
      if (r > s.reach) {
        s.reach = r;
        s.end = cv::Point(x + box.x, y + box.y);
      }
      s.pixels.emplace_back(x + box.x, y + box.y);
      zs[static_cast<std::size_t>(k)].push_back(depth.at<float>(y, x));
    }
  }
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    std::nth_element(zs[k].begin(), zs[k].begin() + static_cast<std::ptrdiff_t>(zs[k].size() / 2),
                     zs[k].end());
    surfaces[k].depthMetres = zs[k][zs[k].size() / 2];
  }
  // A tip lies on the surface of the band pixel nearest to it (within 4 px).
  for (const glm::vec2& t : tips) {
    float best = 5.0f;
    int which = -1;
    for (int dy = -4; dy <= 4; ++dy) {
      for (int dx = -4; dx <= 4; ++dx) {
        const int x = static_cast<int>(std::lround(t.x)) - box.x + dx;
        const int y = static_cast<int>(std::lround(t.y)) - box.y + dy;
        const float d = std::hypot(static_cast<float>(dx), static_cast<float>(dy));
        if (hasDepth(x, y) && d < best) {
          best = d;
          which = index[find(at(x, y))];
        }
      }
    }
    if (which >= 0) {
      surfaces[static_cast<std::size_t>(which)].claimed = true;
      surfaces[static_cast<std::size_t>(which)].tipsOn.push_back(t);
    }
  }
  // Two blades whose ends link into one surface: its branches, each a surface of its own.
  std::vector<BandSurface> split;
  for (const BandSurface& s : surfaces) {
    if (s.size >= kTipSurfaceMinPx) {
      for (BandSurface& branch : branches(c, s, centre, static_cast<float>(c.options.notchMinPx))) {
        split.push_back(std::move(branch));
      }
    }
  }
  return split;
}

/**
 * Fourth pass over a cluster's blades: blades whose neighbours hide all but their outer end, found by the
 * surface that end lies on. Over the cluster's outer band (beyond 1 − tipSurfacesOuterShare of the median
 * distance from the centre to the captured tips) its own pixels are linked into surfaces, split into their
 * branches (bandSurfaces); a branch of at least kTipSurfaceMinPx pixels, running at least half the minimum
 * blade length outwards, that no captured tip lies on or ends near, and whose far end is a free tip
 * (freeTip), is a blade: traced through radial bins
 * of its pixels (their mean, and their count over the bin as its visible width), then finished as any blade.
 * `--explain` lists each such blade with the captured split blades.
 */
void addTipSurfaces(Context& c, Partition& p, const cv::Mat& clusterMask, int clusterIndex) {
  const auto share = static_cast<float>(c.options.tipSurfacesOuterShare);
  if (share <= 0.0f || p.blades.empty()) {
    return;
  }
  const glm::vec2 centre = p.cluster.centre;
  std::vector<glm::vec2> tips;
  std::vector<float> tipRadii;
  for (const CapturedBlade& blade : p.blades) {
    tips.push_back(blade.outline[static_cast<std::size_t>(blade.tip)]);
    tipRadii.push_back(glm::length(tips.back() - centre));
  }
  std::nth_element(tipRadii.begin(), tipRadii.begin() + static_cast<std::ptrdiff_t>(tipRadii.size() / 2),
                   tipRadii.end());
  const float rCut = (1.0f - share) * tipRadii[tipRadii.size() / 2];
  const std::vector<BandSurface> surfaces = bandSurfaces(c, clusterMask, centre, rCut, tips);
  std::vector<CapturedBlade> added;
  for (const BandSurface& s : surfaces) {
    const glm::vec2 end(static_cast<float>(s.end.x), static_cast<float>(s.end.y));
    std::size_t host = 0;
    for (std::size_t b = 1; b < tips.size(); ++b) {
      host = glm::length(tips[b] - end) < glm::length(tips[host] - end) ? b : host;
    }
    const float gap = glm::length(tips[host] - end);
    if (s.claimed || s.size < kTipSurfaceMinPx ||
        s.reach - s.low < 0.5f * static_cast<float>(c.options.minBladeLengthPx) || gap < kTipSurfaceGapPx ||
        !freeTip(c, p.cluster, clusterMask, s)) {
      continue;
    }
    // The mean of the surface's pixels in each radial bin, out to its far end.
    const int bins = static_cast<int>((s.reach - s.low) / kTipSurfaceBinPx) + 1;
    std::vector<glm::vec2> sum(static_cast<std::size_t>(bins), glm::vec2(0.0f));
    std::vector<int> count(static_cast<std::size_t>(bins), 0);
    for (const cv::Point& q : s.pixels) {
      const glm::vec2 v(static_cast<float>(q.x), static_cast<float>(q.y));
      const auto k = static_cast<std::size_t>(
          std::min(bins - 1, static_cast<int>((glm::length(v - centre) - s.low) / kTipSurfaceBinPx)));
      sum[k] += v;
      ++count[k];
    }
    std::vector<glm::vec2> axis;
    std::vector<float> axisWidths;
    for (std::size_t k = 0; k < sum.size(); ++k) {
      if (count[k] > 0) {
        axis.push_back(sum[k] / static_cast<float>(count[k]));
        axisWidths.push_back(static_cast<float>(count[k]) / kTipSurfaceBinPx);
      }
    }
    axis.push_back(end);
    axisWidths.push_back(0.0f);
    if (axis.size() < 3) {
      continue;
    }
    std::vector<float> widths;
    std::vector<glm::vec2> line = smoothOpen(resample(axis, kMatchSamples, &axisWidths, &widths), 2.0, true);
    CapturedBlade blade;
    blade.cluster = clusterIndex;
    blade.outline = p.blades[host].outline;
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < blade.outline.size(); ++i) {
      nearest = glm::length(blade.outline[i] - end) < glm::length(blade.outline[nearest] - end) ? i : nearest;
    }
    blade.tip = static_cast<int>(nearest);
    blade.medialAxis = true;
    blade.sideRatio = p.blades[host].sideRatio;
    std::string reason;
    const float maxWidth = *std::max_element(widths.begin(), widths.end());
    if (finishBlade(c, p.cluster, clusterMask, std::move(line), std::move(widths), maxWidth, std::move(blade),
                    added, reason)) {
      p.cluster.split.push_back(fmt::format(
          "a surface at {:.3f} m ends in a free tip at ({}, {}), {:.0f} px from the nearest captured tip, "
          "where no blade ends: one blade more ({} px of it show in the cluster's outer {:.0f} %)",
          s.depthMetres, s.end.x, s.end.y, gap, s.size, 100.0f * share));
    }
  }
  for (CapturedBlade& blade : added) {
    p.blades.push_back(std::move(blade));
  }
  p.cluster.blades.resize(p.blades.size());
  std::iota(p.cluster.blades.begin(), p.cluster.blades.end(), 0);
}

/** The first knot of a blade beyond its extension to the centre (where it was seen). */
std::size_t firstSeenKnot(const CapturedBlade& blade) {
  float along = 0.0f;
  std::size_t k = 0;
  while (k + 1 < blade.skeletonPx.size() && along < blade.extensionPx) {
    along += glm::length(blade.skeletonPx[k + 1] - blade.skeletonPx[k]);
    ++k;
  }
  return k;
}

/**
 * Widens the samples of a blade's axis where one of its edges is the edge of a nearer surface (a blade in
 * front hides that side, so the visible width falls short; where it hides the blade across its whole width,
 * so that no depth of the blade's own lies on the axis, the sample is judged at the depth of the nearest
 * sample that has one): over each run of such samples the width is at
 * least what the samples on both sides of the run measure (interpolated; only the root's side of a run that
 * reaches the tip, as a blade narrows to its tip). `line` and `widths` are pixels, root end first. Returns
 * whether a width changed.
 */
bool widenOccluded(const Context& c, const cv::Mat& clusterMask, const std::vector<glm::vec2>& line,
                   std::vector<float>& widths) {
  const int count = static_cast<int>(line.size());
  std::vector<char> occluded(line.size(), 0);
  bool any = false;
  // The blade's own depth at each sample; a sample with none near it takes the nearest seen sample's.
  std::vector<float> seen(line.size(), 0.0f);
  for (int k = 0; k < count; ++k) {
    seen[static_cast<std::size_t>(k)] = depthAround(c, line[k], 1);
  }
  std::vector<float> own = seen;
  for (int k = 0; k < count; ++k) {
    if (own[static_cast<std::size_t>(k)] > 0.0f) {
      continue;
    }
    for (int d = 1; d < count; ++d) {
      if (k - d >= 0 && seen[static_cast<std::size_t>(k - d)] > 0.0f) {
        own[static_cast<std::size_t>(k)] = seen[static_cast<std::size_t>(k - d)];
        break;
      }
      if (k + d < count && seen[static_cast<std::size_t>(k + d)] > 0.0f) {
        own[static_cast<std::size_t>(k)] = seen[static_cast<std::size_t>(k + d)];
        break;
      }
    }
  }
  for (int k = 0; k < count; ++k) {
    const glm::vec2 t = line[std::min(k + 2, count - 1)] - line[std::max(k - 2, 0)];
    const float z = own[static_cast<std::size_t>(k)];
    if (glm::length(t) <= 0.0f || z <= 0.0f) {
      continue;
    }
    const float step = layerStepMetres(z, 0.0f);
    const glm::vec2 normal = glm::normalize(glm::vec2(-t.y, t.x));
    for (const float sign : {-1.0f, 1.0f}) {
      float d = 0.0f;
      while (d < 200.0f && insideMask(clusterMask, line[k] + normal * (sign * d))) {
        d += 0.5f;
      }
      // The first pixels beyond the edge: a nearer surface there hides this side.
      for (float e = 0.5f; e <= 2.0f; e += 0.5f) {
        const glm::vec2 q = line[k] + normal * (sign * (d + e));
        const int x = static_cast<int>(std::lround(q.x));
        const int y = static_cast<int>(std::lround(q.y));
        if (x < 0 || y < 0 || x >= c.depth.cols || y >= c.depth.rows) {
          break;
        }
        const float zq = c.depth.at<float>(y, x);
        if (inBladeRange(c, zq) && zq < z - step) {
          occluded[static_cast<std::size_t>(k)] = 1;
          any = true;
          break;
        }
      }
    }
  }
  if (!any) {
    return false;
  }
  bool changed = false;
  for (int k = 0; k < count;) {
    if (!occluded[static_cast<std::size_t>(k)]) {
      ++k;
      continue;
    }
    int end = k;
    while (end < count && occluded[static_cast<std::size_t>(end)]) {
      ++end;
    }
    if (end < count) {
      // Between the free samples on either side, or from the root up to the first free one.
      const float wb = widths[static_cast<std::size_t>(k > 0 ? k - 1 : end)];
      const float wa = widths[static_cast<std::size_t>(end)];
      for (int i = k; i < end; ++i) {
        const float u = static_cast<float>(i - k + 1) / static_cast<float>(end - k + 1);
        const float before = widths[static_cast<std::size_t>(i)];
        widths[static_cast<std::size_t>(i)] =
            std::max(widths[static_cast<std::size_t>(i)], wb + u * (wa - wb));
        changed = changed || widths[static_cast<std::size_t>(i)] != before;
      }
    }
    k = end;
  }
  return changed;
}

/** A scan across a blade stops at a farther surface this many pixels wide (its edge's jitter is narrower). */
constexpr float kFartherRunPx = 1.0f;
/** A blade takes its own surface's widths when they are narrower at its median knot by this ratio. */
constexpr float kSurfaceWidthRatio = 1.05f;

/**
 * Width across a blade at `at` (pixels; `normal` a unit vector across it) over its own depth surface: from
 * depth `z` (metres) outwards on both sides until the cluster's silhouette ends or a surface farther by more
 * than a layer step begins (the blade lies in front of it: there its edge is). A nearer surface hides the
 * blade and does not end it; pixels without depth do not either.
 */
float surfaceWidthAt(const Context& c, const cv::Mat& clusterMask, const glm::vec2& at,
                     const glm::vec2& normal, float z) {
  constexpr float kStep = 0.5f;
  const auto runSamples = static_cast<int>(kFartherRunPx / kStep) + 1;
  float across = 0.0f;
  for (const float sign : {-1.0f, 1.0f}) {
    float d = 0.0f;
    float zs = z;
    int farther = 0;
    while (d < 200.0f) {
      const glm::vec2 q = at + normal * (sign * (d + kStep));
      if (!insideMask(clusterMask, q)) {
        break;
      }
      const float zq =
          c.depth.at<float>(static_cast<int>(std::lround(q.y)), static_cast<int>(std::lround(q.x)));
      const float step = layerStepMetres(zs, 0.0f);
      if (inBladeRange(c, zq)) {
        if (zq - zs > step) {
          if (++farther >= runSamples) {
            d -= kStep * static_cast<float>(runSamples - 1);
            break;
          }
        } else {
          farther = 0;
          if (zq >= zs - step) {
            zs = zq; // follows the blade's own surface as it tilts
          }
        }
      }
      d += kStep;
    }
    across += d + 0.5f * kStep;
  }
  return across;
}

/**
 * Blades found on a medial axis (their outline did not pair into two edges of their own: a split of merged
 * blades, a depth part, a tip surface) measure their widths across a region that other blades may share: a
 * blade in front of its neighbour at nearly the same place measures as wide as both. Such a blade takes the
 * widths of its own depth surface (surfaceWidthAt) at its seen knots, when they are narrower at its median
 * knot by kSurfaceWidthRatio or more (sporadic cuts by a neighbour's jittered edge are not a merge).
 */
void surfaceWidths(Context& c, Partition& p, const cv::Mat& clusterMask) {
  for (CapturedBlade& blade : p.blades) {
    if (!blade.medialAxis) {
      continue;
    }
    const int count = static_cast<int>(blade.skeletonPx.size());
    std::vector<float> surface(blade.widthsPx.size(), 0.0f);
    std::vector<float> ratios;
    for (int k = static_cast<int>(firstSeenKnot(blade)); k + 1 < count; ++k) {
      const glm::vec2 at = blade.skeletonPx[static_cast<std::size_t>(k)];
      const float z = depthAround(c, at, 1);
      const glm::vec2 t = blade.skeletonPx[static_cast<std::size_t>(std::min(k + 2, count - 1))] -
                          blade.skeletonPx[static_cast<std::size_t>(std::max(k - 2, 0))];
      if (z <= 0.0f || glm::length(t) <= 0.0f) {
        continue;
      }
      const float across = surfaceWidthAt(c, clusterMask, at, glm::normalize(glm::vec2(-t.y, t.x)), z);
      const float width = blade.widthsPx[static_cast<std::size_t>(k)];
      surface[static_cast<std::size_t>(k)] = std::min(across, width);
      ratios.push_back(across < width ? width / std::max(across, 0.5f) : 1.0f);
    }
    if (ratios.empty()) {
      continue;
    }
    std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2),
                     ratios.end());
    if (ratios[ratios.size() / 2] < kSurfaceWidthRatio) {
      continue;
    }
    for (std::size_t k = 0; k < surface.size(); ++k) {
      if (surface[k] > 0.0f) {
        blade.widthsPx[k] = surface[k];
      }
    }
    toMetres(c, blade);
  }
}

/** The Gaussian after the running median of a blade's widths: sigma as this share of the median's
 * half-window. */
constexpr double kWidthSmoothShare = 0.3;

/**
 * A running median of `values` over ±`half` samples; near the ends the window shrinks to stay centred, so the
 * first and last values stay.
 */
std::vector<float> runningMedian(const std::vector<float>& values, int half) {
  std::vector<float> out = values;
  const int n = static_cast<int>(values.size());
  std::vector<float> window;
  for (int k = 1; k + 1 < n; ++k) {
    const int r = std::min({half, k, n - 1 - k});
    window.assign(values.begin() + (k - r), values.begin() + (k + r + 1));
    std::nth_element(window.begin(), window.begin() + r, window.end());
    out[static_cast<std::size_t>(k)] = window[static_cast<std::size_t>(r)];
  }
  return out;
}

/** Coverage (IoU) a partition with fewer blades may lose and still win over one with more. */
constexpr double kCoverageMargin = 0.04;

/** A blade this many times as wide as its cluster's median blade is probably several merged. */
/** Notes the blades of a partition that are probably merged (Cluster::merged). */
void flagMerges(Partition& p) {
  if (p.blades.size() < 3) {
    return;
  }
  std::vector<float> widths;
  for (const CapturedBlade& blade : p.blades) {
    widths.push_back(*std::max_element(blade.widthsPx.begin(), blade.widthsPx.end()));
  }
  std::vector<float> sorted = widths;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                   sorted.end());
  const float median = sorted[sorted.size() / 2];
  for (std::size_t b = 0; b < widths.size(); ++b) {
    if (median > 0.0f && widths[b] > kMergedWidthRatio * median) {
      p.cluster.merged.push_back(fmt::format(
          "the blade with its tip at ({:.0f}, {:.0f}) is {:.1f}× as wide as the cluster's median blade "
          "({:.0f} "
          "against {:.0f} px): probably blades merged where the outline shows no junction between them and "
          "depth no step",
          p.blades[b].outline[static_cast<std::size_t>(p.blades[b].tip)].x,
          p.blades[b].outline[static_cast<std::size_t>(p.blades[b].tip)].y, widths[b] / median, widths[b],
          median));
    }
  }
}

/**
 * Partitions one cluster: `clusterMask` is its silhouette (its outer contour is `contourPts`), `ownMask` the
 * pixels whose depth is its own (the silhouette less what nearer layers hide).
 */
void processCluster(Context& c, const std::vector<cv::Point>& contourPts, const cv::Mat& clusterMask,
                    const cv::Mat& ownMask) {
  const int clusterIndex = static_cast<int>(c.result.clusters.size());
  c.ownMask = ownMask;
  cv::distanceTransform(clusterMask, c.clusterDist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const std::vector<CentreCandidate> candidates = centreCandidates(c, clusterMask, contourPts);
  std::optional<Partition> best;
  for (const CentreCandidate& candidate : candidates) {
    Partition p = partition(c, contourPts, clusterMask, candidate, clusterIndex);
    if (candidates.size() > 1) {
      // Auto: the centre whose blades reproduce the silhouette best wins (false splits and missed junctions
      // both cost overlap).
      const std::vector<std::uint8_t> raster = rasteriseBlades(p.blades, clusterMask.cols, clusterMask.rows);
      std::size_t inter = 0;
      std::size_t uni = 0;
      for (std::size_t i = 0; i < raster.size(); ++i) {
        const bool a = raster[i] != 0;
        const bool b = clusterMask.data[i] != 0;
        inter += (a && b) ? 1 : 0;
        uni += (a || b) ? 1 : 0;
      }
      p.coverage = uni > 0 ? static_cast<double>(inter) / static_cast<double>(uni) : 0.0;
    }
    // Within a small margin of coverage the partition with fewer blades wins: a lone blade cut at its middle
    // into two halves covers it as well as the blade does from its root.
    double needed = 1e-4;
    if (best && !p.blades.empty() && p.blades.size() != best->blades.size()) {
      needed =
          p.blades.size() < best->blades.size() || best->blades.empty() ? -kCoverageMargin : kCoverageMargin;
    }
    if (!best || p.coverage > best->coverage + needed) {
      best = std::move(p);
    }
  }
  if (!best || best->blades.empty()) {
    const cv::Moments m = cv::moments(clusterMask, true);
    const glm::vec2 at = m.m00 > 0 ? glm::vec2(m.m10 / m.m00, m.m01 / m.m00) : glm::vec2(0.0f);
    c.result.warnings.push_back(
        fmt::format("{}: cluster at ({:.0f}, {:.0f}) has no usable centre: no centre tried "
                    "({}) splits it into blades",
                    c.frame.label(), at.x, at.y, candidates.size()));
    if (best) {
      c.result.warnings.insert(c.result.warnings.end(), best->warnings.begin(), best->warnings.end());
      c.result.clusters.push_back(std::move(best->cluster));
    }
    return;
  }
  Partition& p = *best;
  if (c.options.depthSplit) {
    splitByDepth(c, p, clusterMask, clusterIndex);
    addTipSurfaces(c, p, clusterMask, clusterIndex);
  }
  if (c.options.surfaceWidths) {
    surfaceWidths(c, p, clusterMask);
  }
  flagMerges(p); // on the widths each blade's own surface gives
  for (CapturedBlade& blade : p.blades) {
    // The captured part only: the extension to the centre is drawn, not seen.
    const std::size_t first = firstSeenKnot(blade);
    const std::vector<glm::vec2> line(blade.skeletonPx.begin() + static_cast<std::ptrdiff_t>(first),
                                      blade.skeletonPx.end());
    std::vector<float> widths(blade.widthsPx.begin() + static_cast<std::ptrdiff_t>(first),
                              blade.widthsPx.end());
    bool changed = c.options.occludedWidths && widenOccluded(c, clusterMask, line, widths);
    if (c.options.widthSmoothKnots > 0.0 && widths.size() > 2) {
      // A sensor's edges jitter from knot to knot; the median keeps a lobe's rise and fall, the Gaussian
      // rounds its plateaus. Ends pinned: the first seen knot meets the extension, the tip stays 0.
      const double half = c.options.widthSmoothKnots * c.options.knots / 128.0;
      widths = smoothOpen(runningMedian(widths, static_cast<int>(std::lround(half))),
                          kWidthSmoothShare * half, true);
      changed = true;
    }
    if (changed) {
      std::copy(widths.begin(), widths.end(), blade.widthsPx.begin() + static_cast<std::ptrdiff_t>(first));
      toMetres(c, blade);
    }
  }
  p.cluster.layer = c.layer;
  p.cluster.layerCount = c.layerCount;
  p.cluster.layerDepthMetres = c.layerDepthMetres;
  const int offset = static_cast<int>(c.result.blades.size());
  for (int& index : p.cluster.blades) {
    index += offset;
  }
  for (CapturedBlade& blade : p.blades) {
    c.result.blades.push_back(std::move(blade));
  }
  c.result.warnings.insert(c.result.warnings.end(), p.warnings.begin(), p.warnings.end());
  c.result.clusters.push_back(std::move(p.cluster));
}

/**
 * Indices of the contours enclosing at least minArea pixels (and of 8 points or more), largest first, so
 * that blade order is stable and meaningful; the others go to `small` when given.
 */
std::vector<std::size_t> largestFirst(const std::vector<std::vector<cv::Point>>& contours, double minArea,
                                      std::vector<std::size_t>* small = nullptr) {
  std::vector<std::pair<double, std::size_t>> order;
  for (std::size_t k = 0; k < contours.size(); ++k) {
    const double area = cv::contourArea(contours[k]);
    if (area >= minArea && contours[k].size() >= 8) {
      order.emplace_back(-area, k);
    } else if (small != nullptr) {
      small->push_back(k);
    }
  }
  std::sort(order.begin(), order.end());
  std::vector<std::size_t> out;
  for (const auto& entry : order) {
    out.push_back(entry.second);
  }
  return out;
}

/** Partitions each part of `mask` (its outer contours of at least minArea pixels), largest first. */
void processParts(Context& c, const cv::Mat& mask, const cv::Mat& own, int minArea) {
  std::vector<std::vector<cv::Point>> parts;
  cv::findContours(mask.clone(), parts, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  std::vector<std::size_t> small;
  const std::vector<std::size_t> order = largestFirst(parts, minArea, &small);
  for (const std::size_t k : small) {
    const cv::Rect r = cv::boundingRect(parts[k]);
    // The pixels it holds (a part one or two pixels thin encloses no area within its outline).
    cv::Mat filled = cv::Mat::zeros(r.size(), CV_8U);
    cv::drawContours(filled, parts, static_cast<int>(k), cv::Scalar(255), cv::FILLED, cv::LINE_8,
                     cv::noArray(), INT_MAX, -r.tl());
    filled &= mask(r);
    const int pixels = cv::countNonZero(filled);
    c.result.droppedParts.push_back(fmt::format(
        "depth layer {} of {} ({:.3f} m): a part of {} pixel{} at ({}, {}), its outline enclosing {:.0f} "
        "px², below the {} px² a part needs",
        c.layer, c.layerCount, c.layerDepthMetres, pixels, pixels == 1 ? "" : "s", r.x + r.width / 2,
        r.y + r.height / 2, cv::contourArea(parts[k]), minArea));
  }
  for (const std::size_t k : order) {
    cv::Mat partMask = cv::Mat::zeros(mask.size(), CV_8U);
    cv::drawContours(partMask, parts, static_cast<int>(k), cv::Scalar(255), cv::FILLED);
    partMask &= mask;
    processCluster(c, parts[k], partMask, partMask & own);
  }
}

/** Direction of a polyline from its point `from` towards its point `to` (indices), unit. */
glm::vec2 directionAlong(const std::vector<glm::vec2>& line, std::size_t from, std::size_t to) {
  const glm::vec2 d = line[to] - line[from];
  return glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec2(0.0f);
}

/** A broken-off piece joins a blade whose tip is within this many of their widths of the piece's base. */
constexpr float kJoinGapWidths = 4.0f;
/** ...and lies at most this many widths to the side of the line the blade's tip points along. */
constexpr float kJoinSideWidths = 2.0f;
/** ...and runs on within this angle of the blade's direction (cosine). */
constexpr float kJoinCos = 0.9f;

/**
 * Joins `piece` (seen from its knot `from` on) onto the end of `blade`: the blade's knots without the last
 * tenth (where the occluder cuts it, its width falls to nothing), then the piece's, resampled to the same
 * count by arc length in the picture. The joined blade keeps the blade's cluster and extension and takes the
 * piece's outline and tip.
 */
void joinPiece(CapturedBlade& blade, const CapturedBlade& piece, std::size_t from) {
  const std::size_t count = blade.skeletonPx.size();
  const std::size_t keep = std::max<std::size_t>(2, count - count / 10);
  std::vector<glm::vec2> px(blade.skeletonPx.begin(), blade.skeletonPx.begin() + keep);
  std::vector<float> wPx(blade.widthsPx.begin(), blade.widthsPx.begin() + keep);
  std::vector<glm::vec3> knots(blade.knots.begin(), blade.knots.begin() + keep);
  std::vector<float> w(blade.widths.begin(), blade.widths.begin() + keep);
  std::vector<glm::vec3> sides(blade.sides.begin(), blade.sides.begin() + keep);
  for (std::size_t k = from; k < piece.skeletonPx.size(); ++k) {
    px.push_back(piece.skeletonPx[k]);
    wPx.push_back(piece.widthsPx[k]);
    knots.push_back(piece.knots[k]);
    w.push_back(piece.widths[k]);
    sides.push_back(piece.sides[k]);
  }
  std::vector<float> arc(px.size(), 0.0f);
  for (std::size_t k = 1; k < px.size(); ++k) {
    arc[k] = arc[k - 1] + glm::length(px[k] - px[k - 1]);
  }
  std::size_t j = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const float target = arc.back() * static_cast<float>(i) / static_cast<float>(count - 1);
    while (j + 2 < px.size() && arc[j + 1] < target) {
      ++j;
    }
    const float seg = arc[j + 1] - arc[j];
    const float t = seg > 0.0f ? std::clamp((target - arc[j]) / seg, 0.0f, 1.0f) : 0.0f;
    blade.skeletonPx[i] = glm::mix(px[j], px[j + 1], t);
    blade.widthsPx[i] = glm::mix(wPx[j], wPx[j + 1], t);
    blade.knots[i] = glm::mix(knots[j], knots[j + 1], t);
    blade.widths[i] = glm::mix(w[j], w[j + 1], t);
    const glm::vec3 side = glm::mix(sides[j], sides[j + 1], t);
    blade.sides[i] = glm::length(side) > 0.0f ? glm::normalize(side) : sides[j];
  }
  blade.widthsPx.back() = 0.0f;
  blade.widths.back() = 0.0f;
  blade.lengthPx = polylineLength(blade.skeletonPx);
  blade.lengthMetres = 0.0f;
  for (std::size_t i = 1; i < count; ++i) {
    blade.lengthMetres += glm::length(blade.knots[i] - blade.knots[i - 1]);
  }
  blade.outline = piece.outline;
  blade.tip = piece.tip;
  blade.medialAxis = blade.medialAxis || piece.medialAxis;
  blade.touchesBorder = blade.touchesBorder || piece.touchesBorder;
}

/**
 * Joins the blades of one blob's depth layers (its clusters from `firstCluster` on) that a nearer blade
 * broke in two. Where a nearer blade crosses a farther one at a shallow angle, the straight runs across it
 * (at most kMaxOccluderRunPx) do not reach the far side, and the farther blade's outer part becomes a depth
 * layer of its own with one blade. Such a piece joins the blade whose tip points at its base: directions
 * within kJoinCos, the base ahead of the tip, at most kJoinGapWidths of their widths from it and
 * kJoinSideWidths to the side, and the depths of tip and base within a layer step. `--explain` lists each.
 */
void joinBrokenBlades(Context& c, std::size_t firstCluster) {
  ExtractResult& r = c.result;
  std::vector<bool> removed(r.blades.size(), false);
  for (std::size_t ci = firstCluster; ci < r.clusters.size(); ++ci) {
    Cluster& cluster = r.clusters[ci];
    if (cluster.blades.size() != 1 || cluster.layerCount < 2) {
      continue;
    }
    const std::size_t pi = static_cast<std::size_t>(cluster.blades.front());
    const CapturedBlade& piece = r.blades[pi];
    const std::size_t n = piece.skeletonPx.size();
    const std::size_t from = firstSeenKnot(piece);
    if (removed[pi] || n < 16 || from + 8 >= n || piece.knots.size() != n) {
      continue;
    }
    const glm::vec2 base = piece.skeletonPx[from];
    const glm::vec2 dir = directionAlong(piece.skeletonPx, from, from + 8);
    const float z = piece.knots[from].z;
    int best = -1;
    float bestGap = 0.0f;
    for (std::size_t bi = 0; bi < r.blades.size(); ++bi) {
      const CapturedBlade& blade = r.blades[bi];
      const std::size_t m = blade.skeletonPx.size();
      if (bi == pi || removed[bi] || blade.cluster < static_cast<int>(firstCluster) ||
          blade.cluster == static_cast<int>(ci) || m < 16 || blade.knots.size() != m) {
        continue;
      }
      const glm::vec2 tip = blade.skeletonPx.back();
      const glm::vec2 tipDir = directionAlong(blade.skeletonPx, m - 9, m - 1);
      const glm::vec2 gap = base - tip;
      const float width = std::max(maxWidthPx(blade), maxWidthPx(piece));
      const float ahead = glm::dot(gap, tipDir);
      const float aside = std::abs(tipDir.x * gap.y - tipDir.y * gap.x);
      if (glm::dot(dir, tipDir) < kJoinCos || ahead <= 0.0f || glm::length(gap) > kJoinGapWidths * width ||
          aside > kJoinSideWidths * width || std::abs(blade.knots.back().z - z) > layerStepMetres(z, 0.0f)) {
        continue;
      }
      if (best < 0 || glm::length(gap) < bestGap) {
        best = static_cast<int>(bi);
        bestGap = glm::length(gap);
      }
    }
    if (best < 0) {
      continue;
    }
    CapturedBlade& blade = r.blades[static_cast<std::size_t>(best)];
    const glm::vec2 tip = blade.skeletonPx.back();
    cluster.joined.push_back(fmt::format(
        "the blade with its tip at ({:.0f}, {:.0f}) broke off where a nearer blade crosses it: joined to the "
        "blade that ends {:.0f} px before its base, at ({:.0f}, {:.0f})",
        piece.outline[static_cast<std::size_t>(piece.tip)].x,
        piece.outline[static_cast<std::size_t>(piece.tip)].y, bestGap, tip.x, tip.y));
    joinPiece(blade, piece, from);
    removed[pi] = true;
  }
  if (std::find(removed.begin(), removed.end(), true) == removed.end()) {
    return;
  }
  // Drop the joined pieces and renumber the clusters' blades.
  std::vector<int> index(r.blades.size(), -1);
  std::vector<CapturedBlade> kept;
  for (std::size_t b = 0; b < r.blades.size(); ++b) {
    if (!removed[b]) {
      index[b] = static_cast<int>(kept.size());
      kept.push_back(std::move(r.blades[b]));
    }
  }
  r.blades = std::move(kept);
  for (Cluster& cluster : r.clusters) {
    std::vector<int> blades;
    for (const int b : cluster.blades) {
      if (index[static_cast<std::size_t>(b)] >= 0) {
        blades.push_back(index[static_cast<std::size_t>(b)]);
      }
    }
    cluster.blades = std::move(blades);
  }
}

} // namespace

ExtractResult extractBlades(const DepthFrame& frame, const ExtractOptions& options) {
  validate(options);
  if (frame.width <= 0 || frame.height <= 0 ||
      frame.depth.size() != static_cast<std::size_t>(frame.width) * frame.height) {
    fail("{}: empty depth frame", frame.label());
  }
  ExtractResult result;
  result.width = frame.width;
  result.height = frame.height;
  Context c{frame, options, result, {}, {}, {}};
  buildMask(c);
  if (cv::countNonZero(c.mask) == 0) {
    return result;
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(c.mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const std::vector<std::size_t> order = largestFirst(contours, options.minClusterAreaPx);
  if (order.empty()) {
    result.warnings.push_back(fmt::format("{}: no contour: no blob of at least {} pixels in the mask",
                                          frame.label(), options.minClusterAreaPx));
    return result;
  }
  for (const std::size_t i : order) {
    cv::Mat clusterMask = cv::Mat::zeros(c.mask.size(), CV_8U);
    cv::drawContours(clusterMask, contours, static_cast<int>(i), cv::Scalar(255), cv::FILLED);
    clusterMask &= c.mask;
    const int layerArea = minLayerArea(options, cv::countNonZero(clusterMask));
    const std::vector<DepthLayer> layers = depthLayers(c, clusterMask, layerArea);
    if (layers.empty()) {
      processCluster(c, contours[i], clusterMask, c.mask);
      continue;
    }
    // Each depth layer is partitioned on its own.
    c.layerCount = static_cast<int>(layers.size());
    const std::size_t firstCluster = result.clusters.size();
    for (std::size_t l = 0; l < layers.size(); ++l) {
      c.layer = static_cast<int>(l);
      c.layerDepthMetres = layers[l].depthMetres;
      processParts(c, layers[l].completed, layers[l].own, layerArea);
    }
    if (options.joinBroken) {
      joinBrokenBlades(c, firstCluster);
    }
    c.layer = -1;
    c.layerCount = 1;
    c.layerDepthMetres = 0.0f;
  }
  return result;
}

void setExtractionThreads(int threads) {
  cv::setNumThreads(threads > 0 ? threads : -1);
}

std::vector<std::uint8_t> rasteriseBlades(const std::vector<CapturedBlade>& blades, int width, int height) {
  cv::Mat mask = cv::Mat::zeros(height, width, CV_8U);
  for (const CapturedBlade& blade : blades) {
    const std::size_t n = blade.skeletonPx.size();
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const glm::vec2 a = blade.skeletonPx[k];
      const glm::vec2 b = blade.skeletonPx[k + 1];
      const glm::vec2 t = b - a;
      if (glm::length(t) <= 0.0f) {
        continue;
      }
      const glm::vec2 s = glm::normalize(glm::vec2(-t.y, t.x));
      const float wa = 0.5f * blade.widthsPx[k];
      const float wb = 0.5f * blade.widthsPx[k + 1];
      // Pixels whose centre lies inside the quad (the sampling the truth and the sensor use).
      const glm::vec2 quad[4] = {a + s * wa, b + s * wb, b - s * wb, a - s * wa};
      const int x0 =
          std::max(0, static_cast<int>(std::floor(std::min({quad[0].x, quad[1].x, quad[2].x, quad[3].x}))));
      const int x1 = std::min(
          width - 1, static_cast<int>(std::ceil(std::max({quad[0].x, quad[1].x, quad[2].x, quad[3].x}))));
      const int y0 =
          std::max(0, static_cast<int>(std::floor(std::min({quad[0].y, quad[1].y, quad[2].y, quad[3].y}))));
      const int y1 = std::min(
          height - 1, static_cast<int>(std::ceil(std::max({quad[0].y, quad[1].y, quad[2].y, quad[3].y}))));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          const glm::vec2 p(static_cast<float>(x), static_cast<float>(y));
          int positive = 0;
          int negative = 0;
          for (int e = 0; e < 4; ++e) {
            const glm::vec2 u = quad[(e + 1) % 4] - quad[e];
            const glm::vec2 v = p - quad[e];
            const float cross = u.x * v.y - u.y * v.x;
            positive += cross >= 0.0f ? 1 : 0;
            negative += cross <= 0.0f ? 1 : 0;
          }
          if (positive == 4 || negative == 4) {
            mask.at<std::uint8_t>(y, x) = 255;
          }
        }
      }
    }
  }
  return {mask.datastart, mask.dataend};
}

} // namespace sylva::capture
