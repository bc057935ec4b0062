// The CPU reference of grass culling: tile culling is conservative (it never drops a blade the per-blade
// tests keep), levels follow distance, and the statistics add up.
#include <sylva/core/Error.hpp>
#include <sylva/core/Geometry.hpp>
#include <sylva/grass/Cull.hpp>
#include <sylva/terrain/Noise.hpp>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace sylva::grass {
namespace {

struct Scene {
  terrain::HeightField field;
  std::vector<gpu::GrassBlade> patch;
  std::vector<BladeType> types = proceduralBladeTypes();
  FieldLayout layout;
  DensityMap density{DensitySettings{}};
};

Scene scene() {
  Scene s;
  terrain::ProceduralSpec spec = terrain::defaultLandscapeSpec(9);
  spec.heightScale = 8.0f;
  s.field = terrain::generate(spec, 0.0, 0.0, 81, 81, 1.0f);
  PatchSettings ps;
  ps.blades = 4096;
  s.patch = makePatch(ps, 3);
  s.layout = layoutOver(s.field, ps.tileSize, 96);
  return s;
}

glm::mat4 viewProj(const glm::vec3& eye, const glm::vec3& at, float fovDegrees) {
  return glm::perspective(glm::radians(fovDegrees), 16.0f / 9.0f, 0.1f, 1000.0f) *
         glm::lookAt(eye, at, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(GrassCull, TileCullingIsConservative) {
  const Scene s = scene();
  const glm::vec3 eye(10.0f, 12.0f, 5.0f);
  const glm::mat4 vp = viewProj(eye, {40.0f, 2.0f, 45.0f}, 60.0f);
  CullSettings settings;
  std::vector<VisibleBlade> visible;
  const CullStats stats =
      cullField(s.layout, s.patch, s.types, s.field, s.density, vp, eye, settings, &visible);
  EXPECT_LT(stats.tilesVisible, stats.tiles);
  EXPECT_GT(stats.drawn(), 1000u);
  EXPECT_EQ(visible.size(), stats.drawn());
  // The oracle: every blade of every tile through the per-blade tests alone.
  const Frustum frustum(vp);
  std::size_t expected = 0;
  for (int tz = 0; tz < s.layout.tilesZ; ++tz) {
    for (int tx = 0; tx < s.layout.tilesX; ++tx) {
      forEachTileBlade(s.layout, s.patch, s.field, s.density, tx, tz, [&](const FieldBlade& fb) {
        const gpu::GrassBlade& b = s.patch[fb.patchIndex];
        const float h = s.types[b.info.x].length() * b.placement.w;
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
  const Scene s = scene();
  const glm::vec3 eye(2.0f, 6.0f, 2.0f);
  const glm::mat4 vp = viewProj(eye, {60.0f, 0.0f, 60.0f}, 75.0f);
  CullSettings settings;
  settings.lodDistances = {10.0f, 30.0f};
  std::vector<VisibleBlade> visible;
  const CullStats stats =
      cullField(s.layout, s.patch, s.types, s.field, s.density, vp, eye, settings, &visible);
  for (const VisibleBlade& v : visible) {
    const float d = glm::length(v.blade.root - eye);
    EXPECT_EQ(v.lod, lodForDistance(settings, d));
  }
  EXPECT_GT(stats.bladesPerLod[0], 0u);
  EXPECT_GT(stats.bladesPerLod[1], stats.bladesPerLod[0]);
  EXPECT_GT(stats.bladesPerLod[2], 0u);
  // Looking over the whole field from above with no limits: every blade is drawn.
  CullSettings open;
  open.maxDistance = 1e4f;
  open.orientationCos = 0.0f;
  const glm::vec3 above(40.0f, 300.0f, 40.01f);
  const CullStats all = cullField(s.layout, s.patch, s.types, s.field, s.density,
                                  viewProj(above, {40.0f, 0.0f, 40.0f}, 60.0f), above, open);
  EXPECT_EQ(all.drawn(), countFieldBlades(s.layout, s.patch, s.field, s.density));
  EXPECT_EQ(all.tilesVisible, all.tiles);
}

TEST(GrassCull, EdgeOnFarBladesAreSkipped) {
  const Scene s = scene();
  const glm::vec3 eye(-30.0f, 10.0f, 40.0f);
  const glm::mat4 vp = viewProj(eye, {40.0f, 2.0f, 40.0f}, 60.0f);
  CullSettings with;
  CullSettings without = with;
  without.orientationCos = 0.0f;
  const CullStats a = cullField(s.layout, s.patch, s.types, s.field, s.density, vp, eye, with);
  const CullStats b = cullField(s.layout, s.patch, s.types, s.field, s.density, vp, eye, without);
  EXPECT_EQ(b.culledOrientation, 0u);
  EXPECT_EQ(a.drawn() + a.culledOrientation, b.drawn());
  // Rotations are uniform: |cos| < 0.12 holds for about 7.7 % of the far blades.
  EXPECT_NEAR(static_cast<double>(a.culledOrientation) / b.drawn(), 0.077, 0.03);
  CullSettings bad;
  bad.lodDistances = {30.0f, 10.0f};
  EXPECT_THROW(validate(bad), Error);
}

} // namespace
} // namespace sylva::grass
