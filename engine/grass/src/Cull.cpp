#include <sylva/grass/Cull.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Geometry.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::grass {

void validate(const CullSettings& s) {
  const std::pair<float, const char*> values[] = {{s.maxDistance, "maxDistance"},
                                                  {s.lodDistances[0], "lodDistances[0]"},
                                                  {s.lodDistances[1], "lodDistances[1]"},
                                                  {s.lodFade, "lodFade"},
                                                  {s.farFade, "farFade"},
                                                  {s.orientationDistance, "orientationDistance"},
                                                  {s.orientationCos, "orientationCos"}};
  for (const auto& [v, name] : values) {
    if (!std::isfinite(v) || v < 0.0f) {
      fail("grass culling: {} must be a finite number ≥ 0, got {}", name, v);
    }
  }
  if (s.lodDistances[0] > s.lodDistances[1]) {
    fail("grass culling: lodDistances must increase, got {} then {}", s.lodDistances[0], s.lodDistances[1]);
  }
  if (s.farFade > s.maxDistance) {
    fail("grass culling: farFade {} m is longer than maxDistance {} m", s.farFade, s.maxDistance);
  }
  const float half = 0.5f * s.lodFade;
  if (s.lodDistances[0] + half > s.lodDistances[1] - half ||
      s.lodDistances[1] + half > s.maxDistance - s.farFade || s.lodDistances[0] < half) {
    fail("grass culling: lodFade {} m makes the bands around lodDistances {} and {} m overlap each other, "
         "the camera or the far fade (which starts at {} m)",
         s.lodFade, s.lodDistances[0], s.lodDistances[1], s.maxDistance - s.farFade);
  }
}

CullSettings scaled(const CullSettings& s, float factor) {
  if (!(factor > 0.0f) || !std::isfinite(factor)) {
    fail("grass culling: distance factor {} must be > 0", factor);
  }
  CullSettings c = s;
  c.maxDistance *= factor;
  c.lodDistances[0] *= factor;
  c.lodDistances[1] *= factor;
  c.lodFade *= factor;
  c.farFade *= factor;
  c.orientationDistance *= factor;
  return c;
}

int lodForDistance(const CullSettings& s, float distance) {
  return distance < s.lodDistances[0] ? 0 : distance < s.lodDistances[1] ? 1 : 2;
}

void lodInstances(const CullSettings& s, float distance, std::vector<VisibleBlade>& out) {
  // grassLodInstances() in shaders/grass/cull.comp, in the same order.
  if (distance > s.maxDistance) {
    return;
  }
  const float half = 0.5f * s.lodFade;
  for (int k = 0; k < 2; ++k) {
    const float start = s.lodDistances[static_cast<std::size_t>(k)] - half;
    if (s.lodFade > 0.0f && distance >= start && distance < start + s.lodFade) {
      const float amount = (distance - start) / s.lodFade;
      out.push_back({{}, k, Fade::FadeOut, amount});
      out.push_back({{}, k + 1, Fade::FadeIn, amount});
      return;
    }
  }
  const int lod = lodForDistance(s, distance);
  const float farStart = s.maxDistance - s.farFade;
  if (s.farFade > 0.0f && distance >= farStart) {
    out.push_back({{}, lod, Fade::FadeOut, std::min((distance - farStart) / s.farFade, 1.0f)});
    return;
  }
  out.push_back({{}, lod, Fade::Full, 0.0f});
}

CullStats cullField(const GrassField& field, const glm::mat4& viewProj, const glm::vec3& eye,
                    const CullSettings& settings, std::vector<VisibleBlade>* visible) {
  validate(settings);
  const FieldLayout& layout = field.layout();
  const std::vector<gpu::GrassBlade>& patch = field.patch();
  const std::vector<float>& lengths = field.typeLengths();
  const float bladeTop = field.bladeTop();
  const Frustum frustum(viewProj);
  CullStats stats;
  std::vector<VisibleBlade> instances;
  // Only tiles that can hold blades within the draw distance are looked at (the tile pass's dispatch).
  const glm::ivec4 window = tileWindow(layout, glm::vec2(eye.x, eye.z), settings.maxDistance);
  for (int tz = window.y; tz < window.y + window.w; ++tz) {
    for (int tx = window.x; tx < window.x + window.z; ++tx) {
      ++stats.tiles;
      // The tile's box: terrain samples inside it and on its border, up to the tallest blade.
      const glm::vec2 range = field.tileRange(tx, tz);
      if (!(range.x <= range.y)) {
        continue;
      }
      const glm::vec2 lo =
          layout.origin + glm::vec2(static_cast<float>(tx), static_cast<float>(tz)) * layout.tileSize;
      const glm::vec2 hi = lo + glm::vec2(layout.tileSize);
      const Aabb box{{lo.x, range.x, lo.y}, {hi.x, range.y + bladeTop, hi.y}};
      if (!frustum.intersects(box)) {
        continue;
      }
      // Nearest point of the box: a tile entirely beyond the draw distance is skipped whole.
      const glm::vec3 nearest = glm::clamp(eye, box.min, box.max);
      if (glm::length(nearest - eye) > settings.maxDistance) {
        continue;
      }
      ++stats.tilesVisible;
      field.forEachTileBlade(tx, tz, [&](const FieldBlade& fb) {
        const gpu::GrassBlade& b = patch[fb.patchIndex];
        const float height = lengths[std::min<std::size_t>(b.info.x, lengths.size() - 1)] * b.placement.w;
        const glm::vec3 centre = fb.root + glm::vec3(0.0f, 0.5f * height, 0.0f);
        if (!frustum.intersectsSphere(centre, 0.5f * height)) {
          ++stats.culledFrustum;
          return;
        }
        const float distance = glm::length(fb.root - eye);
        if (distance > settings.maxDistance) {
          ++stats.culledDistance;
          return;
        }
        if (distance > settings.orientationDistance) {
          // The face normal after the blade's turn about the vertical (+Z turned by the rotation).
          const glm::vec2 face(std::sin(b.placement.z), std::cos(b.placement.z));
          const glm::vec2 view(fb.root.x - eye.x, fb.root.z - eye.z);
          const float len = glm::length(view);
          if (len > 1e-6f && std::abs(glm::dot(face, view / len)) < settings.orientationCos) {
            ++stats.culledOrientation;
            return;
          }
        }
        instances.clear();
        lodInstances(settings, distance, instances);
        ++stats.blades;
        for (VisibleBlade& v : instances) {
          ++stats.bladesPerLod[static_cast<std::size_t>(v.lod)];
          if (visible != nullptr) {
            v.blade = fb;
            visible->push_back(v);
          }
        }
      });
    }
  }
  return stats;
}

} // namespace sylva::grass
