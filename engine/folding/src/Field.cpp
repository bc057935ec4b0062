// Jump fields: anchors from the tools, Shepard-family interpolation over a uniform grid, mean-value deforms,
// polygon utilities and fold intervals (thresholds).
#include <sylva/folding/Field.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::folding {

namespace {

double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}

/** Points every `spacing` pixels along a polyline (closed when `closed`), vertices included. */
std::vector<Vec2> samplePolyline(std::span<const Vec2> pts, bool closed, double spacing) {
  std::vector<Vec2> out;
  const std::size_t n = pts.size();
  if (n == 1) {
    out.push_back(pts[0]);
    return out;
  }
  const std::size_t edges = closed ? n : n - 1;
  for (std::size_t i = 0; i < edges; ++i) {
    const Vec2 a = pts[i];
    const Vec2 b = pts[(i + 1) % n];
    const int steps = std::max(1, static_cast<int>(std::ceil(glm::length(b - a) / spacing)));
    for (int s = 0; s < steps; ++s) {
      out.push_back(a + (b - a) * (static_cast<double>(s) / steps));
    }
  }
  if (!closed) {
    out.push_back(pts[n - 1]);
  }
  return out;
}

/** Forward motion vector at arc-length parameter u, linear between the given (u, v) entries. */
Vec2 vectorAlong(const std::vector<std::pair<double, Vec2>>& vectors, double u) {
  if (u <= vectors.front().first) {
    return vectors.front().second;
  }
  for (std::size_t i = 1; i < vectors.size(); ++i) {
    if (u <= vectors[i].first) {
      const double f = (u - vectors[i - 1].first) / (vectors[i].first - vectors[i - 1].first);
      return glm::mix(vectors[i - 1].second, vectors[i].second, f);
    }
  }
  return vectors.back().second;
}

} // namespace

// ---------------------------------------------------------------------------------------------------------
// Interpolation

double ringHash(std::uint64_t pixelId, std::uint64_t anchorId, std::uint64_t seed) {
  const std::uint64_t h = hash64(hash64(hash64(seed) ^ pixelId) ^ (anchorId * 0x9e3779b97f4a7c15ULL));
  return static_cast<double>(h >> 11) * 0x1.0p-53;
}

AnchorField::AnchorField(std::vector<Anchor> anchors, const Interpolation& interp, std::uint64_t seed)
    : mAnchors(std::move(anchors)), mInterp(interp), mSeed(seed) {
  if (mInterp.type == Interpolation::Type::Shepard || mAnchors.empty()) {
    return;
  }
  Vec2 lo(std::numeric_limits<double>::max());
  Vec2 hi(std::numeric_limits<double>::lowest());
  for (const Anchor& a : mAnchors) {
    lo = glm::min(lo, a.position);
    hi = glm::max(hi, a.position);
  }
  // Cells of size R, so a query visits the 3×3 cells around it; sparse anchors over a large area with a small
  // R would need many empty cells, so the cell grows until the grid has at most ~4 cells per anchor.
  double cell = mInterp.radius;
  const double budget = 4.0 * static_cast<double>(mAnchors.size()) + 1024.0;
  while (((hi.x - lo.x) / cell + 1.0) * ((hi.y - lo.y) / cell + 1.0) > budget) {
    cell *= 2.0;
  }
  mCell = cell;
  mOrigin = lo;
  mCellsX = static_cast<int>((hi.x - lo.x) / cell) + 1;
  mCellsY = static_cast<int>((hi.y - lo.y) / cell) + 1;
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(mCellsX) * mCellsY + 1, 0);
  auto cellOf = [&](Vec2 p) {
    const int cx = std::clamp(static_cast<int>((p.x - lo.x) / cell), 0, mCellsX - 1);
    const int cy = std::clamp(static_cast<int>((p.y - lo.y) / cell), 0, mCellsY - 1);
    return static_cast<std::size_t>(cy) * mCellsX + cx;
  };
  for (const Anchor& a : mAnchors) {
    ++counts[cellOf(a.position) + 1];
  }
  for (std::size_t i = 1; i < counts.size(); ++i) {
    counts[i] += counts[i - 1];
  }
  mCellStart = counts;
  mCellItems.resize(mAnchors.size());
  for (std::size_t i = 0; i < mAnchors.size(); ++i) {
    mCellItems[counts[cellOf(mAnchors[i].position)]++] = static_cast<std::uint32_t>(i);
  }
}

Vec2 AnchorField::evaluate(Vec2 x, std::uint64_t pixelId) const {
  if (mAnchors.empty()) {
    return Vec2(0.0);
  }
  Vec2 sum(0.0);
  double weights = 0.0;
  if (mInterp.type == Interpolation::Type::Shepard) {
    const bool squared = mInterp.power == 2.0;
    for (const Anchor& a : mAnchors) {
      const Vec2 d = x - a.position;
      const double d2 = glm::dot(d, d);
      if (d2 == 0.0) {
        return a.vector;
      }
      const double w = squared ? 1.0 / d2 : std::pow(d2, -0.5 * mInterp.power);
      sum += w * a.vector;
      weights += w;
    }
    return sum / weights;
  }
  const double r = mInterp.radius;
  const double r2 = r * r;
  const bool random = mInterp.type == Interpolation::Type::ModifiedShepardRandom;
  const double inner = r - mInterp.ring;
  const int reach = static_cast<int>(std::ceil(r / mCell));
  const int cx = static_cast<int>(std::floor((x.x - mOrigin.x) / mCell));
  const int cy = static_cast<int>(std::floor((x.y - mOrigin.y) / mCell));
  // Visit candidates in anchor-index order within each cell; the sum's order depends only on x, never on
  // threads, so results are reproducible.
  for (int y = std::max(0, cy - reach); y <= std::min(mCellsY - 1, cy + reach); ++y) {
    for (int xx = std::max(0, cx - reach); xx <= std::min(mCellsX - 1, cx + reach); ++xx) {
      const std::size_t cell = static_cast<std::size_t>(y) * mCellsX + xx;
      for (std::uint32_t k = mCellStart[cell]; k < mCellStart[cell + 1]; ++k) {
        const std::uint32_t i = mCellItems[k];
        const Anchor& a = mAnchors[i];
        const Vec2 dv = x - a.position;
        const double d2 = glm::dot(dv, dv);
        if (d2 >= r2) {
          continue;
        }
        if (d2 == 0.0) {
          return a.vector;
        }
        const double d = std::sqrt(d2);
        if (random && d > inner && ringHash(pixelId, i, mSeed) >= (r - d) / mInterp.ring) {
          continue;
        }
        const double f = (r - d) / (r * d);
        const double w = f * f;
        sum += w * a.vector;
        weights += w;
      }
    }
  }
  return weights > 0.0 ? sum / weights : Vec2(0.0);
}

// ---------------------------------------------------------------------------------------------------------
// Polygons

bool insidePolygon(std::span<const Vec2> polygon, Vec2 p) {
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2 a = polygon[i];
    const Vec2 b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
      inside = !inside;
    }
  }
  return inside;
}

double signedArea(std::span<const Vec2> polygon) {
  double area = 0.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    area += cross(polygon[i], polygon[(i + 1) % n]);
  }
  return 0.5 * area;
}

namespace {
int orientation(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return v > 0.0 ? 1 : v < 0.0 ? -1 : 0;
}
bool onSegment(Vec2 a, Vec2 b, Vec2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}
bool segmentsTouch(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int o1 = orientation(a, b, c);
  const int o2 = orientation(a, b, d);
  const int o3 = orientation(c, d, a);
  const int o4 = orientation(c, d, b);
  if (o1 != o2 && o3 != o4) {
    return true;
  }
  return (o1 == 0 && onSegment(a, b, c)) || (o2 == 0 && onSegment(a, b, d)) ||
         (o3 == 0 && onSegment(c, d, a)) || (o4 == 0 && onSegment(c, d, b));
}
} // namespace

bool selfIntersects(std::span<const Vec2> polygon) {
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = polygon[i];
    const Vec2 b = polygon[(i + 1) % n];
    if (a == b) {
      return true; // repeated vertex
    }
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const Vec2 c = polygon[j];
      const Vec2 d = polygon[(j + 1) % n];
      if (adjacent) {
        // Adjacent edges share one vertex; they overlap only if they fold back on each other.
        const Vec2 shared = j == i + 1 ? b : a;
        const Vec2 p = j == i + 1 ? a : b;
        const Vec2 q = j == i + 1 ? d : c;
        if (orientation(shared, p, q) == 0 && glm::dot(p - shared, q - shared) > 0.0) {
          return true;
        }
        continue;
      }
      if (segmentsTouch(a, b, c, d)) {
        return true;
      }
    }
  }
  return false;
}

std::vector<double> meanValueCoordinates(std::span<const Vec2> polygon, Vec2 p) {
  const std::size_t n = polygon.size();
  std::vector<double> lambda(n, 0.0);
  std::vector<Vec2> s(n);
  std::vector<double> r(n);
  for (std::size_t i = 0; i < n; ++i) {
    s[i] = polygon[i] - p;
    r[i] = glm::length(s[i]);
    if (r[i] == 0.0) {
      lambda[i] = 1.0;
      return lambda;
    }
  }
  std::vector<double> area(n);
  std::vector<double> dotp(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    area[i] = 0.5 * cross(s[i], s[j]);
    dotp[i] = glm::dot(s[i], s[j]);
    if (std::abs(area[i]) <= 1e-12 * r[i] * r[j] && dotp[i] < 0.0) {
      // p lies on edge (i, j): linear interpolation along it.
      lambda[i] = r[j] / (r[i] + r[j]);
      lambda[j] = r[i] / (r[i] + r[j]);
      return lambda;
    }
  }
  // Hormann–Floater: w_i = (r_{i−1} − D_{i−1}/r_i)/A_{i−1} + (r_{i+1} − D_i/r_i)/A_i.
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n;
    const std::size_t next = (i + 1) % n;
    double w = 0.0;
    if (area[prev] != 0.0) {
      w += (r[prev] - dotp[prev] / r[i]) / area[prev];
    }
    if (area[i] != 0.0) {
      w += (r[next] - dotp[i] / r[i]) / area[i];
    }
    lambda[i] = w;
    total += w;
  }
  for (double& l : lambda) {
    l /= total;
  }
  return lambda;
}

// ---------------------------------------------------------------------------------------------------------
// Curves

Vec2 bezier(const std::array<Vec2, 4>& c, double u) {
  const double v = 1.0 - u;
  return v * v * v * c[0] + 3.0 * v * v * u * c[1] + 3.0 * v * u * u * c[2] + u * u * u * c[3];
}

std::vector<double> arcLengthParameters(const std::array<Vec2, 4>& c, int samples) {
  constexpr int kFine = 1024;
  std::vector<double> length(kFine + 1, 0.0);
  Vec2 prev = c[0];
  for (int i = 1; i <= kFine; ++i) {
    const Vec2 p = bezier(c, static_cast<double>(i) / kFine);
    length[i] = length[i - 1] + glm::length(p - prev);
    prev = p;
  }
  std::vector<double> u(static_cast<std::size_t>(samples));
  const double total = length[kFine];
  for (int j = 0; j < samples; ++j) {
    const double target = total * j / (samples - 1);
    if (total <= 0.0) {
      u[j] = static_cast<double>(j) / (samples - 1);
      continue;
    }
    const auto it = std::lower_bound(length.begin(), length.end(), target);
    const std::size_t k = std::clamp<std::size_t>(static_cast<std::size_t>(it - length.begin()), 1, kFine);
    const double seg = length[k] - length[k - 1];
    const double f = seg > 0.0 ? (target - length[k - 1]) / seg : 0.0;
    u[j] = (static_cast<double>(k - 1) + std::clamp(f, 0.0, 1.0)) / kFine;
  }
  u.front() = 0.0;
  u.back() = 1.0;
  return u;
}

// ---------------------------------------------------------------------------------------------------------
// Thresholds

namespace {
std::vector<Interval> unionOf(std::vector<Interval> all) {
  std::sort(all.begin(), all.end(), [](const Interval& a, const Interval& b) { return a.t0 < b.t0; });
  std::vector<Interval> out;
  for (const Interval& iv : all) {
    if (!out.empty() && iv.t0 <= out.back().t1) {
      out.back().t1 = std::max(out.back().t1, iv.t1);
    } else {
      out.push_back(iv);
    }
  }
  return out;
}
} // namespace

std::vector<Interval> foldIntervals(std::span<const std::vector<Vec2>> polygons, Vec2 q, Vec2 jump) {
  // One pass per polygon: the even-odd ray test of q and the path-edge hits share the edge loop; a miss costs
  // no division (signs are compared with den instead), and a polygon whose box the path cannot reach is
  // skipped. Scratch storage is per thread, so the per-pixel call allocates only its result.
  thread_local std::vector<double> hits;
  thread_local std::vector<Interval> all;
  all.clear();
  const Vec2 lo = glm::min(q, q + jump);
  const Vec2 hi = glm::max(q, q + jump);
  for (const std::vector<Vec2>& poly : polygons) {
    const std::size_t n = poly.size();
    hits.clear();
    bool inside = false;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Vec2 a = poly[i];
      const Vec2 b = poly[j];
      // Even-odd crossing of the ray from q towards +x (the same rule as insidePolygon).
      if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x) {
        inside = !inside;
      }
      // Edge (b → a) against the path; skip edges whose box misses the path's box.
      if (std::max(a.x, b.x) < lo.x || std::min(a.x, b.x) > hi.x || std::max(a.y, b.y) < lo.y ||
          std::min(a.y, b.y) > hi.y) {
        continue;
      }
      const Vec2 e = a - b;
      const double den = cross(jump, e);
      if (std::abs(den) < 1e-12) {
        continue; // parallel: the path runs along the edge or misses it
      }
      const double ns = cross(b - q, e);
      const double nr = cross(b - q, jump);
      const double sign = den > 0.0 ? 1.0 : -1.0;
      const double ad = std::abs(den);
      if (ns * sign >= 0.0 && ns * sign <= ad && nr * sign >= 0.0 && nr * sign < ad) {
        hits.push_back(ns / den);
      }
    }
    std::sort(hits.begin(), hits.end());
    double start = 0.0;
    for (double s : hits) {
      if (inside && s > start) {
        all.push_back({start, s});
      }
      inside = !inside;
      start = s;
    }
    if (inside && start < 1.0) {
      all.push_back({start, 1.0});
    } else if (inside && hits.empty()) {
      all.push_back({0.0, 1.0});
    }
  }
  if (all.size() <= 1) {
    return {all.begin(), all.end()};
  }
  return unionOf({all.begin(), all.end()});
}

std::vector<Interval> foldIntervalsFromMask(std::span<const float> mask, int width, int height, Vec2 q,
                                            Vec2 jump) {
  const int steps = std::max(1, static_cast<int>(std::ceil(glm::length(jump))));
  auto insideAt = [&](int i) {
    const Vec2 p = q + jump * (static_cast<double>(i) / steps);
    const int x = static_cast<int>(std::floor(p.x));
    const int y = static_cast<int>(std::floor(p.y));
    if (x < 0 || y < 0 || x >= width || y >= height) {
      return false;
    }
    return mask[static_cast<std::size_t>(y) * width + x] >= 0.5f;
  };
  // A run of inside samples i..j becomes (midpoint before i, midpoint after j], so the steps converge on the
  // exact crossings as J grows.
  std::vector<Interval> out;
  int runStart = -1;
  for (int i = 0; i <= steps; ++i) {
    const bool in = insideAt(i);
    if (in && runStart < 0) {
      runStart = i;
    }
    if ((!in || i == steps) && runStart >= 0) {
      const int last = in ? i : i - 1;
      const double t0 = runStart == 0 ? 0.0 : (runStart - 0.5) / steps;
      const double t1 = last == steps ? 1.0 : (last + 0.5) / steps;
      out.push_back({t0, t1});
      runStart = -1;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// Tools → anchors and fields

std::vector<Anchor> zoneAnchors(const Zone& zone, std::span<const float> freezeMask, glm::ivec2 imageSize) {
  std::vector<Anchor> anchors;
  const double spacing = zone.zeroSpacing;
  for (const Tool& tool : zone.tools) {
    if (const auto* points = std::get_if<PointsTool>(&tool)) {
      for (const auto& [a, b] : points->pairs) {
        anchors.push_back({b, a - b});
      }
    } else if (const auto* curve = std::get_if<CurveTool>(&tool)) {
      const std::vector<double> us = arcLengthParameters(curve->source, curve->samples);
      if (curve->dest) {
        const std::vector<double> ud = arcLengthParameters(*curve->dest, curve->samples);
        for (int j = 0; j < curve->samples; ++j) {
          const Vec2 d = bezier(*curve->dest, ud[j]);
          anchors.push_back({d, bezier(curve->source, us[j]) - d});
        }
      } else {
        for (int j = 0; j < curve->samples; ++j) {
          const Vec2 a = bezier(curve->source, us[j]);
          const Vec2 v = vectorAlong(curve->vectors, static_cast<double>(j) / (curve->samples - 1));
          anchors.push_back({a + v, -v});
        }
      }
    } else if (const auto* lasso = std::get_if<LassoTool>(&tool)) {
      // Vertices and points along the edges, so the motion outside follows the whole outline.
      const std::size_t n = lasso->to.size();
      for (std::size_t i = 0; i < n; ++i) {
        const Vec2 d0 = lasso->to[i];
        const Vec2 d1 = lasso->to[(i + 1) % n];
        const Vec2 v0 = lasso->from[i] - d0;
        const Vec2 v1 = lasso->from[(i + 1) % n] - d1;
        const int steps = std::max(1, static_cast<int>(std::ceil(glm::length(d1 - d0) / spacing)));
        for (int s = 0; s < steps; ++s) {
          const double f = static_cast<double>(s) / steps;
          anchors.push_back({glm::mix(d0, d1, f), glm::mix(v0, v1, f)});
        }
      }
    } else if (const auto* zero = std::get_if<ZeroTool>(&tool)) {
      for (const Vec2& p : samplePolyline(zero->pts, false, spacing)) {
        anchors.push_back({p, Vec2(0.0)});
      }
    }
  }
  if (zone.zeroBoundary) {
    const std::vector<Vec2> outline = zone.shape.outline();
    for (const Vec2& p : samplePolyline(outline, true, spacing)) {
      anchors.push_back({p, Vec2(0.0)});
    }
  }
  if (!freezeMask.empty()) {
    // Frozen pixels on the mask's border become zero anchors, one per cell of `spacing` pixels.
    const int w = imageSize.x;
    const int h = imageSize.y;
    const int step = std::max(1, static_cast<int>(spacing));
    std::vector<std::uint8_t> taken(static_cast<std::size_t>((w + step - 1) / step) * ((h + step - 1) / step),
                                    0);
    auto frozen = [&](int x, int y) {
      return x >= 0 && y >= 0 && x < w && y < h && freezeMask[static_cast<std::size_t>(y) * w + x] >= 0.5f;
    };
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        if (!frozen(x, y) || (frozen(x - 1, y) && frozen(x + 1, y) && frozen(x, y - 1) && frozen(x, y + 1))) {
          continue;
        }
        std::uint8_t& cell = taken[static_cast<std::size_t>(y / step) * ((w + step - 1) / step) + x / step];
        if (!cell) {
          cell = 1;
          anchors.push_back({Vec2(x + 0.5, y + 0.5), Vec2(0.0)});
        }
      }
    }
  }
  return anchors;
}

Vec2 baseJump(const Zone& zone, Vec2 x) {
  Vec2 j(0.0);
  for (const Tool& tool : zone.tools) {
    if (const auto* t = std::get_if<TranslateTool>(&tool)) {
      j -= t->v;
    } else if (const auto* s = std::get_if<ScaleTool>(&tool)) {
      j += (x - s->centre) * (1.0 / s->factor - 1.0);
    } else if (const auto* f = std::get_if<FlyOverTool>(&tool)) {
      j += f->from - f->to;
    }
  }
  return j;
}

namespace {
std::vector<Anchor> residuals(const Zone& zone, std::vector<Anchor> anchors) {
  for (Anchor& a : anchors) {
    a.vector -= baseJump(zone, a.position);
  }
  return anchors;
}
} // namespace

ZoneField::ZoneField(const Zone& zone, std::span<const float> freezeMask, glm::ivec2 imageSize,
                     std::uint64_t seed)
    : mZone(&zone), mFreeze(freezeMask), mImageSize(imageSize),
      mField(residuals(zone, zoneAnchors(zone, freezeMask, imageSize)), zone.interp, seed) {
  for (const Tool& tool : zone.tools) {
    if (const auto* lasso = std::get_if<LassoTool>(&tool); lasso && lasso->meanValue) {
      Deform deform;
      deform.polygon = lasso->to;
      for (std::size_t i = 0; i < lasso->to.size(); ++i) {
        deform.vectors.push_back(lasso->from[i] - lasso->to[i]);
      }
      mDeforms.push_back(std::move(deform));
    }
  }
}

Vec2 ZoneField::evaluate(Vec2 x, std::uint64_t pixelId) const {
  if (!mFreeze.empty()) {
    const int px = static_cast<int>(std::floor(x.x));
    const int py = static_cast<int>(std::floor(x.y));
    if (px >= 0 && py >= 0 && px < mImageSize.x && py < mImageSize.y &&
        mFreeze[static_cast<std::size_t>(py) * mImageSize.x + px] >= 0.5f) {
      return Vec2(0.0);
    }
  }
  for (const Deform& deform : mDeforms) {
    if (insidePolygon(deform.polygon, x)) {
      const std::vector<double> lambda = meanValueCoordinates(deform.polygon, x);
      Vec2 j(0.0);
      for (std::size_t i = 0; i < lambda.size(); ++i) {
        j += lambda[i] * deform.vectors[i];
      }
      return j;
    }
  }
  return baseJump(*mZone, x) + mField.evaluate(x, pixelId);
}

} // namespace sylva::folding
