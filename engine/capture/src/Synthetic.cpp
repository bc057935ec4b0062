// Synthetic blade clusters with known truth. Each blade is a centreline in camera space, swept by a
// cross-section of the shape's width profile facing the camera; consecutive cross-sections form quads that
// are rasterised with a z-buffer (perspective-correct depth), so overlapping blades occlude each other as
// they would for a sensor. Noise follows the Kinect v1 literature: axial σ(z) = 1.2 mm + 1.9 mm·(z − 0.4 m)²
// (Nguyen, Izadi & Lovell 2012), lateral edge jitter of about half a pixel, dropouts along depth edges
// (projector shadows) and the 11-bit disparity quantisation of the device.
#include <sylva/capture/Synthetic.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/core/Random.hpp>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace sylva::capture {
namespace {

constexpr int kSamples = 256;

struct ShapeInfo {
  BladeShape shape;
  const char* name;
  float length;
  float width;
};

constexpr std::array<ShapeInfo, 5> kShapes{{
    {BladeShape::SlimGrass, "slim", 0.30f, 0.008f},
    {BladeShape::QuadraticLeaf, "quadratic", 0.18f, 0.026f},
    {BladeShape::SlenderLeaf, "slender", 0.28f, 0.012f},
    {BladeShape::BambooLeaf, "bamboo", 0.22f, 0.022f},
    {BladeShape::SharpTip, "sharp", 0.25f, 0.012f},
}};

const ShapeInfo& info(BladeShape shape) {
  for (const ShapeInfo& s : kShapes) {
    if (s.shape == shape) {
      return s;
    }
  }
  return kShapes[0];
}

/** Standard normal deviate (Box–Muller; one of the pair is dropped for simplicity). */
float gaussian(Rng& rng) {
  const float u1 = std::max(rng.uniform(), 1e-7f);
  const float u2 = rng.uniform();
  return std::sqrt(-2.0f * std::log(u1)) * std::cos(2.0f * std::numbers::pi_v<float> * u2);
}

/** One blade's geometry: centreline, left and right edge points (camera space, metres). */
struct BladeGeometry {
  std::vector<glm::vec3> centre;
  std::vector<glm::vec3> left;
  std::vector<glm::vec3> right;
};

BladeGeometry sweep(const SyntheticBlade& blade, const glm::vec3& root, float extraBend) {
  BladeGeometry g;
  g.centre.resize(kSamples);
  g.left.resize(kSamples);
  g.right.resize(kSamples);
  const float ds = blade.lengthMetres / static_cast<float>(kSamples - 1);
  const float cosTilt = std::cos(blade.tiltRadians);
  const float sinTilt = std::sin(blade.tiltRadians);
  glm::vec3 p = root;
  for (int i = 0; i < kSamples; ++i) {
    const float t = static_cast<float>(i) / static_cast<float>(kSamples - 1);
    const float theta = blade.leanRadians + blade.bendRadians * t + extraBend * t * t;
    // Up in the image is −y in camera space; the lean turns it to the right (+x).
    const glm::vec3 dir{std::sin(theta) * cosTilt, -std::cos(theta) * cosTilt, -sinTilt};
    const glm::vec3 side{std::cos(theta), std::sin(theta), 0.0f};
    if (i > 0) {
      p += dir * ds;
    }
    const float w = blade.widthMetres * bladeWidthProfile(blade.shape, t);
    g.centre[i] = p;
    g.left[i] = p - side * (0.5f * w);
    const float bulge =
        blade.lobe * blade.widthMetres * std::exp(-0.5f * (t - 0.5f) * (t - 0.5f) / (0.08f * 0.08f));
    g.right[i] = p + side * (0.5f * w * (1.0f - blade.asymmetry) + bulge);
  }
  return g;
}

/** The camera's roll and pitch applied to a blade: every point turned about the scene's root. */
void turnCamera(const SyntheticScene& scene, BladeGeometry& g) {
  if (scene.rollRadians == 0.0f && scene.pitchRadians == 0.0f) {
    return;
  }
  const float cr = std::cos(scene.rollRadians);
  const float sr = std::sin(scene.rollRadians);
  const float cp = std::cos(scene.pitchRadians);
  const float sp = std::sin(scene.pitchRadians);
  const auto turn = [&](glm::vec3& p) {
    glm::vec3 d = p - scene.rootMetres;
    // Pitch about x (an upright blade's tip comes towards the camera), then roll about the optical axis (x
    // right, y down: a positive angle turns the picture clockwise).
    d = {d.x, cp * d.y - sp * d.z, sp * d.y + cp * d.z};
    d = {cr * d.x - sr * d.y, sr * d.x + cr * d.y, d.z};
    p = scene.rootMetres + d;
  };
  for (std::vector<glm::vec3>* line : {&g.centre, &g.left, &g.right}) {
    std::for_each(line->begin(), line->end(), turn);
  }
}

glm::vec3 project(const CameraIntrinsics& k, const glm::vec3& p) {
  return {static_cast<float>(k.fx * p.x / p.z + k.cx), static_cast<float>(k.fy * p.y / p.z + k.cy), p.z};
}

/** Rasterises triangle (a, b, c) (pixels xy, depth z) into the z-buffer with perspective-correct depth. */
void rasterTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, int label, int width,
                    int height, std::vector<float>& zbuf, std::vector<int>& labels) {
  const float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (std::abs(area) < 1e-9f) {
    return;
  }
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
  const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
  const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const float px = static_cast<float>(x);
      const float py = static_cast<float>(y);
      const float w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
      const float w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
      const float w2 = 1.0f - w0 - w1;
      if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) {
        continue;
      }
      const float invZ = w0 / a.z + w1 / b.z + w2 / c.z;
      const float z = 1.0f / invZ;
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      if (zbuf[i] == 0.0f || z < zbuf[i]) {
        zbuf[i] = z;
        labels[i] = label;
      }
    }
  }
}

SyntheticFrame renderWithBends(const SyntheticScene& scene, const std::vector<float>& extraBends,
                               int frameIndex) {
  if (scene.width < 16 || scene.height < 16 || scene.width > 8192 || scene.height > 8192) {
    fail("synthetic scene: size {}x{} outside 16..8192", scene.width, scene.height);
  }
  if (scene.rootMetres.z <= 0.05f) {
    fail("synthetic scene: root depth {} m must be in front of the camera", scene.rootMetres.z);
  }
  SyntheticFrame out;
  DepthFrame& frame = out.frame;
  frame = DepthFrame(scene.width, scene.height);
  frame.intrinsics = scene.intrinsics;
  frame.kind = DepthSourceKind::Synthetic;
  frame.source = "synthetic";
  frame.frame = frameIndex;
  frame.timestamp = 0.0;
  const std::size_t n = static_cast<std::size_t>(scene.width) * scene.height;
  std::vector<float> zbuf(n, 0.0f);
  std::vector<int> labels(n, -1);
  SyntheticTruth& truth = out.truth;
  for (std::size_t b = 0; b < scene.blades.size(); ++b) {
    const SyntheticBlade& blade = scene.blades[b];
    const glm::vec3 root =
        scene.rootMetres * (1.0f - blade.nearerMetres / scene.rootMetres.z) + blade.rootOffsetMetres;
    BladeGeometry g = sweep(blade, root, b < extraBends.size() ? extraBends[b] : 0.0f);
    turnCamera(scene, g);
    for (const std::vector<glm::vec3>* line : {&g.centre, &g.left, &g.right}) {
      for (const glm::vec3& p : *line) {
        if (!(p.z > 0.05f)) {
          fail("synthetic scene: blade {} comes within 5 cm of the camera plane (move it farther or turn the "
               "camera less)",
               b);
        }
      }
    }
    std::vector<glm::vec2> linePx(kSamples);
    std::vector<float> widthPx(kSamples);
    for (int i = 0; i < kSamples; ++i) {
      const glm::vec3 c = project(scene.intrinsics, g.centre[i]);
      const glm::vec3 l = project(scene.intrinsics, g.left[i]);
      const glm::vec3 r = project(scene.intrinsics, g.right[i]);
      linePx[i] = {c.x, c.y};
      widthPx[i] = glm::length(glm::vec2(l) - glm::vec2(r));
      if (i > 0) {
        const glm::vec3 lp = project(scene.intrinsics, g.left[i - 1]);
        const glm::vec3 rp = project(scene.intrinsics, g.right[i - 1]);
        rasterTriangle(lp, rp, r, static_cast<int>(b), scene.width, scene.height, zbuf, labels);
        rasterTriangle(lp, r, l, static_cast<int>(b), scene.width, scene.height, zbuf, labels);
      }
    }
    truth.centrelinePx.push_back(std::move(linePx));
    truth.widthsPx.push_back(std::move(widthPx));
    truth.centrelineMetres.push_back(g.centre);
    std::vector<float> wm(kSamples);
    for (int i = 0; i < kSamples; ++i) {
      wm[i] = glm::length(g.left[i] - g.right[i]);
    }
    truth.widthsMetres.push_back(std::move(wm));
  }
  truth.label = labels;
  truth.mask.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    truth.mask[i] = labels[i] >= 0 ? 255 : 0;
  }

  // Clean depth: blades over the background wall.
  std::vector<float> clean(n);
  for (std::size_t i = 0; i < n; ++i) {
    clean[i] = labels[i] >= 0 ? zbuf[i] : scene.backgroundMetres;
  }
  Rng rng(hash64(scene.seed * 0x9e3779b97f4a7c15ULL + static_cast<std::uint64_t>(frameIndex) + 1));
  const int w = scene.width;
  const int h = scene.height;
  auto cleanAt = [&](int x, int y) {
    return clean[static_cast<std::size_t>(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)];
  };
  auto labelAt = [&](int x, int y) {
    return labels[static_cast<std::size_t>(std::clamp(y, 0, h - 1)) * w + std::clamp(x, 0, w - 1)];
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      float z = clean[static_cast<std::size_t>(y) * w + x];
      if (scene.noise) {
        const int dx = static_cast<int>(std::lround(gaussian(rng) * scene.lateralNoisePx));
        const int dy = static_cast<int>(std::lround(gaussian(rng) * scene.lateralNoisePx));
        z = cleanAt(x + dx, y + dy);
        const int l = labelAt(x, y);
        const bool edge = l != labelAt(x - 1, y) || l != labelAt(x + 1, y) || l != labelAt(x, y - 1) ||
                          l != labelAt(x, y + 1);
        if (edge && rng.uniform() < scene.edgeDropout) {
          z = 0.0f;
        }
        if (z > 0.0f) {
          const float sigma = 0.0012f + 0.0019f * (z - 0.4f) * (z - 0.4f);
          z += gaussian(rng) * sigma;
          z = kinectRawToMetres(metresToKinectRaw(z));
        }
      }
      frame.at(x, y) = std::max(z, 0.0f);
    }
  }

  if (scene.colour) {
    frame.colour = Image(w, h, 3, PixelType::U8);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const int l = labels[static_cast<std::size_t>(y) * w + x];
        glm::vec3 c;
        if (l >= 0) {
          // Green with a per-blade hue shift, lighter towards the tip (higher in the image).
          const float shift =
              0.06f * static_cast<float>(hash64(scene.seed + static_cast<std::uint64_t>(l)) % 7) / 6.0f;
          const float up = 1.0f - static_cast<float>(y) / static_cast<float>(h);
          c = glm::vec3(0.16f + shift, 0.42f + 0.15f * up, 0.10f);
        } else {
          // A soil-brown wall with fine deterministic texture.
          const float n =
              static_cast<float>(hash64(static_cast<std::uint64_t>(y) * 7919u + x) % 1000) / 1000.0f;
          c = glm::vec3(0.42f, 0.31f, 0.22f) * (0.85f + 0.3f * n);
        }
        for (int ch = 0; ch < 3; ++ch) {
          frame.colour.set(x, y, ch, c[ch]);
        }
      }
    }
  }
  return out;
}

} // namespace

const char* bladeShapeName(BladeShape shape) {
  return info(shape).name;
}

std::optional<BladeShape> parseBladeShape(const std::string& name) {
  for (const ShapeInfo& s : kShapes) {
    if (name == s.name) {
      return s.shape;
    }
  }
  return std::nullopt;
}

float bladeWidthProfile(BladeShape shape, float t) {
  t = std::clamp(t, 0.0f, 1.0f);
  switch (shape) {
  case BladeShape::SlimGrass:
    // Nearly constant, narrowing steadily and closing over the last fifth.
    return 1.0f - 0.3f * t - 0.7f * std::pow(t, 6.0f);
  case BladeShape::QuadraticLeaf:
    // Widest at the middle: a parabola, with a stalk of 35 % at the root.
    return t < 0.5f ? 0.35f + 0.65f * 4.0f * t * (1.0f - t) : 4.0f * t * (1.0f - t);
  case BladeShape::SlenderLeaf:
    return std::pow(1.0f - t, 0.6f);
  case BladeShape::BambooLeaf:
    // Lanceolate: a short stalk widening to the full width at 35 %, then a long taper.
    return t < 0.35f ? 0.3f + 0.7f * std::sin(0.5f * std::numbers::pi_v<float> * t / 0.35f)
                     : std::pow((1.0f - t) / 0.65f, 0.8f);
  case BladeShape::SharpTip:
    return t < 0.85f ? 1.0f : (1.0f - t) / 0.15f;
  }
  return 1.0f;
}

float bladeShapeLength(BladeShape shape) {
  return info(shape).length;
}
float bladeShapeWidth(BladeShape shape) {
  return info(shape).width;
}

SyntheticScene makeCluster(BladeShape shape, int count, float bendRadians, float orientationRadians,
                           std::uint64_t seed, float spreadRadians) {
  if (count < 1 || count > 64) {
    fail("synthetic cluster: blade count {} outside 1..64", count);
  }
  SyntheticScene scene;
  scene.seed = seed;
  Rng rng(hash64(seed));
  for (int i = 0; i < count; ++i) {
    SyntheticBlade b;
    b.shape = shape;
    const float u = count == 1 ? 0.0f : static_cast<float>(i) / static_cast<float>(count - 1) - 0.5f;
    b.leanRadians = orientationRadians + u * spreadRadians;
    // Bend away from the cluster's axis, so blades open like a real tuft.
    b.bendRadians = bendRadians * (u == 0.0f ? 1.0f : (u > 0.0f ? 1.0f : -1.0f));
    b.lengthMetres = bladeShapeLength(shape) * rng.uniform(0.9f, 1.1f);
    b.widthMetres = bladeShapeWidth(shape) * rng.uniform(0.9f, 1.1f);
    b.tiltRadians = rng.uniform(-0.15f, 0.15f);
    scene.blades.push_back(b);
  }
  return scene;
}

const char* clusterLayoutName(ClusterLayout layout) {
  switch (layout) {
  case ClusterLayout::Fan:
    return "fan";
  case ClusterLayout::Occluded:
    return "occluded";
  case ClusterLayout::Crossing:
    return "crossing";
  case ClusterLayout::Dense:
    return "dense";
  }
  return "fan";
}

std::optional<ClusterLayout> parseClusterLayout(const std::string& name) {
  for (const ClusterLayout layout : kClusterLayouts) {
    if (name == clusterLayoutName(layout)) {
      return layout;
    }
  }
  return std::nullopt;
}

SyntheticScene makeLayoutCluster(ClusterLayout layout, BladeShape shape, int count, float bendRadians,
                                 float orientationRadians, std::uint64_t seed, float spreadRadians) {
  if ((layout == ClusterLayout::Occluded || layout == ClusterLayout::Crossing) && count < 2) {
    fail("synthetic cluster: the {} layout needs at least 2 blades, not {}", clusterLayoutName(layout),
         count);
  }
  switch (layout) {
  case ClusterLayout::Fan:
    return makeCluster(shape, count, bendRadians, orientationRadians, seed, spreadRadians);
  case ClusterLayout::Dense:
    return makeCluster(shape, count, bendRadians, orientationRadians, seed, std::numbers::pi_v<float> / 3.0f);
  case ClusterLayout::Occluded: {
    SyntheticScene scene =
        makeCluster(shape, count - 1, bendRadians, orientationRadians, seed, spreadRadians);
    Rng rng(hash64(seed ^ 0x6f63636c75646564ULL));
    const std::size_t k = rng.below(static_cast<std::uint32_t>(scene.blades.size()));
    // The extra blade follows its neighbour's centreline 3 cm nearer along the ray through the root (so the
    // roots meet in the picture), narrower and shorter: its outline lies inside the neighbour's.
    SyntheticBlade front = scene.blades[k];
    front.widthMetres *= rng.uniform(0.45f, 0.6f);
    const float shorter = rng.uniform(0.65f, 0.8f);
    front.lengthMetres *= shorter;
    front.bendRadians *= shorter; // the same turn per metre: it runs along the neighbour's centreline
    front.nearerMetres = 0.03f;
    scene.blades.insert(scene.blades.begin() + static_cast<std::ptrdiff_t>(k) + 1, front);
    return scene;
  }
  case ClusterLayout::Crossing: {
    // Two fans 5 cm apart and 3 cm apart in depth, each leaning 0.35 rad towards the other over 0.8 rad.
    const int left = (count + 1) / 2;
    SyntheticScene scene = makeCluster(shape, left, bendRadians, orientationRadians + 0.35f, seed, 0.8f);
    for (SyntheticBlade& b : scene.blades) {
      b.rootOffsetMetres = {-0.025f, 0.0f, 0.015f};
    }
    if (count - left > 0) {
      SyntheticScene other =
          makeCluster(shape, count - left, -bendRadians, orientationRadians - 0.35f, seed + 1, 0.8f);
      for (SyntheticBlade& b : other.blades) {
        b.rootOffsetMetres = {0.025f, 0.0f, -0.015f};
        scene.blades.push_back(b);
      }
    }
    return scene;
  }
  }
  return makeCluster(shape, count, bendRadians, orientationRadians, seed, spreadRadians);
}

SyntheticScene makeSweepCluster(std::uint64_t seed, ClusterLayout* layoutOut,
                                std::optional<ClusterLayout> only) {
  Rng rng(hash64(seed * 0x9e3779b97f4a7c15ULL + 0x5377656570ULL));
  const ClusterLayout drawn = kClusterLayouts[rng.below(4)];
  const ClusterLayout layout = only.value_or(drawn);
  const BladeShape shape = kBladeShapes[rng.below(5)];
  int count = 0;
  switch (layout) {
  case ClusterLayout::Fan:
    count = 3 + static_cast<int>(rng.below(5));
    break;
  case ClusterLayout::Occluded:
    count = 4 + static_cast<int>(rng.below(4));
    break;
  case ClusterLayout::Crossing:
    count = 4 + static_cast<int>(rng.below(5));
    break;
  case ClusterLayout::Dense:
    count = 11 + static_cast<int>(rng.below(4));
    break;
  }
  const float bend = rng.uniform(-0.2f, 0.5f);
  const float lean = rng.uniform(-0.3f, 0.3f);
  const float spread = rng.uniform(1.0f, 1.6f);
  SyntheticScene scene = makeLayoutCluster(layout, shape, count, bend, lean, seed, spread);
  scene.rollRadians = rng.uniform(-0.5f, 0.5f);
  scene.pitchRadians = rng.uniform(-0.3f, 0.3f);
  const float distance = rng.uniform(0.55f, 0.9f);
  scene.rootMetres = {0.0f, 0.2f * distance / 0.65f, distance};
  scene.edgeDropout = rng.uniform(0.05f, 0.3f);
  if (layoutOut != nullptr) {
    *layoutOut = layout;
  }
  return scene;
}

SyntheticFrame renderScene(const SyntheticScene& scene, float extraBendRadians, int frameIndex) {
  return renderWithBends(scene, std::vector<float>(scene.blades.size(), extraBendRadians), frameIndex);
}

std::vector<SyntheticFrame> swaySequence(const SyntheticScene& scene, int frames, double fps,
                                         float amplitudeRadians, double frequencyHz) {
  if (frames < 1 || frames > 100000 || !(fps > 0.0) || !std::isfinite(amplitudeRadians) ||
      !(frequencyHz >= 0.0)) {
    fail("synthetic sway: need frames in 1..100000, fps > 0, a finite amplitude and frequency ≥ 0");
  }
  std::vector<SyntheticFrame> out;
  out.reserve(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    std::vector<float> bends(scene.blades.size());
    for (std::size_t b = 0; b < bends.size(); ++b) {
      const double phase = 0.9 * static_cast<double>(b);
      bends[b] = amplitudeRadians *
                 static_cast<float>(std::sin(2.0 * std::numbers::pi * frequencyHz * f / fps + phase));
    }
    SyntheticFrame frame = renderWithBends(scene, bends, f);
    frame.frame.timestamp = f / fps;
    out.push_back(std::move(frame));
  }
  return out;
}

namespace {

float pointSegmentDistance(const glm::vec2& p, const glm::vec2& a, const glm::vec2& b) {
  const glm::vec2 ab = b - a;
  const float len2 = glm::dot(ab, ab);
  const float t = len2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

/** Nearest centreline sample and the distance to the polyline. */
std::pair<std::size_t, float> nearestOnLine(const std::vector<glm::vec2>& line, const glm::vec2& p) {
  std::size_t best = 0;
  float bestD = std::numeric_limits<float>::max();
  float segD = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < line.size(); ++i) {
    const float d = glm::length(line[i] - p);
    if (d < bestD) {
      bestD = d;
      best = i;
    }
    if (i + 1 < line.size()) {
      segD = std::min(segD, pointSegmentDistance(p, line[i], line[i + 1]));
    }
  }
  return {best, std::min(segD, bestD)};
}

} // namespace

AccuracyReport evaluateCapture(const SyntheticTruth& truth, const ExtractResult& result) {
  AccuracyReport report;
  report.bladesExpected = static_cast<int>(truth.centrelinePx.size());
  report.bladesFound = static_cast<int>(result.blades.size());

  // Silhouette IoU of the rasterised capture against the noise-free silhouette.
  if (!truth.mask.empty() && result.width > 0) {
    const std::vector<std::uint8_t> mine = rasteriseBlades(result.blades, result.width, result.height);
    std::size_t inter = 0;
    std::size_t uni = 0;
    for (std::size_t i = 0; i < mine.size() && i < truth.mask.size(); ++i) {
      const bool a = mine[i] != 0;
      const bool b = truth.mask[i] != 0;
      inter += (a && b) ? 1 : 0;
      uni += (a || b) ? 1 : 0;
    }
    report.silhouetteIoU = uni > 0 ? static_cast<double>(inter) / static_cast<double>(uni) : 0.0;
  }

  // Greedy matching by tip distance.
  struct Pair {
    float d;
    std::size_t found;
    std::size_t truth;
  };
  std::vector<Pair> pairs;
  for (std::size_t f = 0; f < result.blades.size(); ++f) {
    if (result.blades[f].skeletonPx.empty()) {
      continue;
    }
    for (std::size_t t = 0; t < truth.centrelinePx.size(); ++t) {
      pairs.push_back({glm::length(result.blades[f].skeletonPx.back() - truth.centrelinePx[t].back()), f, t});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
    return a.d < b.d || (a.d == b.d && (a.found < b.found || (a.found == b.found && a.truth < b.truth)));
  });
  std::vector<bool> usedF(result.blades.size(), false);
  std::vector<bool> usedT(truth.centrelinePx.size(), false);
  int matched = 0;
  double widthSum = 0.0;
  double skelSum = 0.0;
  double lengthSum = 0.0;
  for (const Pair& p : pairs) {
    if (usedF[p.found] || usedT[p.truth]) {
      continue;
    }
    usedF[p.found] = usedT[p.truth] = true;
    const CapturedBlade& blade = result.blades[p.found];
    const std::vector<glm::vec2>& line = truth.centrelinePx[p.truth];
    const std::vector<float>& widths = truth.widthsPx[p.truth];
    const float maxW = *std::max_element(widths.begin(), widths.end());
    // Knots of the captured part (beyond the extension to the centre).
    const std::size_t n = blade.skeletonPx.size();
    float along = 0.0f;
    std::vector<float> arc(n, 0.0f);
    for (std::size_t k = 1; k < n; ++k) {
      along += glm::length(blade.skeletonPx[k] - blade.skeletonPx[k - 1]);
      arc[k] = along;
    }
    const float start = blade.extensionPx;
    const float span = std::max(along - start, 1e-3f);
    double wErr = 0.0;
    int wCount = 0;
    double sErr = 0.0;
    int sCount = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (arc[k] < start) {
        continue;
      }
      const auto [nearest, distance] = nearestOnLine(line, blade.skeletonPx[k]);
      sErr += distance;
      ++sCount;
      const float u = (arc[k] - start) / span;
      if (u >= 0.1f && u <= 0.9f) {
        wErr += std::abs(blade.widthsPx[k] - widths[nearest]) / std::max(maxW, 1e-3f);
        ++wCount;
      }
    }
    const double bladeW = wCount > 0 ? wErr / wCount : 1.0;
    const double bladeS = sCount > 0 ? sErr / sCount : 1e9;
    float trueLength = 0.0f;
    for (std::size_t i = 1; i < line.size(); ++i) {
      trueLength += glm::length(line[i] - line[i - 1]);
    }
    widthSum += bladeW;
    report.bladeWidthErrors.push_back(bladeW);
    skelSum += bladeS;
    lengthSum += blade.lengthPx / std::max(trueLength, 1e-3f);
    report.widthErrorMax = std::max(report.widthErrorMax, bladeW);
    report.skeletonErrorMaxPx = std::max(report.skeletonErrorMaxPx, bladeS);
    report.skeletonErrorRelative =
        std::max(report.skeletonErrorRelative, bladeS / std::max(trueLength, 1e-3f));
    ++matched;
  }
  if (matched > 0) {
    report.widthError = widthSum / matched;
    report.skeletonErrorPx = skelSum / matched;
    report.lengthRatio = lengthSum / matched;
  }
  return report;
}

std::vector<bool> tipsStandFree(const SyntheticTruth& truth, int width, int height) {
  const std::size_t bladeCount = truth.centrelinePx.size();
  std::vector<bool> free(bladeCount, false);
  if (truth.label.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    return free;
  }
  // Depth of blade l near pixel p: its nearest centreline sample's (blades face the camera, so across a
  // blade's width its depth is its centreline's).
  const auto depthNear = [&truth](std::size_t l, glm::vec2 p) {
    const std::vector<glm::vec2>& line = truth.centrelinePx[l];
    std::size_t best = 0;
    float bestD = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < line.size(); ++i) {
      const float d = glm::dot(line[i] - p, line[i] - p);
      if (d < bestD) {
        bestD = d;
        best = i;
      }
    }
    return truth.centrelineMetres[l][best].z;
  };
  constexpr float kSameSurfaceMetres = 0.005f; // the extractor's smallest depth step between layers
  for (std::size_t b = 0; b < bladeCount; ++b) {
    const std::vector<glm::vec2>& line = truth.centrelinePx[b];
    if (line.empty() || truth.widthsPx[b].size() != line.size()) {
      continue;
    }
    const std::size_t from = line.size() * 85 / 100;
    const int r = std::max(2, static_cast<int>(std::lround(0.6f * truth.widthsPx[b][from])));
    for (std::size_t i = from; i < line.size() && !free[b]; ++i) {
      const int x = static_cast<int>(std::lround(line[i].x));
      const int y = static_cast<int>(std::lround(line[i].y));
      if (x < 0 || y < 0 || x >= width || y >= height ||
          truth.label[static_cast<std::size_t>(y) * width + x] != static_cast<int>(b)) {
        continue;
      }
      const float z = truth.centrelineMetres[b][i].z;
      bool alone = true;
      for (int dy = -r; dy <= r && alone; ++dy) {
        for (int dx = -r; dx <= r && alone; ++dx) {
          const int qx = x + dx;
          const int qy = y + dy;
          if (dx * dx + dy * dy > r * r || qx < 0 || qy < 0 || qx >= width || qy >= height) {
            continue;
          }
          const int l = truth.label[static_cast<std::size_t>(qy) * width + qx];
          alone =
              l < 0 || l == static_cast<int>(b) ||
              std::abs(depthNear(static_cast<std::size_t>(l), glm::vec2(qx, qy)) - z) > kSameSurfaceMetres;
        }
      }
      free[b] = alone;
    }
  }
  return free;
}

std::string sweepLine(const char* name, const SweepTally& t) {
  return fmt::format(
      "{:<9} {:>5} clusters  count exact {:>5.1f} %  ({} with blades missing)  width within 10 % on "
      "{:>5.1f} % of {} blades  every tip free in {} (exact {:.1f} %)",
      name, t.clusters, 100.0 * t.exactShare(), t.fewer, 100.0 * t.widthShare(), t.blades, t.tipsFree,
      100.0 * t.tipsFreeExactShare());
}

std::string describeSweep(const SweepReport& report, std::optional<ClusterLayout> only) {
  std::string text;
  for (std::size_t i = 0; i < report.byLayout.size(); ++i) {
    if (report.byLayout[i].clusters > 0) {
      text += sweepLine(clusterLayoutName(kClusterLayouts[i]), report.byLayout[i]) + "\n";
    }
  }
  text += sweepLine("all", report.all) + "\n";
  if (!report.wrongSeeds.empty()) {
    std::string seeds;
    for (std::size_t i = 0; i < std::min<std::size_t>(report.wrongSeeds.size(), 12); ++i) {
      seeds += fmt::format("{}{}", i > 0 ? ", " : "", report.wrongSeeds[i]);
    }
    const std::string redraw = only ? fmt::format(" --layout {}", clusterLayoutName(*only)) : std::string();
    text += fmt::format("wrong counts at seeds {}{} (draw one with --sweep-cluster SEED{}, capture it with "
                        "--explain)\n",
                        seeds, report.wrongSeeds.size() > 12 ? ", …" : "", redraw);
  }
  return text;
}

SweepReport captureSweep(int clusters, std::uint64_t firstSeed, Progress* progress,
                         std::optional<ClusterLayout> only) {
  if (clusters < 1 || clusters > 1000000) {
    fail("capture sweep: {} clusters; give 1..1000000", clusters);
  }
  SweepReport report;
  for (int i = 0; i < clusters; ++i) {
    ClusterLayout layout = ClusterLayout::Fan;
    SyntheticScene scene = makeSweepCluster(firstSeed + static_cast<std::uint64_t>(i), &layout, only);
    scene.colour = false;
    SyntheticFrame frame = renderScene(scene);
    // Captured as the depth PNG that --sweep-cluster writes holds it, so that a cluster redrawn from its seed
    // and captured from the file is counted as the sweep counted it.
    roundToDepthPng(frame.frame);
    const AccuracyReport accuracy = evaluateCapture(frame.truth, extractBlades(frame.frame));
    const std::size_t slot =
        static_cast<std::size_t>(std::find(std::begin(kClusterLayouts), std::end(kClusterLayouts), layout) -
                                 std::begin(kClusterLayouts));
    if (accuracy.bladesFound != accuracy.bladesExpected) {
      report.wrongSeeds.push_back(firstSeed + static_cast<std::uint64_t>(i));
    }
    const std::vector<bool> free = tipsStandFree(frame.truth, scene.width, scene.height);
    const bool allFree = std::all_of(free.begin(), free.end(), [](bool f) { return f; });
    for (SweepTally* t : {&report.byLayout[slot], &report.all}) {
      ++t->clusters;
      t->exact += accuracy.bladesFound == accuracy.bladesExpected ? 1 : 0;
      t->tipsFree += allFree ? 1 : 0;
      t->tipsFreeExact += allFree && accuracy.bladesFound == accuracy.bladesExpected ? 1 : 0;
      t->fewer += accuracy.bladesFound < accuracy.bladesExpected ? 1 : 0;
      t->blades += accuracy.bladesExpected;
      t->widthWithin10 +=
          static_cast<int>(std::count_if(accuracy.bladeWidthErrors.begin(), accuracy.bladeWidthErrors.end(),
                                         [](double e) { return e <= 0.10; }));
    }
    if (progress != nullptr) {
      progress->advance();
    }
  }
  return report;
}

} // namespace sylva::capture
