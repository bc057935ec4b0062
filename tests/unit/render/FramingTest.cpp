// Framing cameras (render::frameBox and friends): every corner of the framed box is in view, the fit is
// tight, directions follow the compass of height fields (row 0 north = -z), clip planes and fog follow the
// scene.
#include <sylva/core/Error.hpp>
#include <sylva/core/Geometry.hpp>
#include <sylva/render/Camera.hpp>

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace sylva::render {
namespace {

std::array<glm::vec3, 8> cornersOf(const Aabb& box) {
  std::array<glm::vec3, 8> out{};
  for (int k = 0; k < 8; ++k) {
    out[static_cast<std::size_t>(k)] = {(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                        (k & 4) ? box.max.z : box.min.z};
  }
  return out;
}

/** Largest |x|, |y| of the corners in normalised device coordinates; fails if one is behind or clipped. */
glm::vec2 ndcReach(const Camera& camera, const Aabb& box, float aspect) {
  const glm::mat4 vp = camera.viewProjection(aspect);
  glm::vec2 reach(0.0f);
  for (const glm::vec3& c : cornersOf(box)) {
    const glm::vec4 clip = vp * glm::vec4(c, 1.0f);
    EXPECT_GT(clip.w, 0.0f) << "corner behind the camera";
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    EXPECT_LE(std::abs(ndc.x), 1.0f + 1e-4f);
    EXPECT_LE(std::abs(ndc.y), 1.0f + 1e-4f);
    EXPECT_GE(ndc.z, -1.0f) << "corner before the near plane";
    EXPECT_LE(ndc.z, 1.0f) << "corner beyond the far plane";
    reach = glm::max(reach, glm::abs(glm::vec2(ndc)));
  }
  return reach;
}

TEST(Framing, EveryCornerIsInViewAndTheFitIsTight) {
  // A demo-like terrain, a tall narrow DEM (relief >> extent) and a continental one (extent >> relief).
  const Aabb boxes[] = {{{0, 0, 0}, {2048, 400, 2048}},
                        {{0, -50, 0}, {300, 4000, 120}},
                        {{0, -8000, 0}, {4.0e7f, 6000, 2.0e7f}}};
  for (const Aabb& box : boxes) {
    for (const std::string& name : viewFromNames()) {
      for (const float aspect : {16.0f / 9.0f, 1.0f, 0.5f}) {
        const Camera camera =
            frameBox(box, parseViewFrom(name), glm::radians(50.0f), aspect, box.center(), 1.0f);
        const glm::vec2 reach = ndcReach(camera, box, aspect);
        // Tight: the box touches the frame on at least one axis (1 % slack for the centring passes).
        EXPECT_GT(std::max(reach.x, reach.y), 0.99f) << name << " aspect " << aspect;
      }
    }
  }
}

TEST(Framing, CompassDirectionsFollowTheHeightFieldAxes) {
  const Aabb box{{0, 0, 0}, {1000, 100, 1000}};
  const glm::vec3 centre = box.center();
  const auto from = [&](const char* name) {
    return frameBox(box, parseViewFrom(name), glm::radians(50.0f), 1.5f, centre);
  };
  EXPECT_GT(from("south").position.z, box.max.z); // south is +z (rows grow southwards)
  EXPECT_LT(from("north").position.z, box.min.z);
  EXPECT_GT(from("east").position.x, box.max.x);
  EXPECT_LT(from("west").position.x, box.min.x);
  const Camera sw = from("south-west");
  EXPECT_LT(sw.position.x, centre.x);
  EXPECT_GT(sw.position.z, centre.z);
  const Camera top = from("top");
  EXPECT_NEAR(top.position.x, centre.x, 1e-2f);
  EXPECT_NEAR(top.position.z, centre.z, 1e-2f);
  EXPECT_GT(top.position.y, box.max.y);
  // North (-z) is up in the image: a point north of the centre projects above it.
  const glm::mat4 vp = top.viewProjection(1.5f);
  const glm::vec4 north = vp * glm::vec4(centre.x, centre.y, 100.0f, 1.0f);
  EXPECT_GT(north.y / north.w, 0.0f);
  EXPECT_THROW((void)parseViewFrom("up"), Error);
}

TEST(Framing, ClipPlanesFollowTheCameraAndFogScalesWithTheScene) {
  const Aabb box{{0, 0, 0}, {1000, 100, 1000}};
  Camera camera;
  camera.position = {500, 50, 500}; // inside the box (a walking camera)
  camera.target = {600, 50, 500};
  fitClipPlanes(camera, box);
  EXPECT_GT(camera.nearPlane, 0.0f);
  EXPECT_GE(camera.farPlane, glm::length(glm::vec3(500, 50, 500)));
  EXPECT_GE(camera.nearPlane, camera.farPlane * 1e-5f);
  camera.position = {5000, 3000, 5000}; // far outside: near plane moves out with the distance
  fitClipPlanes(camera, box);
  EXPECT_GT(camera.nearPlane, 100.0f);
  EXPECT_GT(camera.farPlane, glm::length(camera.position));
  // Fog reaches the requested amount at the farthest corner, for a 1 km and a 1000 km scene alike.
  for (const float scale : {1.0f, 1000.0f}) {
    const Aabb scaled{box.min * scale, box.max * scale};
    const glm::vec3 eye = glm::vec3(-500, 800, 1500) * scale;
    const float density = fogDensityFor(eye, scaled, 0.5f);
    float farthest = 0.0f;
    for (const glm::vec3& c : cornersOf(scaled)) {
      farthest = std::max(farthest, glm::length(c - eye));
    }
    EXPECT_NEAR(1.0f - std::exp(-density * farthest), 0.5f, 1e-4f) << scale;
  }
  EXPECT_EQ(fogDensityFor({0, 0, 0}, box, 0.0f), 0.0f);
}

TEST(Framing, OrbitStartsAtTheFramingAndZoomsOutToItsLimit) {
  const Aabb box{{0, 0, 0}, {5.0e5f, 3000, 5.0e5f}};
  const Camera framed = frameBox(box, ViewFrom::SouthWest, glm::radians(50.0f), 1.5f, box.center());
  OrbitController orbit = OrbitController::from(framed);
  Camera again;
  orbit.apply(again);
  EXPECT_LT(glm::length(again.position - framed.position), 1e-3f * glm::length(framed.position));
  orbit.maxDistance = 4.0f * orbit.distance;
  for (int i = 0; i < 200; ++i) {
    orbit.zoom(-1.0f); // scrolling out: well past the old 100 km clamp, up to the limit
  }
  EXPECT_FLOAT_EQ(orbit.distance, orbit.maxDistance);
  EXPECT_GT(orbit.distance, 1.0e5f);
}

} // namespace
} // namespace sylva::render
