// Skeleton refining (paper §4.4, eq. 1–3, Algorithm 1) and the kinematic sway model that gives it frames when
// there is no recording. Both refiners share the difference and merge helpers below, so the heap version
// reproduces the reference bit for bit: same floating-point operations, same tie-break (the pair nearer the
// root).
#include <sylva/capture/Refine.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sylva::capture {

namespace {

/** Knot trajectories stored knot-major: knot k's frames are contiguous, so D reads two runs of memory. */
struct Trajectories {
  std::size_t frameCount = 0;
  std::vector<glm::vec3> positions;

  std::span<glm::vec3> of(std::size_t knot) { return {positions.data() + knot * frameCount, frameCount}; }
  std::span<const glm::vec3> of(std::size_t knot) const {
    return {positions.data() + knot * frameCount, frameCount};
  }
};

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/** Checks the input of both refiners; returns the knot count. */
std::size_t validate(const KnotFrames& frames, std::span<const float> widths, const RefineOptions& options) {
  if (frames.empty()) {
    fail("refine: no frames");
  }
  const std::size_t knots = frames[0].size();
  if (knots < 2) {
    fail("refine: the skeleton has {} knots; at least 2 are needed", knots);
  }
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].size() != knots) {
      fail("refine: frame {} has {} knots, frame 0 has {}", f, frames[f].size(), knots);
    }
    for (std::size_t k = 0; k < knots; ++k) {
      if (!finite(frames[f][k])) {
        fail("refine: frame {}, knot {}: position is not finite", f, k);
      }
    }
  }
  if (options.knots < 2) {
    fail("refine: cannot refine to {} knots; at least 2 are needed", options.knots);
  }
  if (!(options.unitMetres >= 0.0) || !std::isfinite(options.unitMetres)) {
    fail("refine: unit {} m must be finite and ≥ 0", options.unitMetres);
  }
  if (!(options.mu >= 0.0 && options.mu <= 1.0)) {
    fail("refine: mu = {} is outside [0, 1]", options.mu);
  }
  if (!widths.empty() && widths.size() != knots) {
    fail("refine: {} widths for {} knots", widths.size(), knots);
  }
  for (std::size_t k = 0; k < widths.size(); ++k) {
    if (!std::isfinite(widths[k]) || widths[k] < 0.0f) {
      fail("refine: width {} is {}; widths must be finite and ≥ 0", k, widths[k]);
    }
  }
  return knots;
}

Trajectories knotMajor(const KnotFrames& frames, std::size_t knots) {
  Trajectories t;
  t.frameCount = frames.size();
  t.positions.resize(knots * t.frameCount);
  for (std::size_t f = 0; f < t.frameCount; ++f) {
    for (std::size_t k = 0; k < knots; ++k) {
      t.positions[k * t.frameCount + f] = frames[f][k];
    }
  }
  return t;
}

/** D of eq. 1–3 without validation (sizes equal and non-zero). Out of line: one code path for both refiners.
 */
[[gnu::noinline]] double difference(std::span<const glm::vec3> a, std::span<const glm::vec3> b,
                                    const RefineOptions& options) {
  const double scale = options.unitMetres > 0.0 ? 1.0 / options.unitMetres : 1.0;
  const double n = static_cast<double>(a.size());
  double sum = 0.0;
  double sumSquares = 0.0;
  glm::dvec3 sumVector(0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const glm::dvec3 d = (glm::dvec3(a[i]) - glm::dvec3(b[i])) * scale;
    const double squared = d.x * d.x + d.y * d.y + d.z * d.z;
    sum += std::sqrt(squared);
    sumSquares += squared;
    sumVector += d;
  }
  const double dis = sum / n;
  double var = 0.0;
  if (options.measure == RefineOptions::Measure::Distance) {
    // Σd²/n − (Σd)²/n²: the variance of d; rounding can leave a tiny negative value for constant d.
    var = std::max(0.0, sumSquares / n - (sum * sum) / (n * n));
  } else {
    // Σ|Δ|²/n − |ΣΔ/n|²: the variance of the relative position Δ = a − b.
    const glm::dvec3 mean = sumVector / n;
    var = std::max(0.0, sumSquares / n - (mean.x * mean.x + mean.y * mean.y + mean.z * mean.z));
  }
  return options.mu * dis + (1.0 - options.mu) * var;
}

/**
 * Merges the pair (left, right) into `left`: the per-frame midpoint and mean width, or with keepEnds the end
 * knot itself (width included) when the pair holds the root (`leftIsRoot`) or the tip (`rightIsTip`).
 */
[[gnu::noinline]] void merge(std::span<glm::vec3> left, std::span<const glm::vec3> right, float* leftWidth,
                             float rightWidth, bool leftIsRoot, bool rightIsTip, bool keepEnds) {
  if (keepEnds && leftIsRoot) {
    return;
  }
  if (keepEnds && rightIsTip) {
    std::copy(right.begin(), right.end(), left.begin());
    if (leftWidth != nullptr) {
      *leftWidth = rightWidth;
    }
    return;
  }
  // In double: the midpoint of two finite floats stays finite even near FLT_MAX.
  for (std::size_t i = 0; i < left.size(); ++i) {
    left[i] = glm::vec3((glm::dvec3(left[i]) + glm::dvec3(right[i])) * 0.5);
  }
  if (leftWidth != nullptr) {
    *leftWidth =
        static_cast<float>((static_cast<double>(*leftWidth) + static_cast<double>(rightWidth)) * 0.5);
  }
}

RefineResult unchanged(const KnotFrames& frames, std::span<const float> widths) {
  RefineResult result;
  result.frames = frames;
  result.widths.assign(widths.begin(), widths.end());
  result.merged.assign(frames[0].size(), 1);
  return result;
}

} // namespace

double movementDifference(std::span<const glm::vec3> a, std::span<const glm::vec3> b, double mu) {
  if (a.size() != b.size()) {
    fail("movementDifference: trajectories of {} and {} frames", a.size(), b.size());
  }
  if (a.empty()) {
    fail("movementDifference: no frames");
  }
  if (!(mu >= 0.0 && mu <= 1.0)) {
    fail("movementDifference: mu = {} is outside [0, 1]", mu);
  }
  RefineOptions options;
  options.mu = mu;
  return difference(a, b, options);
}

double movementDifference(std::span<const glm::vec3> a, std::span<const glm::vec3> b,
                          const RefineOptions& options) {
  if (!(options.unitMetres >= 0.0) || !std::isfinite(options.unitMetres)) {
    fail("movementDifference: unit {} m must be finite and ≥ 0", options.unitMetres);
  }
  const double d = movementDifference(a, b, options.mu);
  if (options.measure == RefineOptions::Measure::Distance && options.unitMetres == 0.0) {
    return d;
  }
  return difference(a, b, options);
}

RefineResult refineKnotsReference(const KnotFrames& frames, std::span<const float> widths,
                                  const RefineOptions& options) {
  const std::size_t inputKnots = validate(frames, widths, options);
  const auto target = static_cast<std::size_t>(options.knots);
  if (target >= inputKnots) {
    return unchanged(frames, widths);
  }
  struct Knot {
    std::vector<glm::vec3> trajectory;
    float width = 0.0f;
    int merged = 1;
  };
  std::vector<Knot> knots(inputKnots);
  const Trajectories t = knotMajor(frames, inputKnots);
  for (std::size_t k = 0; k < inputKnots; ++k) {
    const std::span<const glm::vec3> run = t.of(k);
    knots[k].trajectory.assign(run.begin(), run.end());
    knots[k].width = widths.empty() ? 0.0f : widths[k];
  }
  const bool hasWidths = !widths.empty();
  std::vector<double> differences;
  while (knots.size() > target) {
    differences.clear();
    for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
      differences.push_back(difference(knots[i].trajectory, knots[i + 1].trajectory, options));
    }
    // The first minimum: the pair nearest the root among equal differences.
    const std::size_t ind = static_cast<std::size_t>(
        std::distance(differences.begin(), std::min_element(differences.begin(), differences.end())));
    merge(knots[ind].trajectory, knots[ind + 1].trajectory, hasWidths ? &knots[ind].width : nullptr,
          knots[ind + 1].width, ind == 0, ind + 2 == knots.size(), options.keepEnds);
    knots[ind].merged += knots[ind + 1].merged;
    knots.erase(knots.begin() + static_cast<std::ptrdiff_t>(ind) + 1);
  }
  RefineResult result;
  result.frames.assign(frames.size(), std::vector<glm::vec3>(knots.size()));
  for (std::size_t k = 0; k < knots.size(); ++k) {
    for (std::size_t f = 0; f < frames.size(); ++f) {
      result.frames[f][k] = knots[k].trajectory[f];
    }
    if (hasWidths) {
      result.widths.push_back(knots[k].width);
    }
    result.merged.push_back(knots[k].merged);
  }
  return result;
}

RefineResult refineKnots(const KnotFrames& frames, std::span<const float> widths,
                         const RefineOptions& options) {
  const std::size_t inputKnots = validate(frames, widths, options);
  const auto target = static_cast<std::size_t>(options.knots);
  if (target >= inputKnots) {
    return unchanged(frames, widths);
  }
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  Trajectories t = knotMajor(frames, inputKnots);
  std::vector<float> knotWidths(widths.begin(), widths.end());
  const bool hasWidths = !widths.empty();
  // A doubly linked list of live knots; a merged knot keeps its left knot's id, so ids stay in root → tip
  // order.
  std::vector<std::uint32_t> prev(inputKnots);
  std::vector<std::uint32_t> next(inputKnots);
  std::vector<std::uint32_t> version(inputKnots, 0);
  std::vector<int> merged(inputKnots, 1);
  for (std::size_t k = 0; k < inputKnots; ++k) {
    prev[k] = k == 0 ? kNone : static_cast<std::uint32_t>(k - 1);
    next[k] = k + 1 == inputKnots ? kNone : static_cast<std::uint32_t>(k + 1);
  }

  // Min-heap of adjacent pairs by (D, left id); an entry is stale once either knot changed (version) or died
  // (a dead knot's version is bumped too). Equal D: the lower left id is the pair nearer the root, which is
  // what the reference's first minimum picks.
  struct Pair {
    double d;
    std::uint32_t left;
    std::uint32_t right;
    std::uint32_t leftVersion;
    std::uint32_t rightVersion;
  };
  const auto later = [](const Pair& a, const Pair& b) {
    return a.d > b.d || (a.d == b.d && a.left > b.left);
  };
  std::vector<Pair> heap;
  heap.reserve(3 * inputKnots);
  const auto push = [&](std::uint32_t left, std::uint32_t right) {
    heap.push_back(
        {difference(t.of(left), t.of(right), options), left, right, version[left], version[right]});
    std::push_heap(heap.begin(), heap.end(), later);
  };
  for (std::uint32_t k = 0; k + 1 < inputKnots; ++k) {
    heap.push_back({difference(t.of(k), t.of(k + 1), options), k, k + 1, 0, 0});
  }
  std::make_heap(heap.begin(), heap.end(), later);

  std::size_t count = inputKnots;
  while (count > target) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const Pair pair = heap.back();
    heap.pop_back();
    if (version[pair.left] != pair.leftVersion || version[pair.right] != pair.rightVersion) {
      continue;
    }
    const std::uint32_t left = pair.left;
    const std::uint32_t right = pair.right;
    const std::uint32_t after = next[right];
    merge(t.of(left), t.of(right), hasWidths ? &knotWidths[left] : nullptr,
          hasWidths ? knotWidths[right] : 0.0f, prev[left] == kNone, after == kNone, options.keepEnds);
    merged[left] += merged[right];
    ++version[left];
    ++version[right];
    next[left] = after;
    if (after != kNone) {
      prev[after] = left;
    }
    --count;
    if (prev[left] != kNone) {
      push(prev[left], left);
    }
    if (after != kNone) {
      push(left, after);
    }
  }

  RefineResult result;
  result.frames.assign(frames.size(), std::vector<glm::vec3>());
  for (auto& frame : result.frames) {
    frame.reserve(count);
  }
  for (std::uint32_t k = 0; k != kNone; k = next[k]) {
    const std::span<const glm::vec3> run = t.of(k);
    for (std::size_t f = 0; f < frames.size(); ++f) {
      result.frames[f].push_back(run[f]);
    }
    if (hasWidths) {
      result.widths.push_back(knotWidths[k]);
    }
    result.merged.push_back(merged[k]);
  }
  return result;
}

KnotFrames swayFrames(std::span<const glm::vec3> restKnots, const glm::vec3& axis,
                      const SwayOptions& options) {
  if (restKnots.size() < 2) {
    fail("sway: the blade has {} knots; at least 2 are needed", restKnots.size());
  }
  for (std::size_t k = 0; k < restKnots.size(); ++k) {
    if (!finite(restKnots[k])) {
      fail("sway: knot {}: position is not finite", k);
    }
  }
  if (!finite(axis) || glm::length(glm::dvec3(axis)) < 1e-12) {
    fail("sway: the bend axis ({}, {}, {}) is not a non-zero finite vector", axis.x, axis.y, axis.z);
  }
  if (options.frames < 1) {
    fail("sway: {} frames; at least 1 is needed", options.frames);
  }
  if (!(std::isfinite(options.fps) && options.fps > 0.0)) {
    fail("sway: fps = {} must be a finite number > 0", options.fps);
  }
  if (!std::isfinite(options.amplitude) || !std::isfinite(options.frequency) || !std::isfinite(options.lag)) {
    fail("sway: amplitude, frequency and lag must be finite");
  }
  const glm::dvec3 k = glm::normalize(glm::dvec3(axis));
  const std::size_t segmentCount = restKnots.size() - 1;
  std::vector<glm::dvec3> segments(segmentCount);
  std::vector<double> arcEnd(segmentCount);
  double length = 0.0;
  for (std::size_t i = 0; i < segmentCount; ++i) {
    segments[i] = glm::dvec3(restKnots[i + 1]) - glm::dvec3(restKnots[i]);
    length += glm::length(segments[i]);
    arcEnd[i] = length;
  }
  if (!(length > 0.0)) {
    fail("sway: the blade has zero length");
  }

  Rng rng(options.seed);
  KnotFrames frames(static_cast<std::size_t>(options.frames), std::vector<glm::vec3>(restKnots.size()));
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const double time = static_cast<double>(f) / options.fps;
    const double turbulence = 0.1 * options.amplitude * static_cast<double>(rng.uniform(-1.0f, 1.0f));
    glm::dvec3 p(restKnots[0]);
    frames[f][0] = restKnots[0];
    for (std::size_t i = 0; i < segmentCount; ++i) {
      const double u = arcEnd[i] / length;
      const double theta =
          (options.amplitude * std::sin(2.0 * std::numbers::pi * options.frequency * time - options.lag * u) +
           turbulence) *
          u * u;
      // Rodrigues: v cos θ + (k × v) sin θ + k (k · v)(1 − cos θ).
      const glm::dvec3& v = segments[i];
      const double c = std::cos(theta);
      const double s = std::sin(theta);
      p += v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.0 - c));
      frames[f][i + 1] = glm::vec3(p);
    }
  }
  return frames;
}

} // namespace sylva::capture
