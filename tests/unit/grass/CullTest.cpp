// The CPU reference of grass culling: tile culling is conservative (it never drops a blade the per-blade
// tests keep), levels follow distance, and the statistics add up.
#include <sylva/core/Error.hpp>
#include <sylva/core/Geometry.hpp>
#include <sylva/grass/Cull.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/Noise.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace sylva::grass {
namespace {

GrassField scene() {
  terrain::ProceduralSpec spec = terrain::defaultLandscapeSpec(9);
  spec.heightScale = 8.0f;
  FieldSettings fs;
  fs.patch.blades = 4096;
  fs.bladesPerTile = 96;
  return GrassField(terrain::generate(spec, 0.0, 0.0, 81, 81, 1.0f), proceduralBladeTypes(), fs);
}

glm::mat4 viewProj(const glm::vec3& eye, const glm::vec3& at, float fovDegrees) {
  return glm::perspective(glm::radians(fovDegrees), 16.0f / 9.0f, 0.1f, 1000.0f) *
         glm::lookAt(eye, at, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(GrassCull, TileCullingIsConservative) {
  const GrassField s = scene();
  const glm::vec3 eye(10.0f, 12.0f, 5.0f);
  const glm::mat4 vp = viewProj(eye, {40.0f, 2.0f, 45.0f}, 60.0f);
  CullSettings settings;
  std::vector<VisibleBlade> visible;
  const CullStats stats = cullField(s, vp, eye, settings, &visible);
  EXPECT_LT(stats.tilesVisible, stats.tiles);
  EXPECT_GT(stats.drawn(), 1000u);
  EXPECT_EQ(visible.size(), stats.instances());
  EXPECT_GE(stats.instances(), stats.drawn());
  // The oracle: every blade of every tile through the per-blade tests alone.
  const Frustum frustum(vp);
  std::size_t expected = 0;
  for (int tz = 0; tz < s.layout().tilesZ; ++tz) {
    for (int tx = 0; tx < s.layout().tilesX; ++tx) {
      s.forEachTileBlade(tx, tz, [&](const FieldBlade& fb) {
        const gpu::GrassBlade& b = s.patch()[fb.patchIndex];
        const float h = s.types()[b.info.x].length() * b.placement.w;
        const float d = glm::length(fb.root - eye);
        if (!frustum.intersectsSphere(fb.root + glm::vec3(0.0f, 0.5f * h, 0.0f), 0.5f * h) ||
            d > settings.maxDistance) {
          return;
        }
        const glm::vec2 face(std::sin(b.placement.z), std::cos(b.placement.z));
        const glm::vec2 view = glm::normalize(glm::vec2(fb.root.x - eye.x, fb.root.z - eye.z));
        if (d > settings.orientationDistance && std::abs(glm::dot(face, view)) < settings.orientationCos) {
          return;
        }
        ++expected;
      });
    }
  }
  EXPECT_EQ(stats.drawn(), expected);
}

TEST(GrassCull, LevelsFollowDistance) {
  const GrassField s = scene();
  const glm::vec3 eye(2.0f, 6.0f, 2.0f);
  const glm::mat4 vp = viewProj(eye, {60.0f, 0.0f, 60.0f}, 75.0f);
  CullSettings settings;
  settings.lodDistances = {10.0f, 30.0f};
  std::vector<VisibleBlade> visible;
  const CullStats stats = cullField(s, vp, eye, settings, &visible);
  std::size_t fading = 0;
  for (const VisibleBlade& v : visible) {
    const float d = glm::length(v.blade.root - eye);
    if (v.blade.guide >= 0) {
      // A near tuft blade: level 0, inside the near layers' reach (NearTuftsThickenTheFieldTowardsTheCamera).
      EXPECT_EQ(v.lod, 0);
      EXPECT_LT(d, nearReach(settings));
      continue;
    }
    if (v.fade == Fade::Full) {
      EXPECT_EQ(v.lod, lodForDistance(settings, d));
    } else if (v.lod < 2 || d < settings.maxDistance - settings.farFade) {
      // Inside a cross-fade band: both levels around the boundary, the amount rising with distance.
      ++fading;
      const float boundary =
          settings.lodDistances[static_cast<std::size_t>(v.fade == Fade::FadeOut ? v.lod : v.lod - 1)];
      EXPECT_LE(std::abs(d - boundary), 0.5f * settings.lodFade + 1e-4f);
      EXPECT_NEAR(v.amount, (d - boundary) / settings.lodFade + 0.5f, 1e-4f);
    }
  }
  EXPECT_GT(fading, 0u);
  EXPECT_GT(stats.bladesPerLod[0], 0u);
  EXPECT_GT(stats.bladesPerLod[1], stats.bladesPerLod[0]);
  EXPECT_GT(stats.bladesPerLod[2], 0u);
  // Looking over the whole field from above with no limits: every blade is drawn.
  CullSettings open;
  open.maxDistance = 1e4f;
  open.orientationCos = 0.0f;
  const glm::vec3 above(40.0f, 300.0f, 40.01f);
  const CullStats all = cullField(s, viewProj(above, {40.0f, 0.0f, 40.0f}, 60.0f), above, open);
  EXPECT_EQ(all.drawn(), s.countBlades());
  EXPECT_EQ(all.tilesVisible, all.tiles);
}

TEST(GrassCull, ScaledSettingsDrawTheSameRulesOverAShorterRange) {
  const GrassField s = scene();
  const glm::vec3 eye(2.0f, 6.0f, 2.0f);
  const glm::mat4 vp = viewProj(eye, {60.0f, 0.0f, 60.0f}, 75.0f);
  CullSettings settings;
  settings.maxDistance = 60.0f;
  settings.lodDistances = {10.0f, 30.0f};
  const CullSettings half = scaled(settings, 0.5f);
  EXPECT_NO_THROW(validate(half));
  EXPECT_FLOAT_EQ(half.maxDistance, 30.0f);
  EXPECT_FLOAT_EQ(half.lodDistances[1], 15.0f);
  EXPECT_FLOAT_EQ(half.lodFade, 0.5f * settings.lodFade);
  EXPECT_FLOAT_EQ(half.farFade, 0.5f * settings.farFade);
  EXPECT_FLOAT_EQ(half.orientationDistance, 0.5f * settings.orientationDistance);
  EXPECT_EQ(half.orientationCos, settings.orientationCos);
  // Fewer blades, all within the shorter range.
  std::vector<VisibleBlade> all;
  std::vector<VisibleBlade> near;
  const CullStats full = cullField(s, vp, eye, settings, &all);
  const CullStats shorter = cullField(s, vp, eye, half, &near);
  EXPECT_GT(shorter.drawn(), 0u);
  EXPECT_LT(shorter.drawn(), full.drawn());
  for (const VisibleBlade& v : near) {
    EXPECT_LE(glm::length(v.blade.root - eye), half.maxDistance + 1e-3f);
  }
  EXPECT_THROW(scaled(settings, 0.0f), Error);
  EXPECT_THROW(scaled(settings, std::nanf("")), Error);
}

TEST(GrassCull, EdgeOnFarBladesAreSkipped) {
  const GrassField s = scene();
  const glm::vec3 eye(-30.0f, 10.0f, 40.0f);
  const glm::mat4 vp = viewProj(eye, {40.0f, 2.0f, 40.0f}, 60.0f);
  CullSettings with;
  CullSettings without = with;
  without.orientationCos = 0.0f;
  const CullStats a = cullField(s, vp, eye, with);
  const CullStats b = cullField(s, vp, eye, without);
  EXPECT_EQ(b.culledOrientation, 0u);
  EXPECT_EQ(a.drawn() + a.culledOrientation, b.drawn());
  // Rotations are uniform: |cos| < 0.12 holds for about 7.7 % of the far blades.
  EXPECT_NEAR(static_cast<double>(a.culledOrientation) / b.drawn(), 0.077, 0.03);
  CullSettings bad;
  bad.lodDistances = {30.0f, 10.0f};
  EXPECT_THROW(validate(bad), Error);
  CullSettings overlapping;
  overlapping.lodFade = 30.0f;
  EXPECT_THROW(validate(overlapping), Error);
}

/** Drawn instances of the field's own blades and of the near tufts in rings of `width` metres around `eye`.
 */
struct Rings {
  std::vector<double> field;
  std::vector<double> tufts;
};

Rings rings(const std::vector<VisibleBlade>& visible, const glm::vec3& eye, float width, std::size_t count) {
  Rings r{std::vector<double>(count, 0.0), std::vector<double>(count, 0.0)};
  for (const VisibleBlade& v : visible) {
    const auto ring = static_cast<std::size_t>(glm::length(v.blade.root - eye) / width);
    if (ring < count) {
      (v.blade.guide >= 0 ? r.tufts : r.field)[ring] += 1.0;
    }
  }
  return r;
}

TEST(GrassCull, NearTuftsThickenTheFieldTowardsTheCamera) {
  const GrassField s = scene();
  const glm::vec3 eye(30.0f, terrain::heightAt(s.terrain(), 30.0f, 30.0f) + 1.0f, 30.0f);
  const glm::mat4 vp = viewProj(eye, {60.0f, eye.y - 6.0f, 50.0f}, 90.0f);
  CullSettings settings; // 8 layers within 8 m
  std::vector<VisibleBlade> visible;
  const CullStats stats = cullField(s, vp, eye, settings, &visible);
  CullSettings off = settings;
  off.nearLayers = 1;
  std::vector<VisibleBlade> plain;
  const CullStats without = cullField(s, vp, eye, off, &plain);
  // The field's own blades are untouched; the tufts come on top.
  EXPECT_EQ(without.tuftBlades, 0u);
  EXPECT_EQ(stats.drawn(), without.drawn() + stats.tuftBlades);
  const float reach = nearReach(settings);
  ASSERT_FLOAT_EQ(reach, 8.0f);
  const auto withinReach = std::count_if(plain.begin(), plain.end(), [&](const VisibleBlade& v) {
    return glm::length(v.blade.root - eye) < reach;
  });
  EXPECT_GT(stats.tuftBlades, 2u * static_cast<std::size_t>(withinReach));
  // Density: close to the camera every layer is drawn (7 tufts per field blade), thinning with distance to
  // none past the reach, never rising on the way out.
  const Rings r = rings(visible, eye, 1.0f, 12);
  double before = 1e9;
  int measured = 0;
  for (std::size_t k = 0; k < r.field.size(); ++k) {
    if (r.field[k] < 30.0) {
      continue; // the ring under the camera, mostly outside the view
    }
    ++measured;
    const double ratio = r.tufts[k] / r.field[k];
    const float outer = static_cast<float>(k + 1);
    if (outer <= 0.75f * nearLayerReach(settings, 7, 8)) {
      EXPECT_NEAR(ratio, 7.0, 1.0) << "ring " << k;
    }
    if (static_cast<float>(k) >= reach) {
      EXPECT_EQ(r.tufts[k], 0.0) << "ring " << k;
    }
    EXPECT_LE(ratio, before + 0.6) << "ring " << k;
    before = ratio;
  }
  EXPECT_GE(measured, 8);
  // Each tuft blade stands within tuftRadius (each axis) of a field blade the density keeps, and fades out
  // continuously: its coverage (1 − fade amount) is 0 at its layer's reach, so nothing pops as the camera
  // moves.
  std::map<std::tuple<int, int, int>, glm::vec3> fieldRoots;
  for (int tz = 0; tz < s.layout().tilesZ; ++tz) {
    for (int tx = 0; tx < s.layout().tilesX; ++tx) {
      s.forEachTileBlade(tx, tz, [&](const FieldBlade& fb) {
        fieldRoots[{tx, tz, fb.rangeIndex}] = fb.root;
      });
    }
  }
  const float radius = tuftRadius(s.layout());
  EXPECT_NEAR(radius, 0.5f * 2.0f / std::sqrt(96.0f), 1e-6f);
  for (const VisibleBlade& v : visible) {
    if (v.blade.guide < 0) {
      continue;
    }
    const auto it = fieldRoots.find({v.blade.tileX, v.blade.tileZ, v.blade.guide});
    ASSERT_NE(it, fieldRoots.end()) << "a tuft beside a blade the field does not draw";
    EXPECT_LE(std::abs(v.blade.root.x - it->second.x), radius + 1e-4f);
    EXPECT_LE(std::abs(v.blade.root.z - it->second.z), radius + 1e-4f);
    const int layer = v.blade.rangeIndex / s.layout().bladesPerTile;
    ASSERT_GE(layer, 1);
    const float layerReach = nearLayerReach(settings, layer, 8);
    const float d = glm::length(v.blade.root - eye);
    const float coverage = v.fade == Fade::Full ? 1.0f : 1.0f - v.amount;
    EXPECT_LE(coverage, (layerReach - d) / (0.25f * layerReach) + 1e-4f);
    EXPECT_EQ(v.fade == Fade::Full, d < 0.75f * layerReach);
  }
}

TEST(GrassCull, NearLayersStopBeforeTheFirstLodBandAndFitThePatch) {
  CullSettings s;
  s.lodDistances = {5.0f, 30.0f};
  EXPECT_FLOAT_EQ(nearReach(s), 5.0f - 0.5f * s.lodFade);
  FieldLayout layout;
  layout.bladesPerTile = 1024;
  EXPECT_EQ(nearLayerCount(s, layout, 4096), 4);
  EXPECT_EQ(nearLayerCount(s, layout, 512), 1);
  layout.bladesPerTile = 16;
  EXPECT_EQ(nearLayerCount(s, layout, 1u << 20), 8);
  EXPECT_FLOAT_EQ(nearLayerReach(s, 1, 8), nearReach(s));
  EXPECT_NEAR(nearLayerReach(s, 7, 8), nearReach(s) * std::sqrt(1.0f / 7.0f), 1e-5f);
  EXPECT_FLOAT_EQ(scaled(s, 0.5f).nearDistance, 4.0f);
  CullSettings bad;
  bad.nearLayers = 0;
  EXPECT_THROW(validate(bad), Error);
  bad.nearLayers = 65;
  EXPECT_THROW(validate(bad), Error);
  bad.nearLayers = 8;
  bad.nearDistance = std::nanf("");
  EXPECT_THROW(validate(bad), Error);
}

TEST(GrassCull, TileWindowHoldsEveryTileWithinTheDistance) {
  const GrassField s = scene();
  const FieldLayout& layout = s.layout();
  for (const glm::vec2 eye : {glm::vec2(40.0f, 40.0f), glm::vec2(-20.0f, 5.0f), glm::vec2(79.0f, 81.0f)}) {
    const float distance = 17.0f;
    const glm::ivec4 w = tileWindow(layout, eye, distance);
    for (int tz = 0; tz < layout.tilesZ; ++tz) {
      for (int tx = 0; tx < layout.tilesX; ++tx) {
        const glm::vec2 lo =
            layout.origin + glm::vec2(static_cast<float>(tx), static_cast<float>(tz)) * layout.tileSize;
        const glm::vec2 nearest = glm::clamp(eye, lo, lo + glm::vec2(layout.tileSize));
        const bool inside = tx >= w.x && tx < w.x + w.z && tz >= w.y && tz < w.y + w.w;
        // Roots lie in [lo, lo + tileSize): a tile whose far edge is exactly at the distance holds none
        // within it.
        if (glm::length(nearest - eye) < distance) {
          EXPECT_TRUE(inside) << tx << "," << tz;
        }
      }
    }
  }
  // The estimate from the mean density is close to the exact count.
  EXPECT_NEAR(s.estimateBlades(), static_cast<double>(s.countBlades()),
              0.05 * static_cast<double>(s.countBlades()));
}

TEST(GrassCull, CrossFadesCoverEachBladeOnce) {
  CullSettings s;
  std::vector<VisibleBlade> out;
  for (float d = 0.0f; d <= s.maxDistance + 5.0f; d += 0.05f) {
    out.clear();
    lodInstances(s, d, out);
    if (d > s.maxDistance) {
      EXPECT_TRUE(out.empty());
      continue;
    }
    ASSERT_FALSE(out.empty());
    ASSERT_LE(out.size(), 2u);
    // Coverage: a Full instance covers everything; FadeOut covers 1 - amount, FadeIn amount.
    float coverage = 0.0f;
    for (const VisibleBlade& v : out) {
      coverage += v.fade == Fade::Full ? 1.0f : v.fade == Fade::FadeOut ? 1.0f - v.amount : v.amount;
    }
    const float farStart = s.maxDistance - s.farFade;
    const float expected = d < farStart ? 1.0f : 1.0f - (d - farStart) / s.farFade;
    EXPECT_NEAR(coverage, expected, 1e-4f) << d;
  }
}

} // namespace
} // namespace sylva::grass
