#include <sylva/terrain/ScreenError.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightQuery.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace sylva::terrain {

namespace {

/**
 * The heights of the two diagonal triangulations of the reference cell containing (x, z), low and high: a
 * cell of the sample grid (lattice 0) or of a square lattice of that spacing from the origin whose corner
 * heights are heightAt. False when outside the field or next to an absent sample.
 */
bool fullResolutionInterval(const HeightField& field, float lattice, float x, float z, float& lo, float& hi) {
  if (!(x >= 0.0f && z >= 0.0f && x <= field.extentX() && z <= field.extentZ())) {
    return false;
  }
  float fx = 0.0f;
  float fz = 0.0f;
  float h00 = 0.0f;
  float h10 = 0.0f;
  float h01 = 0.0f;
  float h11 = 0.0f;
  if (lattice > 0.0f) {
    const float u = x / lattice;
    const float v = z / lattice;
    const float i = std::floor(u);
    const float j = std::floor(v);
    fx = u - i;
    fz = v - j;
    h00 = heightAt(field, i * lattice, j * lattice);
    h10 = heightAt(field, (i + 1.0f) * lattice, j * lattice);
    h01 = heightAt(field, i * lattice, (j + 1.0f) * lattice);
    h11 = heightAt(field, (i + 1.0f) * lattice, (j + 1.0f) * lattice);
  } else {
    const float u = x / field.spacingX();
    const float v = z / field.spacingZ();
    const int i = std::clamp(static_cast<int>(u), 0, field.width() - 2);
    const int j = std::clamp(static_cast<int>(v), 0, field.height() - 2);
    fx = u - static_cast<float>(i);
    fz = v - static_cast<float>(j);
    h00 = field.at(i, j);
    h10 = field.at(i + 1, j);
    h01 = field.at(i, j + 1);
    h11 = field.at(i + 1, j + 1);
  }
  // Diagonal 00–11, then diagonal 10–01.
  const float a =
      fz <= fx ? h00 + (h10 - h00) * fx + (h11 - h10) * fz : h00 + (h11 - h01) * fx + (h01 - h00) * fz;
  const float b = fx + fz <= 1.0f ? h00 + (h10 - h00) * fx + (h01 - h00) * fz
                                  : h11 + (h01 - h11) * (1.0f - fx) + (h10 - h11) * (1.0f - fz);
  if (std::isnan(a) || std::isnan(b)) {
    return false;
  }
  lo = std::min(a, b);
  hi = std::max(a, b);
  return true;
}

} // namespace

float fullResolutionGap(const HeightField& field, const glm::vec3& p, float latticeSpacing) {
  float lo = 0.0f;
  float hi = 0.0f;
  if (!fullResolutionInterval(field, latticeSpacing, p.x, p.z, lo, hi)) {
    return std::numeric_limits<float>::quiet_NaN();
  }
  return p.y < lo ? lo - p.y : p.y > hi ? p.y - hi : 0.0f;
}

ScreenErrorStats measureScreenError(const HeightField& field, const Image& positions, const Image& reference,
                                    const glm::mat4& viewProj, float latticeSpacing) {
  if (!(latticeSpacing > 0.0f)) {
    fail("measureScreenError: lattice spacing {} m must be positive", latticeSpacing);
  }
  for (const Image* image : {&positions, &reference}) {
    if (image->channels() != 4 || image->type() != PixelType::F32) {
      fail("measureScreenError: positions must be 4-channel float images");
    }
  }
  if (positions.width() != reference.width() || positions.height() != reference.height()) {
    fail("measureScreenError: {}x{} positions against a {}x{} reference", positions.width(),
         positions.height(), reference.width(), reference.height());
  }
  const float halfW = 0.5f * static_cast<float>(positions.width());
  const float halfH = 0.5f * static_cast<float>(positions.height());
  const auto screen = [&](const glm::vec3& w) {
    const glm::vec4 c = viewProj * glm::vec4(w, 1.0f);
    return glm::vec2(c.x / c.w * halfW, c.y / c.w * halfH);
  };
  const float step = 0.5f * std::min(field.spacingX(), field.spacingZ());
  constexpr int kWindow = 3; // reference pixels searched around each pixel, each way
  const float farAway = 4.0f * latticeSpacing * latticeSpacing; // (2 lattice spacings)²
  std::vector<float> errors;
  errors.reserve(static_cast<std::size_t>(positions.width()) * static_cast<std::size_t>(positions.height()));
  ScreenErrorStats stats;
  double sum = 0.0;
  for (int y = 0; y < positions.height(); ++y) {
    for (int x = 0; x < positions.width(); ++x) {
      const bool drawn = positions.get(x, y, 3) > 0.0f;
      const bool ref = reference.get(x, y, 3) > 0.0f;
      if (drawn != ref) {
        ++stats.coverageMismatch;
      }
      if (!drawn || !ref) {
        continue;
      }
      const glm::vec3 p(positions.get(x, y, 0), positions.get(x, y, 1), positions.get(x, y, 2));
      // The reference point nearest P in xz within the window: on the same ray at most pixels, a few pixels
      // away where a silhouette moved (there the ray's own reference point lies on another slope).
      glm::vec3 r(reference.get(x, y, 0), reference.get(x, y, 1), reference.get(x, y, 2));
      float nearest = glm::dot(glm::vec2(p.x - r.x, p.z - r.z), glm::vec2(p.x - r.x, p.z - r.z));
      for (int wy = std::max(y - kWindow, 0);
           nearest > 0.0f && wy <= std::min(y + kWindow, reference.height() - 1); ++wy) {
        for (int wx = std::max(x - kWindow, 0); wx <= std::min(x + kWindow, reference.width() - 1); ++wx) {
          if (!(reference.get(wx, wy, 3) > 0.0f)) {
            continue;
          }
          const glm::vec3 q(reference.get(wx, wy, 0), reference.get(wx, wy, 1), reference.get(wx, wy, 2));
          const float d2 = (p.x - q.x) * (p.x - q.x) + (p.z - q.z) * (p.z - q.z);
          if (d2 < nearest) {
            nearest = d2;
            r = q;
          }
        }
      }
      const glm::vec3 d = p - r;
      float px = 0.0f;
      if (nearest > farAway) {
        // The reference surface at P's xz is hidden in the reference view (a silhouette moved, or a grazing
        // ray runs on): compare with the reference lattice, triangulated either way.
        float lo = 0.0f;
        float hi = 0.0f;
        if (!fullResolutionInterval(field, latticeSpacing, p.x, p.z, lo, hi)) {
          continue;
        }
        if (p.y < lo || p.y > hi) {
          px = glm::length(screen(p) - screen({p.x, p.y < lo ? lo : hi, p.z}));
        }
      } else if (d != glm::vec3(0.0f)) {
        // Tangent plane of the reference surface at R: y = R.y + gx·(x − R.x) + gz·(z − R.z).
        const float gx =
            (heightAt(field, r.x + step, r.z) - heightAt(field, r.x - step, r.z)) / (2.0f * step);
        const float gz =
            (heightAt(field, r.x, r.z + step) - heightAt(field, r.x, r.z - step)) / (2.0f * step);
        const float offset = d.y - gx * d.x - gz * d.z;
        if (std::isnan(offset)) {
          continue;
        }
        px = glm::length(screen(p) - screen({p.x, p.y - offset, p.z}));
      }
      errors.push_back(px);
      sum += px;
    }
  }
  stats.pixels = errors.size();
  if (errors.empty()) {
    return stats;
  }
  stats.meanPx = sum / static_cast<double>(errors.size());
  const auto k = static_cast<std::size_t>(std::floor(0.999 * static_cast<double>(errors.size() - 1)));
  std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
  stats.p999Px = errors[k];
  stats.worstPx = *std::max_element(errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
  return stats;
}

} // namespace sylva::terrain
