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
  if (s.nearLayers < 1 || s.nearLayers > 64) {
    fail("grass culling: nearLayers must be in 1..64, got {}", s.nearLayers);
  }
  if (!std::isfinite(s.nearDistance) || s.nearDistance < 0.0f) {
    fail("grass culling: nearDistance must be a finite number ≥ 0, got {}", s.nearDistance);
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
  c.nearDistance *= factor;
  return c;
}

float nearReach(const CullSettings& s) {
  return std::max(0.0f, std::min(s.nearDistance, s.lodDistances[0] - 0.5f * s.lodFade));
}

int nearLayerCount(const CullSettings& s, const FieldLayout& layout, std::uint32_t patchBlades) {
  const int perTile = std::max(layout.bladesPerTile, 1);
  const int fit =
      static_cast<int>(std::min<std::uint32_t>(patchBlades / static_cast<std::uint32_t>(perTile), 64u));
  return std::max(1, std::min(s.nearLayers, fit));
}

float nearLayerReach(const CullSettings& s, int layer, int layers) {
  // The blade pass's tuftReach (shaders/grass/blades.comp), in the same order.
  return nearReach(s) * std::sqrt(static_cast<float>(layers - layer) / static_cast<float>(layers - 1));
}

float tuftRadius(const FieldLayout& layout) {
  return 0.5f * layout.tileSize / std::sqrt(static_cast<float>(std::max(layout.bladesPerTile, 1)));
}

void forEachTuftBlade(const GrassField& field, int tx, int tz, const glm::vec3& eye, const CullSettings& s,
                      const std::function<void(const FieldBlade&, float reach)>& visit) {
  // The near branch of the blade pass (shaders/grass/blades.comp), test for test.
  const FieldLayout& layout = field.layout();
  const std::vector<gpu::GrassBlade>& patch = field.patch();
  const auto n = static_cast<std::uint32_t>(patch.size());
  const int layers = nearLayerCount(s, layout, n);
  if (layers < 2 || n == 0) {
    return;
  }
  const terrain::HeightField& terrain = field.terrain();
  const int perTile = layout.bladesPerTile;
  const std::uint32_t start = tileStart(tx, tz, n);
  const glm::vec2 corner =
      layout.origin + glm::vec2(static_cast<float>(tx), static_cast<float>(tz)) * layout.tileSize;
  const float radius = tuftRadius(layout);
  const auto inside = [&](glm::vec2 xz) {
    return !(xz.x < 0.0f || xz.y < 0.0f || xz.x > terrain.extentX() || xz.y > terrain.extentZ());
  };
  for (int j = perTile; j < perTile * layers; ++j) {
    const int i = j % perTile;
    const float reach = nearLayerReach(s, j / perTile, layers);
    const gpu::GrassBlade& g = patch[(start + static_cast<std::uint32_t>(i)) % n];
    const glm::vec2 guide = corner + glm::vec2(g.placement.x, g.placement.y);
    const std::uint32_t index = (start + static_cast<std::uint32_t>(j)) % n;
    const gpu::GrassBlade& b = patch[index];
    const glm::vec2 xz =
        guide + (glm::vec2(b.placement.x, b.placement.y) / layout.tileSize - 0.5f) * (2.0f * radius);
    if (!inside(guide) || !inside(xz) || glm::length(xz - glm::vec2(eye.x, eye.z)) >= reach) {
      continue;
    }
    if (std::isnan(rootHeight(terrain, guide.x, guide.y)) ||
        (static_cast<float>(i) + 0.5f) / static_cast<float>(perTile) >=
            field.density().at(guide.x, guide.y)) {
      continue;
    }
    const float height = rootHeight(terrain, xz.x, xz.y);
    if (std::isnan(height)) {
      continue;
    }
    const glm::vec3 root(xz.x, height, xz.y);
    if (glm::length(root - eye) >= reach) {
      continue;
    }
    visit({root, index, j, tx, tz, i}, reach);
  }
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

void tuftFade(float reach, float distance, VisibleBlade& v) {
  // The blade pass's tuft fade (shaders/grass/blades.comp): dithered out over the last quarter of the reach.
  const float start = 0.75f * reach;
  if (distance >= start) {
    v.fade = Fade::FadeOut;
    v.amount = std::min((distance - start) / (reach - start), 1.0f);
  }
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
      // Frustum and orientation tests of one blade; its distance when it passes, else a negative number.
      const auto passes = [&](const FieldBlade& fb) {
        const gpu::GrassBlade& b = patch[fb.patchIndex];
        const float height = lengths[std::min<std::size_t>(b.info.x, lengths.size() - 1)] * b.placement.w;
        const glm::vec3 centre = fb.root + glm::vec3(0.0f, 0.5f * height, 0.0f);
        if (!frustum.intersectsSphere(centre, 0.5f * height)) {
          ++stats.culledFrustum;
          return -1.0f;
        }
        const float distance = glm::length(fb.root - eye);
        if (distance > settings.maxDistance) {
          ++stats.culledDistance;
          return -1.0f;
        }
        if (distance > settings.orientationDistance) {
          // The face normal after the blade's turn about the vertical (+Z turned by the rotation).
          const glm::vec2 face(std::sin(b.placement.z), std::cos(b.placement.z));
          const glm::vec2 view(fb.root.x - eye.x, fb.root.z - eye.z);
          const float len = glm::length(view);
          if (len > 1e-6f && std::abs(glm::dot(face, view / len)) < settings.orientationCos) {
            ++stats.culledOrientation;
            return -1.0f;
          }
        }
        ++stats.blades;
        return distance;
      };
      const auto keep = [&](const FieldBlade& fb) {
        for (VisibleBlade& v : instances) {
          ++stats.bladesPerLod[static_cast<std::size_t>(v.lod)];
          if (visible != nullptr) {
            v.blade = fb;
            visible->push_back(v);
          }
        }
      };
      field.forEachTileBlade(tx, tz, [&](const FieldBlade& fb) {
        const float distance = passes(fb);
        if (distance >= 0.0f) {
          instances.clear();
          lodInstances(settings, distance, instances);
          keep(fb);
        }
      });
      // Tuft blades, only in tiles that reach within the first layer's distance (horizontally).
      const glm::vec2 closest = glm::clamp(glm::vec2(eye.x, eye.z), lo, hi);
      if (glm::length(closest - glm::vec2(eye.x, eye.z)) < nearReach(settings)) {
        forEachTuftBlade(field, tx, tz, eye, settings, [&](const FieldBlade& fb, float reach) {
          const float distance = passes(fb);
          if (distance >= 0.0f) {
            ++stats.tuftBlades;
            instances.clear();
            instances.push_back({{}, 0, Fade::Full, 0.0f});
            tuftFade(reach, distance, instances.back());
            keep(fb);
          }
        });
      }
    }
  }
  return stats;
}

} // namespace sylva::grass
