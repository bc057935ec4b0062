// Screen-space-error LOD, measured as drawn: the terrain's world positions rendered on the GPU and compared,
// pixel by pixel, with the full-resolution surface (docs/terrain-lod.md, "Screen-space error").
#include <sylva/core/Random.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/gpu/TerrainError.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace sylva::terrain {
namespace {

using TerrainErrorLod = test::GlTest;

/** Pose `index` over Jacksboro: 60 m to 3 km above the ground, looking slightly down. */
render::Camera errorPose(const HeightField& field, int index) {
  Rng rng(0xE4404ULL + static_cast<std::uint64_t>(index));
  render::Camera camera;
  const float x = rng.uniform(0.1f, 0.9f) * field.extentX();
  const float z = rng.uniform(0.1f, 0.9f) * field.extentZ();
  camera.position = {x, heightAt(field, x, z) + 60.0f * std::pow(50.0f, rng.uniform()), z};
  const float yaw = rng.uniform(0.0f, 6.2831853f);
  const float pitch = rng.uniform(-0.6f, -0.08f);
  camera.target = camera.position + glm::vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                              std::cos(pitch) * std::cos(yaw));
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 5.0f;
  camera.farPlane = 2.0f * std::max(field.extentX(), field.extentZ());
  return camera;
}

// The error rule bounds each leaf's projected error by τ at the image centre (corners magnify a little). Over
// whole frames, measured against the same view drawn with every patch at the deepest level, the drawn error
// stays within τ, while distance LOD at its default factor leaves larger errors: the measure sees LOD.
TEST_F(TerrainErrorLod, DrawnErrorStaysNearTheThresholdOnJacksboro) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  const HeightField field = loadHeightField(test::externalData("jacksboro_fault_dem.npz"));
  const HeightFieldInfo info = heightFieldInfo(field);
  TerrainRenderer renderer(shaders(), field, defaultSplatLayers(info.minHeight, info.maxHeight));
  PositionTarget target(480, 300);
  QuadtreeConfig config = QuadtreeConfig::forRootCount(16, field.extentX(), field.extentZ());
  config.maxDepth = 5;
  config.patchTessLevel = 16;
  Quadtree distance(config, field);
  config.lodErrorPixels = 1.0f;
  config.pixelsPerRadian = QuadtreeConfig::pixelsPerRadianFor(300.0f, glm::radians(50.0f));
  Quadtree error(config, field);
  Quadtree full(config.fullDepth(), field);
  double worstError = 0.0;
  double worstDistance = 0.0;
  double meanError = 0.0;
  std::size_t leavesError = 0;
  std::size_t leavesDistance = 0;
  constexpr int kPoses = 12;
  for (int pose = 0; pose < kPoses; ++pose) {
    const render::Camera camera = errorPose(field, pose);
    const Frustum frustum = camera.frustum(target.aspect());
    const QuadtreeSelection byError = error.select(camera.position, &frustum);
    const QuadtreeSelection byDistance = distance.select(camera.position, &frustum);
    const Image reference = target.draw(renderer, full.select(camera.position, &frustum), camera);
    const ScreenErrorStats e = target.measure(renderer, field, byError, reference, camera);
    const ScreenErrorStats d = target.measure(renderer, field, byDistance, reference, camera);
    const ScreenErrorStats self =
        target.measure(renderer, field, full.select(camera.position, &frustum), reference, camera);
    ASSERT_EQ(self.worstPx, 0.0) << "pose " << pose << ": the reference against itself";
    ASSERT_GT(e.pixels, 1000u) << "pose " << pose << " sees too little terrain";
    worstError = std::max(worstError, e.worstPx);
    worstDistance = std::max(worstDistance, d.worstPx);
    meanError += e.meanPx / kPoses;
    leavesError += byError.nodes.size();
    leavesDistance += byDistance.nodes.size();
  }
  RecordProperty("worst_px_error_lod", fmt::format("{:.3f}", worstError));
  RecordProperty("mean_px_error_lod", fmt::format("{:.4f}", meanError));
  RecordProperty("worst_px_distance_lod", fmt::format("{:.3f}", worstDistance));
  RecordProperty("leaves_error_lod", std::to_string(leavesError));
  RecordProperty("leaves_distance_lod", std::to_string(leavesDistance));
  std::printf("error LOD: worst %.3f px, mean %.4f px, %zu leaves; distance LOD: worst %.3f px, %zu leaves\n",
              worstError, meanError, leavesError, worstDistance, leavesDistance);
  EXPECT_LE(worstError, 1.0);
  EXPECT_GT(worstDistance, 1.5);
}

} // namespace
} // namespace sylva::terrain
