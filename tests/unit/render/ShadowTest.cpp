// Cascaded sun shadows on the CPU (render::cascadeSplits, fitCascades, toFrame) and the orthographic camera:
// the split formula, every point of each frustum slice inside its cascade, casters inside the depth range,
// and texel snapping (a camera translation moves every cascade's grid over the world by whole texels).
#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/Shadows.hpp>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

Camera viewer(const glm::vec3& position, const glm::vec3& target) {
  Camera camera;
  camera.position = position;
  camera.target = target;
  camera.fovY = glm::radians(55.0f);
  camera.nearPlane = 0.2f;
  camera.farPlane = 3000.0f;
  return camera;
}

const Aabb kCasters{{-600.0f, -50.0f, -600.0f}, {600.0f, 250.0f, 600.0f}};
const glm::vec3 kSun = glm::normalize(glm::vec3(0.6f, 0.35f, -0.4f));

TEST(ShadowSplits, UniformAndLogarithmicEnds) {
  const std::vector<float> uniform = cascadeSplits(1.0f, 101.0f, 4, 0.0f);
  ASSERT_EQ(uniform.size(), 5u);
  for (int i = 0; i <= 4; ++i) {
    EXPECT_NEAR(uniform[static_cast<std::size_t>(i)], 1.0f + 25.0f * static_cast<float>(i), 1e-4f);
  }
  const std::vector<float> logarithmic = cascadeSplits(1.0f, 1000.0f, 3, 1.0f);
  ASSERT_EQ(logarithmic.size(), 4u);
  EXPECT_NEAR(logarithmic[1], 10.0f, 1e-4f);
  EXPECT_NEAR(logarithmic[2], 100.0f, 1e-3f);
  EXPECT_EQ(logarithmic[3], 1000.0f);
  // λ blends the two linearly, and the ends are exact.
  const std::vector<float> practical = cascadeSplits(0.5f, 400.0f, 3, 0.7f);
  const std::vector<float> u = cascadeSplits(0.5f, 400.0f, 3, 0.0f);
  const std::vector<float> l = cascadeSplits(0.5f, 400.0f, 3, 1.0f);
  EXPECT_EQ(practical.front(), 0.5f);
  EXPECT_EQ(practical.back(), 400.0f);
  for (std::size_t i = 0; i < practical.size(); ++i) {
    EXPECT_NEAR(practical[i], 0.7f * l[i] + 0.3f * u[i], 1e-3f);
    if (i > 0) {
      EXPECT_GT(practical[i], practical[i - 1]);
    }
  }
}

TEST(ShadowSplits, RejectsBadInput) {
  EXPECT_THROW(cascadeSplits(0.0f, 10.0f, 3, 0.5f), Error);
  EXPECT_THROW(cascadeSplits(10.0f, 10.0f, 3, 0.5f), Error);
  EXPECT_THROW(cascadeSplits(1.0f, 10.0f, 0, 0.5f), Error);
  EXPECT_THROW(cascadeSplits(1.0f, 10.0f, 3, 1.5f), Error);
  ShadowSettings settings;
  settings.cascades = 5;
  EXPECT_THROW(fitCascades(viewer({0, 10, 0}, {1, 10, 0}), 1.5f, kSun, settings, kCasters), Error);
  settings.cascades = 3;
  EXPECT_THROW(fitCascades(viewer({0, 10, 0}, {1, 10, 0}), 1.5f, glm::vec3(0.0f), settings, kCasters), Error);
}

TEST(ShadowCamera, OrthographicModeAndPerspectiveUnchanged) {
  Camera camera = viewer({3, 4, 5}, {0, 0, 0});
  EXPECT_EQ(camera.projection(1.7f), glm::perspective(camera.fovY, 1.7f, camera.nearPlane, camera.farPlane));
  camera.orthoHeight = 25.0f;
  EXPECT_EQ(camera.projection(2.0f), glm::ortho(-50.0f, 50.0f, -25.0f, 25.0f, 0.2f, 3000.0f));
  // A point 20 m right and 10 m up of the axis lands at the same NDC at every depth.
  const glm::vec3 right = glm::normalize(glm::cross(camera.forward(), camera.up));
  const glm::vec3 up = glm::cross(right, camera.forward());
  for (float d : {1.0f, 50.0f, 900.0f}) {
    const glm::vec4 clip = camera.viewProjection(2.0f) *
                           glm::vec4(camera.position + d * camera.forward() + 20.0f * right + 10.0f * up, 1);
    EXPECT_NEAR(clip.x / clip.w, 0.4f, 1e-4f);
    EXPECT_NEAR(clip.y / clip.w, 0.4f, 1e-4f);
  }
}

TEST(ShadowCascades, EverySlicePointInsideItsCascade) {
  Rng rng(11);
  const float aspect = 16.0f / 9.0f;
  ShadowSettings settings;
  settings.cascades = 4;
  settings.size = 1024;
  settings.distance = 500.0f;
  for (int pose = 0; pose < 20; ++pose) {
    const glm::vec3 position(rng.uniform(-300, 300), rng.uniform(0, 200), rng.uniform(-300, 300));
    const glm::vec3 look(rng.uniform(-1, 1), rng.uniform(-0.8f, 0.3f), rng.uniform(-1, 1));
    const Camera camera = viewer(position, position + look);
    const glm::vec3 sun =
        glm::normalize(glm::vec3(rng.uniform(-1, 1), rng.uniform(0.1f, 1), rng.uniform(-1, 1)));
    const ShadowCascades fit = fitCascades(camera, aspect, sun, settings, kCasters);
    ASSERT_EQ(fit.cascades.size(), 4u);
    const ShadowFrame frame = toFrame(fit, settings);
    const glm::mat4 view = camera.view();
    const glm::mat4 invViewProj = glm::inverse(camera.projection(aspect));
    const glm::mat4 invView = glm::inverse(view);
    for (int c = 0; c < 4; ++c) {
      const ShadowCascade& cascade = fit.cascades[static_cast<std::size_t>(c)];
      const float margin = 1.5f / static_cast<float>(settings.size); // PCF reach in [0,1] units
      for (int k = 0; k < 200; ++k) {
        // Corners first, then random points of the slice: a view ray through NDC (x, y) to depth d.
        glm::vec2 ndc(rng.uniform(-1, 1), rng.uniform(-1, 1));
        float t = rng.uniform();
        if (k < 8) {
          ndc = {(k & 1) ? 1.0f : -1.0f, (k & 2) ? 1.0f : -1.0f};
          t = (k & 4) ? 1.0f : 0.0f;
        }
        const float d = glm::mix(cascade.nearDepth, cascade.farDepth, t);
        glm::vec4 dir = invViewProj * glm::vec4(ndc, 1.0f, 1.0f);
        glm::vec3 v = glm::vec3(dir) / dir.w;
        v *= d / -v.z; // view space point at depth d
        const glm::vec3 world = glm::vec3(invView * glm::vec4(v, 1.0f));
        const glm::vec3 s = glm::vec3(cascade.shadow * glm::vec4(world, 1.0f));
        EXPECT_GE(s.x, margin) << "pose " << pose << " cascade " << c;
        EXPECT_LE(s.x, 1.0f - margin) << "pose " << pose << " cascade " << c;
        EXPECT_GE(s.y, margin) << "pose " << pose << " cascade " << c;
        EXPECT_LE(s.y, 1.0f - margin) << "pose " << pose << " cascade " << c;
        const bool inCasters = glm::all(glm::greaterThanEqual(world, kCasters.min)) &&
                               glm::all(glm::lessThanEqual(world, kCasters.max));
        if (inCasters) {
          EXPECT_GT(s.z, 0.0f);
          EXPECT_LT(s.z, 1.0f);
          // Culling with the orthographic camera keeps it (Frustum planes from the ortho view-projection).
          EXPECT_TRUE(cascade.camera.frustum(1.0f).contains(world)) << "pose " << pose << " cascade " << c;
        }
        if (t > 0.01f && t < 0.99f) {
          EXPECT_EQ(cascadeFor(frame, view, world), c);
        }
      }
    }
  }
}

TEST(ShadowCascades, CastersInsideTheDepthRangeAndSunCameraOutside) {
  const Camera camera = viewer({10, 30, 20}, {200, 0, -80});
  ShadowSettings settings;
  const ShadowCascades fit = fitCascades(camera, 1.5f, kSun, settings, kCasters);
  for (const ShadowCascade& cascade : fit.cascades) {
    for (int k = 0; k < 8; ++k) {
      const glm::vec3 corner = {(k & 1) ? kCasters.max.x : kCasters.min.x,
                                (k & 2) ? kCasters.max.y : kCasters.min.y,
                                (k & 4) ? kCasters.max.z : kCasters.min.z};
      const float z = (cascade.shadow * glm::vec4(corner, 1.0f)).z;
      EXPECT_GT(z, 0.0f) << "caster corner in front of the near plane";
      EXPECT_LT(z, 1.0f) << "caster corner beyond the far plane";
    }
    // The sun camera stands outside the casters, on the sun's side; its matrices match the cascade's.
    const glm::vec3 p = cascade.camera.position;
    const glm::vec3 c = glm::clamp(p, kCasters.min, kCasters.max);
    EXPECT_GT(glm::length(p - c), 0.5f);
    EXPECT_GT(glm::dot(p - kCasters.center(), kSun), 0.0f);
    const glm::mat4 a = cascade.camera.viewProjection(1.0f);
    for (int col = 0; col < 4; ++col) {
      for (int row = 0; row < 4; ++row) {
        EXPECT_NEAR(a[col][row], cascade.viewProj[col][row],
                    1e-5f * (1.0f + std::abs(cascade.viewProj[col][row])));
      }
    }
  }
  // toFrame: one depth bias in [0,1] units for the shared range; splits are the slices' far ends.
  const ShadowFrame frame = toFrame(fit, settings);
  EXPECT_EQ(frame.cascades, 3);
  EXPECT_FLOAT_EQ(frame.texel, 1.0f / 2048.0f);
  const Camera& sunCam = fit.cascades[0].camera;
  EXPECT_NEAR(frame.depthBias * (sunCam.farPlane - sunCam.nearPlane), settings.depthBias, 1e-5f);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(frame.splits[i], fit.splits[static_cast<std::size_t>(i) + 1]);
  }
}

TEST(ShadowCascades, SizeStableUnderRotationAndTexelSnapped) {
  ShadowSettings settings;
  settings.size = 2048;
  const Camera base = viewer({40, 25, -30}, {140, 5, 10});
  const ShadowCascades first = fitCascades(base, 1.5f, kSun, settings, kCasters);
  // Turning the camera keeps every cascade's radius and texel size.
  Camera turned = base;
  turned.target = base.position + glm::vec3(-0.3f, -0.2f, 1.0f);
  const ShadowCascades rotated = fitCascades(turned, 1.5f, kSun, settings, kCasters);
  for (std::size_t c = 0; c < first.cascades.size(); ++c) {
    EXPECT_EQ(first.cascades[c].radius, rotated.cascades[c].radius);
    EXPECT_EQ(first.cascades[c].texelSize, rotated.cascades[c].texelSize);
  }
  // Small translations: a fixed world point moves on each cascade's map by whole texels.
  const glm::vec3 probes[] = {{0, 0, 0}, {123.4f, 17.0f, -55.5f}, {-300.0f, 80.0f, 250.0f}};
  Camera moving = base;
  int moved = 0;
  for (int step = 1; step <= 40; ++step) {
    const glm::vec3 delta(0.173f * static_cast<float>(step), 0.05f * static_cast<float>(step),
                          -0.091f * static_cast<float>(step));
    moving.position = base.position + delta;
    moving.target = base.target + delta;
    const ShadowCascades fit = fitCascades(moving, 1.5f, kSun, settings, kCasters);
    for (std::size_t c = 0; c < fit.cascades.size(); ++c) {
      for (const glm::vec3& p : probes) {
        const glm::vec2 a = glm::vec2(first.cascades[c].shadow * glm::vec4(p, 1.0f)) * 2048.0f;
        const glm::vec2 b = glm::vec2(fit.cascades[c].shadow * glm::vec4(p, 1.0f)) * 2048.0f;
        const glm::vec2 shift = b - a;
        EXPECT_NEAR(shift.x, std::round(shift.x), 2e-3f) << "cascade " << c << " step " << step;
        EXPECT_NEAR(shift.y, std::round(shift.y), 2e-3f) << "cascade " << c << " step " << step;
        moved += (std::round(shift.x) != 0.0f || std::round(shift.y) != 0.0f) ? 1 : 0;
        // Depth of a fixed point stays put: the depth range comes from the casters.
        EXPECT_NEAR((fit.cascades[c].shadow * glm::vec4(p, 1.0f)).z,
                    (first.cascades[c].shadow * glm::vec4(p, 1.0f)).z, 1e-6f);
      }
    }
  }
  EXPECT_GT(moved, 0) << "the cascades followed the camera";
}

} // namespace
} // namespace sylva::render
