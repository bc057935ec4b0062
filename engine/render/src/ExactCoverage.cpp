#include <sylva/render/ExactCoverage.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::render {

namespace {

using Polygon = std::vector<glm::dvec4>;

/** Sutherland–Hodgman against the half-space distance(v) ≥ 0 (distance linear in clip space). */
template <typename Distance> Polygon clipAgainst(const Polygon& in, Distance distance) {
  Polygon out;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const glm::dvec4& a = in[i];
    const glm::dvec4& b = in[(i + 1) % in.size()];
    const double da = distance(a);
    const double db = distance(b);
    if (da >= 0.0) {
      out.push_back(a);
    }
    if ((da >= 0.0) != (db >= 0.0)) {
      out.push_back(a + (b - a) * (da / (da - db)));
    }
  }
  return out;
}

/** A clipped triangle in window space: a convex polygon with its vertices in counter-clockwise order. */
struct WindowPolygon {
  std::vector<glm::dvec3> v; // x, y in pixels, z = window depth
  glm::dvec2 lo{0.0};
  glm::dvec2 hi{0.0};
  // Window depth as an affine function of x and y: depth = a·x + b·y + c.
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
};

bool toWindow(const ClipTriangle& tri, glm::ivec2 viewport, WindowPolygon& out) {
  Polygon poly{glm::dvec4(tri.clip[0]), glm::dvec4(tri.clip[1]), glm::dvec4(tri.clip[2])};
  // w > 0 strictly: a tiny positive w keeps the projection finite; the near plane (z ≥ −w) lies inside it.
  constexpr double kMinW = 1e-12;
  poly = clipAgainst(poly, [](const glm::dvec4& p) { return p.w - kMinW; });
  poly = clipAgainst(poly, [](const glm::dvec4& p) { return p.z + p.w; });
  poly = clipAgainst(poly, [](const glm::dvec4& p) { return p.w - p.z; });
  if (poly.size() < 3) {
    return false;
  }
  out.v.clear();
  for (const glm::dvec4& p : poly) {
    out.v.emplace_back((p.x / p.w + 1.0) * 0.5 * viewport.x, (p.y / p.w + 1.0) * 0.5 * viewport.y,
                       (p.z / p.w + 1.0) * 0.5);
  }
  // Newell's normal of the (planar) polygon in window space: nz is twice its signed area, and the depth
  // plane z = z0 − (nx·(x − x0) + ny·(y − y0)) / nz.
  glm::dvec3 normal(0.0);
  for (std::size_t i = 0; i < out.v.size(); ++i) {
    const glm::dvec3& p = out.v[i];
    const glm::dvec3& q = out.v[(i + 1) % out.v.size()];
    normal += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  if (normal.z == 0.0 || !std::isfinite(normal.z)) {
    return false;
  }
  if (normal.z < 0.0) { // clockwise on screen: reverse so that inside is to the left of every edge
    std::reverse(out.v.begin(), out.v.end());
  }
  const glm::dvec3& p0 = out.v.front();
  out.a = -normal.x / normal.z;
  out.b = -normal.y / normal.z;
  out.c = p0.z - out.a * p0.x - out.b * p0.y;
  out.lo = glm::dvec2(std::numeric_limits<double>::infinity());
  out.hi = -out.lo;
  for (const glm::dvec3& p : out.v) {
    out.lo = glm::min(out.lo, glm::dvec2(p));
    out.hi = glm::max(out.hi, glm::dvec2(p));
  }
  return true;
}

/** Signed distance in pixels from `s` to the polygon's boundary (≥ 0 inside, < 0 outside). */
double insideDistance(const WindowPolygon& poly, const glm::dvec2& s) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.v.size(); ++i) {
    const glm::dvec2 a(poly.v[i]);
    const glm::dvec2 b(poly.v[(i + 1) % poly.v.size()]);
    const glm::dvec2 e = b - a;
    const double length = std::hypot(e.x, e.y);
    if (length == 0.0) {
      continue; // a repeated vertex: no edge
    }
    d = std::min(d, (e.x * (s.y - a.y) - e.y * (s.x - a.x)) / length);
  }
  return d;
}

} // namespace

std::vector<std::vector<ExactHit>> exactCoverage(std::span<const ClipTriangle> triangles, glm::ivec2 viewport,
                                                 std::span<const glm::dvec2> samples) {
  std::vector<std::vector<ExactHit>> hits(samples.size());
  WindowPolygon poly;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!toWindow(triangles[t], viewport, poly)) {
      continue;
    }
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const glm::dvec2& s = samples[k];
      if (s.x < poly.lo.x || s.x > poly.hi.x || s.y < poly.lo.y || s.y > poly.hi.y) {
        continue;
      }
      const double distance = insideDistance(poly, s);
      if (distance >= 0.0) {
        hits[k].push_back({t, triangles[t].tag, poly.a * s.x + poly.b * s.y + poly.c, distance});
      }
    }
  }
  for (std::vector<ExactHit>& list : hits) {
    std::stable_sort(list.begin(), list.end(),
                     [](const ExactHit& x, const ExactHit& y) { return x.depth < y.depth; });
  }
  return hits;
}

} // namespace sylva::render
