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
}

int lodForDistance(const CullSettings& s, float distance) {
  return distance < s.lodDistances[0] ? 0 : distance < s.lodDistances[1] ? 1 : 2;
}

CullStats cullField(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                    const std::vector<BladeType>& types, const terrain::HeightField& terrain,
                    const DensityMap& density, const glm::mat4& viewProj, const glm::vec3& eye,
                    const CullSettings& settings, std::vector<VisibleBlade>* visible) {
  validate(settings);
  if (types.empty()) {
    fail("grass culling: no blade types");
  }
  std::vector<float> heights;
  float tallest = 0.0f;
  for (const BladeType& t : types) {
    heights.push_back(t.length());
    tallest = std::max(tallest, t.length());
  }
  float maxScale = 0.0f;
  for (const gpu::GrassBlade& b : patch) {
    maxScale = std::max(maxScale, b.placement.w);
  }
  const float bladeTop = tallest * maxScale;
  const Frustum frustum(viewProj);
  CullStats stats;
  for (int tz = 0; tz < layout.tilesZ; ++tz) {
    for (int tx = 0; tx < layout.tilesX; ++tx) {
      ++stats.tiles;
      // The tile's box: terrain samples inside it and on its border, up to the tallest blade.
      const glm::vec2 lo =
          layout.origin + glm::vec2(static_cast<float>(tx), static_cast<float>(tz)) * layout.tileSize;
      const glm::vec2 hi = lo + glm::vec2(layout.tileSize);
      const int i0 =
          std::clamp(static_cast<int>(std::floor(lo.x / terrain.spacingX())), 0, terrain.width() - 1);
      const int i1 =
          std::clamp(static_cast<int>(std::ceil(hi.x / terrain.spacingX())), 0, terrain.width() - 1);
      const int j0 =
          std::clamp(static_cast<int>(std::floor(lo.y / terrain.spacingZ())), 0, terrain.height() - 1);
      const int j1 =
          std::clamp(static_cast<int>(std::ceil(hi.y / terrain.spacingZ())), 0, terrain.height() - 1);
      float minY = std::numeric_limits<float>::infinity();
      float maxY = -std::numeric_limits<float>::infinity();
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
          if (terrain.valid(i, j)) {
            minY = std::min(minY, terrain.at(i, j));
            maxY = std::max(maxY, terrain.at(i, j));
          }
        }
      }
      if (!(minY <= maxY)) {
        continue;
      }
      const Aabb box{{lo.x, minY, lo.y}, {hi.x, maxY + bladeTop, hi.y}};
      if (!frustum.intersects(box)) {
        continue;
      }
      // Nearest point of the box: a tile entirely beyond the draw distance is skipped whole.
      const glm::vec3 nearest = glm::clamp(eye, box.min, box.max);
      if (glm::length(nearest - eye) > settings.maxDistance) {
        continue;
      }
      ++stats.tilesVisible;
      forEachTileBlade(layout, patch, terrain, density, tx, tz, [&](const FieldBlade& fb) {
        const gpu::GrassBlade& b = patch[fb.patchIndex];
        const float height = heights[std::min<std::size_t>(b.info.x, heights.size() - 1)] * b.placement.w;
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
          glm::vec2 view(fb.root.x - eye.x, fb.root.z - eye.z);
          const float len = glm::length(view);
          if (len > 1e-6f && std::abs(glm::dot(face, view / len)) < settings.orientationCos) {
            ++stats.culledOrientation;
            return;
          }
        }
        const int lod = lodForDistance(settings, distance);
        ++stats.bladesPerLod[static_cast<std::size_t>(lod)];
        if (visible != nullptr) {
          visible->push_back({fb, lod});
        }
      });
    }
  }
  return stats;
}

} // namespace sylva::grass
