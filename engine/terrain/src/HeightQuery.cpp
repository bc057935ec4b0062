#include <sylva/terrain/HeightQuery.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sylva::terrain {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/** a + t·(b − a), ignoring the side whose weight is exactly 0 (so an absent sample there does not matter). */
double lerpSkip(double a, double b, double t) {
  if (t == 0.0) {
    return a;
  }
  if (t == 1.0) {
    return b;
  }
  return a + t * (b - a);
}

/** Cell index and fraction along one axis for n samples; g is clamped to [0, n − 1]. */
struct AxisCell {
  int index = 0;
  double t = 0.0;
};
AxisCell axisCell(double g, int n) {
  g = std::clamp(g, 0.0, static_cast<double>(n - 1));
  AxisCell cell;
  cell.index = std::min(static_cast<int>(std::floor(g)), std::max(n - 2, 0));
  cell.t = g - cell.index;
  return cell;
}

std::array<double, 4> catmullRom(double t) {
  const double t2 = t * t;
  const double t3 = t2 * t;
  return {0.5 * (-t3 + 2.0 * t2 - t), 0.5 * (3.0 * t3 - 5.0 * t2 + 2.0), 0.5 * (-3.0 * t3 + 4.0 * t2 + t),
          0.5 * (t3 - t2)};
}

/** Interpolated height at grid coordinates (gx, gz), clamped to the grid; double precision. */
double heightGrid(const HeightField& f, double gx, double gz, Interpolation interpolation) {
  const int w = f.width();
  const int h = f.height();
  if (w < 1 || h < 1 || std::isnan(gx) || std::isnan(gz)) {
    return kNaN;
  }
  const AxisCell cx = axisCell(gx, w);
  const AxisCell cz = axisCell(gz, h);
  if (interpolation == Interpolation::Bilinear) {
    const int i1 = std::min(cx.index + 1, w - 1);
    const int j1 = std::min(cz.index + 1, h - 1);
    const auto row = [&](int j) { return lerpSkip(f.at(cx.index, j), f.at(i1, j), cx.t); };
    // Rows with weight 0 are not evaluated at all, so their absent samples cannot leak in.
    if (cz.t == 0.0) {
      return row(cz.index);
    }
    if (cz.t == 1.0) {
      return row(j1);
    }
    return lerpSkip(row(cz.index), row(j1), cz.t);
  }
  const std::array<double, 4> wx = catmullRom(cx.t);
  const std::array<double, 4> wz = catmullRom(cz.t);
  double sum = 0.0;
  for (int b = 0; b < 4; ++b) {
    if (wz[static_cast<std::size_t>(b)] == 0.0) {
      continue;
    }
    const int j = std::clamp(cz.index - 1 + b, 0, h - 1);
    double row = 0.0;
    for (int a = 0; a < 4; ++a) {
      if (wx[static_cast<std::size_t>(a)] == 0.0) {
        continue;
      }
      const int i = std::clamp(cx.index - 1 + a, 0, w - 1);
      row += wx[static_cast<std::size_t>(a)] * f.at(i, j);
    }
    sum += wz[static_cast<std::size_t>(b)] * row;
  }
  return sum;
}

/** Slope ∂h/∂(world axis) from heights at c − e (minus), c (centre), c + e (plus); see normalAt. */
double slope(double minus, double centre, double plus, double distMinus, double distPlus) {
  const bool haveMinus = !std::isnan(minus) && distMinus > 0.0;
  const bool havePlus = !std::isnan(plus) && distPlus > 0.0;
  if (haveMinus && havePlus) {
    return (plus - minus) / (distMinus + distPlus);
  }
  if (havePlus) {
    return (plus - centre) / distPlus;
  }
  if (haveMinus) {
    return (centre - minus) / distMinus;
  }
  return 0.0;
}

glm::dvec3 normalWorld(const HeightField& f, double x, double z, Interpolation interpolation) {
  const double sx = f.spacingX();
  const double sz = f.spacingZ();
  x = std::clamp(x, 0.0, static_cast<double>(std::max(f.width() - 1, 0)) * sx);
  z = std::clamp(z, 0.0, static_cast<double>(std::max(f.height() - 1, 0)) * sz);
  const auto h = [&](double wx, double wz) { return heightGrid(f, wx / sx, wz / sz, interpolation); };
  const double centre = h(x, z);
  if (std::isnan(centre)) {
    return glm::dvec3(kNaN);
  }
  const double extentX = static_cast<double>(f.width() - 1) * sx;
  const double extentZ = static_cast<double>(f.height() - 1) * sz;
  const double x0 = std::max(x - 0.5 * sx, 0.0);
  const double x1 = std::min(x + 0.5 * sx, extentX);
  const double z0 = std::max(z - 0.5 * sz, 0.0);
  const double z1 = std::min(z + 0.5 * sz, extentZ);
  const double dhdx = slope(h(x0, z), centre, h(x1, z), x - x0, x1 - x);
  const double dhdz = slope(h(x, z0), centre, h(x, z1), z - z0, z1 - z);
  return glm::normalize(glm::dvec3(-dhdx, 1.0, -dhdz));
}

/** Smallest root s ∈ [0, len] of C + B·s + A·s² given C > 0; negative if none. */
double firstRoot(double a, double b, double c, double len) {
  const double slack = 1e-12 * (1.0 + len);
  const auto inRange = [&](double s) { return s >= 0.0 && s <= len + slack; };
  if (a == 0.0) {
    if (b < 0.0) {
      const double s = -c / b;
      return inRange(s) ? std::min(s, len) : -1.0;
    }
    return -1.0;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) {
    return -1.0;
  }
  const double sq = std::sqrt(disc);
  // Numerically stable pair of roots (no cancellation between b and sq).
  const double q = -0.5 * (b + (b >= 0.0 ? sq : -sq));
  double best = -1.0;
  for (const double s : {q / a, q != 0.0 ? c / q : -1.0}) {
    if (inRange(s) && (best < 0.0 || s < best)) {
      best = std::min(s, len);
    }
  }
  return best;
}

} // namespace

float heightAt(const HeightField& field, float x, float z, Interpolation interpolation) {
  return static_cast<float>(heightGrid(field, static_cast<double>(x) / field.spacingX(),
                                       static_cast<double>(z) / field.spacingZ(), interpolation));
}

glm::vec3 normalAt(const HeightField& field, float x, float z, Interpolation interpolation) {
  return glm::vec3(normalWorld(field, x, z, interpolation));
}

std::optional<RayHit> raycast(const HeightField& field, const glm::vec3& origin, const glm::vec3& dir,
                              float maxDistance, Interpolation interpolation) {
  const double length = glm::length(glm::dvec3(dir));
  if (!std::isfinite(length) || length == 0.0) {
    fail("raycast: direction ({}, {}, {}) must be finite and non-zero", dir.x, dir.y, dir.z);
  }
  const int w = field.width();
  const int h = field.height();
  if (w < 2 || h < 2 || !(maxDistance >= 0.0f) || !std::isfinite(origin.x) || !std::isfinite(origin.y) ||
      !std::isfinite(origin.z)) {
    return std::nullopt;
  }
  const glm::dvec3 o(origin);
  const glm::dvec3 d = glm::dvec3(dir) / length;
  const double sx = field.spacingX();
  const double sz = field.spacingZ();

  // Clip the ray to the footprint box (slabs in x and z), t in metres along d.
  double tEnter = 0.0;
  double tExit = maxDistance;
  const auto clip = [&](double p, double v, double hi) {
    if (v == 0.0) {
      return p >= 0.0 && p <= hi;
    }
    double t0 = (0.0 - p) / v;
    double t1 = (hi - p) / v;
    if (t0 > t1) {
      std::swap(t0, t1);
    }
    tEnter = std::max(tEnter, t0);
    tExit = std::min(tExit, t1);
    return tEnter <= tExit;
  };
  if (!clip(o.x, d.x, (w - 1) * sx) || !clip(o.z, d.z, (h - 1) * sz)) {
    return std::nullopt;
  }

  const auto makeHit = [&](double t) {
    RayHit hit;
    hit.distance = static_cast<float>(t);
    hit.position = glm::vec3(o + d * t);
    hit.normal = glm::vec3(normalWorld(field, o.x + d.x * t, o.z + d.z * t, interpolation));
    return hit;
  };
  if (d.x == 0.0 && d.z == 0.0) {
    // Vertical ray: one column of constant ground height (and tExit may be infinite).
    const double ground = heightGrid(field, o.x / sx, o.z / sz, interpolation);
    if (std::isnan(ground)) {
      return std::nullopt;
    }
    const double above = o.y - ground;
    if (above <= 0.0) {
      return makeHit(0.0);
    }
    if (d.y < 0.0 && above / -d.y <= tExit) {
      return makeHit(above / -d.y);
    }
    return std::nullopt;
  }

  // Grid space: g = o_g + d_g · t with t still metres along d.
  const double gx0 = o.x / sx;
  const double gz0 = o.z / sz;
  const double dgx = d.x / sx;
  const double dgz = d.z / sz;
  // Clamp in double before converting: far-away origins may land slightly off the footprint after rounding.
  int ix = static_cast<int>(std::clamp(std::floor(gx0 + dgx * tEnter), 0.0, static_cast<double>(w - 2)));
  int iz = static_cast<int>(std::clamp(std::floor(gz0 + dgz * tEnter), 0.0, static_cast<double>(h - 2)));
  const int stepX = dgx > 0.0 ? 1 : -1;
  const int stepZ = dgz > 0.0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Distance at which the ray leaves the current cell through its x (z) side; computed from the boundary
  // index each time so no error accumulates.
  const auto exitX = [&](int i) { return dgx == 0.0 ? kInf : ((dgx > 0.0 ? i + 1 : i) - gx0) / dgx; };
  const auto exitZ = [&](int j) { return dgz == 0.0 ? kInf : ((dgz > 0.0 ? j + 1 : j) - gz0) / dgz; };

  const auto below = [&](double t) {
    return o.y + d.y * t - heightGrid(field, gx0 + dgx * t, gz0 + dgz * t, interpolation);
  };

  double t0 = tEnter;
  for (int guard = 0; guard < w + h + 4; ++guard) {
    const double tx = exitX(ix);
    const double tz = exitZ(iz);
    const double t1 = std::min({tx, tz, tExit});
    const double len = std::max(t1 - t0, 0.0);
    if (interpolation == Interpolation::Bilinear) {
      const double h00 = field.at(ix, iz);
      const double h10 = field.at(ix + 1, iz);
      const double h01 = field.at(ix, iz + 1);
      const double h11 = field.at(ix + 1, iz + 1);
      if (!std::isnan(h00 + h10 + h01 + h11)) {
        // h(u, v) = h00 + b·u + c·v + e·u·v in cell-local (u, v); along the ray u, v, y are linear in s = t −
        // t0, so y − h is the quadratic C + B·s + A·s².
        const double b = h10 - h00;
        const double c = h01 - h00;
        const double e = h00 - h10 - h01 + h11;
        const double u0 = gx0 + dgx * t0 - ix;
        const double v0 = gz0 + dgz * t0 - iz;
        const double y0 = o.y + d.y * t0;
        const double cc = y0 - (h00 + b * u0 + c * v0 + e * u0 * v0);
        if (cc <= 0.0) {
          return makeHit(t0);
        }
        const double bb = d.y - b * dgx - c * dgz - e * (u0 * dgz + v0 * dgx);
        const double aa = -e * dgx * dgz;
        const double s = firstRoot(aa, bb, cc, len);
        if (s >= 0.0) {
          return makeHit(t0 + s);
        }
      }
    } else {
      constexpr int kSteps = 8;
      std::array<double, kSteps + 1> f{};
      bool hole = false;
      for (int k = 0; k <= kSteps; ++k) {
        f[static_cast<std::size_t>(k)] = below(t0 + len * k / kSteps);
        hole = hole || std::isnan(f[static_cast<std::size_t>(k)]);
      }
      if (!hole) {
        if (f[0] <= 0.0) {
          return makeHit(t0);
        }
        for (int k = 1; k <= kSteps; ++k) {
          if (f[static_cast<std::size_t>(k)] <= 0.0) {
            double lo = t0 + len * (k - 1) / kSteps;
            double hi = t0 + len * k / kSteps;
            while (hi - lo > 1e-6) {
              const double mid = 0.5 * (lo + hi);
              const double fm = below(mid);
              (fm <= 0.0 || std::isnan(fm) ? hi : lo) = mid;
            }
            return makeHit(hi);
          }
        }
      }
    }
    if (t1 >= tExit) {
      break;
    }
    // Step to the next cell; on an exact corner both indices advance.
    if (tx <= tz) {
      ix += stepX;
    }
    if (tz <= tx) {
      iz += stepZ;
    }
    if (ix < 0 || ix > w - 2 || iz < 0 || iz > h - 2) {
      break;
    }
    t0 = t1;
  }
  return std::nullopt;
}

} // namespace sylva::terrain
