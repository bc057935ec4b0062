// Debug pictures of a capture: the overlay of every stage on the depth image, and the distance-signal plot.
#include <sylva/capture/Extract.hpp>

#include <sylva/core/Error.hpp>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::capture {
namespace {

/** A distinct colour per blade (golden-ratio hue steps), BGR. */
cv::Scalar bladeColour(int i) {
  const float h = std::fmod(0.1f + 0.618034f * static_cast<float>(i), 1.0f) * 6.0f;
  const float x = 1.0f - std::abs(std::fmod(h, 2.0f) - 1.0f);
  float r = 0.0f;
  float g = 0.0f;
  float b = 0.0f;
  switch (static_cast<int>(h)) {
  case 0:
    r = 1;
    g = x;
    break;
  case 1:
    r = x;
    g = 1;
    break;
  case 2:
    g = 1;
    b = x;
    break;
  case 3:
    g = x;
    b = 1;
    break;
  case 4:
    r = x;
    b = 1;
    break;
  default:
    r = 1;
    b = x;
    break;
  }
  return {40 + 215 * b, 40 + 215 * g, 40 + 215 * r};
}

Image toImage(const cv::Mat& bgr) {
  Image out(bgr.cols, bgr.rows, 3, PixelType::U8);
  auto values = out.values<std::uint8_t>();
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      const std::size_t i = (static_cast<std::size_t>(y) * bgr.cols + x) * 3;
      values[i + 0] = p[2];
      values[i + 1] = p[1];
      values[i + 2] = p[0];
    }
  }
  return out;
}

} // namespace

Image overlayImage(const DepthFrame& frame, const ExtractResult& result, const std::string& captionText) {
  if (frame.width <= 0 || frame.height <= 0 || result.width != frame.width || result.height != frame.height) {
    fail("{}: overlay: the capture result does not belong to this frame", frame.label());
  }
  const int scale = std::max(1, (640 + frame.width - 1) / frame.width);
  const auto range = depthRange(frame);
  const float nearM = result.nearMetres > 0.0f ? result.nearMetres : range.first;
  const float farM =
      std::max(result.farMetres > 0.0f ? result.farMetres * 1.3f : range.second, nearM + 1e-3f);
  const Image grey = depthPreview(frame, nearM, farM);
  cv::Mat base(frame.height, frame.width, CV_8UC3);
  for (int y = 0; y < frame.height; ++y) {
    for (int x = 0; x < frame.width; ++x) {
      const auto v = static_cast<std::uint8_t>(std::lround(grey.get(x, y, 0) * 200.0f));
      cv::Vec3b p(v, v, v);
      if (!result.mask.empty() && result.mask[static_cast<std::size_t>(y) * frame.width + x]) {
        p = cv::Vec3b(static_cast<std::uint8_t>(p[0] * 0.6), static_cast<std::uint8_t>(p[1] * 0.6 + 70),
                      static_cast<std::uint8_t>(p[2] * 0.6 + 20));
      }
      base.at<cv::Vec3b>(y, x) = p;
    }
  }
  cv::Mat img;
  cv::resize(base, img, {frame.width * scale, frame.height * scale}, 0, 0, cv::INTER_NEAREST);
  const float s = static_cast<float>(scale);
  auto pt = [&](const glm::vec2& p) {
    return cv::Point(static_cast<int>(std::lround((p.x + 0.5f) * s * 16.0f - 8.0f)),
                     static_cast<int>(std::lround((p.y + 0.5f) * s * 16.0f - 8.0f)));
  };
  const int thick = std::max(1, scale / 2 + (frame.width > 900 ? 1 : 0));
  for (const Cluster& cluster : result.clusters) {
    std::vector<cv::Point> poly;
    for (const glm::vec2& p : cluster.contour) {
      poly.push_back(pt(p));
    }
    if (!poly.empty()) {
      cv::polylines(img, std::vector<std::vector<cv::Point>>{poly}, true, {0, 220, 255}, thick, cv::LINE_AA,
                    4);
    }
  }
  for (std::size_t b = 0; b < result.blades.size(); ++b) {
    const CapturedBlade& blade = result.blades[b];
    const cv::Scalar colour = bladeColour(static_cast<int>(b));
    const std::size_t n = blade.skeletonPx.size();
    // Width ticks: the blade's cross-section every few knots.
    const std::size_t step = std::max<std::size_t>(1, n / 24);
    for (std::size_t k = 0; k < n; k += step) {
      const glm::vec2 t = blade.skeletonPx[std::min(k + 1, n - 1)] - blade.skeletonPx[k > 0 ? k - 1 : 0];
      if (glm::length(t) <= 0.0f) {
        continue;
      }
      const glm::vec2 side = glm::normalize(glm::vec2(-t.y, t.x)) * (0.5f * blade.widthsPx[k]);
      cv::line(img, pt(blade.skeletonPx[k] - side), pt(blade.skeletonPx[k] + side), colour * 0.8, 1,
               cv::LINE_AA, 4);
    }
    std::vector<cv::Point> line;
    for (const glm::vec2& p : blade.skeletonPx) {
      line.push_back(pt(p));
    }
    cv::polylines(img, std::vector<std::vector<cv::Point>>{line}, false, colour, thick + 1, cv::LINE_AA, 4);
    if (n > 0) {
      const glm::vec2 tip = blade.skeletonPx.back();
      const std::string text = fmt::format("{}{}", b, blade.medialAxis ? "m" : "");
      const cv::Point at(static_cast<int>((tip.x + 4.0f) * s), static_cast<int>((tip.y - 4.0f) * s));
      cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45 * std::max(1.0, s * 0.75), {0, 0, 0}, 3,
                  cv::LINE_AA);
      cv::putText(img, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45 * std::max(1.0, s * 0.75), colour, 1,
                  cv::LINE_AA);
    }
  }
  for (const Cluster& cluster : result.clusters) {
    for (const Junction& j : cluster.junctions) {
      cv::circle(img, pt(j.px), static_cast<int>(4 * s * 16), {255, 0, 255}, thick + 1, cv::LINE_AA, 4);
    }
    const cv::Point c = pt(cluster.centre);
    const int r = static_cast<int>(7 * s * 16);
    cv::line(img, c - cv::Point(r, 0), c + cv::Point(r, 0), {0, 0, 255}, thick + 1, cv::LINE_AA, 4);
    cv::line(img, c - cv::Point(0, r), c + cv::Point(0, r), {0, 0, 255}, thick + 1, cv::LINE_AA, 4);
  }
  const std::string caption =
      !captionText.empty()
          ? captionText
          : fmt::format("{}: {} blade{} in {} cluster{}, depth {:.3f}-{:.3f} m{}", frame.label(),
                        result.blades.size(), result.blades.size() == 1 ? "" : "s", result.clusters.size(),
                        result.clusters.size() == 1 ? "" : "s", result.nearMetres, result.farMetres,
                        result.colourRefined ? ", colour-refined" : "");
  const double fontScale = 0.5 * std::max(1.0, img.cols / 900.0);
  cv::rectangle(img, {0, 0}, {img.cols, static_cast<int>(26 * fontScale / 0.5)}, {0, 0, 0}, cv::FILLED);
  cv::putText(img, caption, {8, static_cast<int>(18 * fontScale / 0.5)}, cv::FONT_HERSHEY_SIMPLEX, fontScale,
              {255, 255, 255}, 1, cv::LINE_AA);
  return toImage(img);
}

Image signalPlot(const Cluster& cluster, int width, int height) {
  if (width < 64 || height < 48 || width > 8192 || height > 8192) {
    fail("signal plot: size {}x{} outside 64x48..8192x8192", width, height);
  }
  cv::Mat img(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int n = static_cast<int>(cluster.signal.size());
  if (n < 2) {
    return toImage(img);
  }
  const float maxV = std::max(*std::max_element(cluster.signal.begin(), cluster.signal.end()), 1.0f);
  const int left = 40;
  const int bottom = height - 20;
  const int top = 10;
  auto px = [&](int i, float v) {
    return cv::Point(left + static_cast<int>(static_cast<double>(i) * (width - left - 10) / (n - 1)),
                     bottom - static_cast<int>(v / maxV * static_cast<float>(bottom - top)));
  };
  cv::line(img, {left, bottom}, {width - 10, bottom}, {0, 0, 0}, 1);
  cv::line(img, {left, bottom}, {left, top}, {0, 0, 0}, 1);
  cv::putText(img, fmt::format("{:.0f} px", maxV), {2, top + 10}, cv::FONT_HERSHEY_SIMPLEX, 0.35, {0, 0, 0},
              1, cv::LINE_AA);
  cv::putText(img, "contour index", {width / 2 - 40, height - 5}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0}, 1,
              cv::LINE_AA);
  std::vector<cv::Point> raw;
  std::vector<cv::Point> smooth;
  for (int i = 0; i < n; ++i) {
    raw.push_back(px(i, cluster.signal[i]));
    smooth.push_back(px(i, cluster.smoothed[i]));
  }
  cv::polylines(img, std::vector<std::vector<cv::Point>>{raw}, false, {180, 180, 180}, 1, cv::LINE_AA);
  cv::polylines(img, std::vector<std::vector<cv::Point>>{smooth}, false, {200, 80, 0}, 2, cv::LINE_AA);
  for (const Junction& j : cluster.junctions) {
    const cv::Point p = px(j.index, j.distancePx);
    cv::line(img, {p.x, bottom}, {p.x, top}, {255, 0, 255}, 1);
    cv::circle(img, p, 4, {255, 0, 255}, 2, cv::LINE_AA);
  }
  return toImage(img);
}

} // namespace sylva::capture
