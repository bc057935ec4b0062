// Terrain images: a small procedural terrain in each debug view, and the real Jacksboro DEM shaded.
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"
#include "Golden.hpp"

namespace sylva::terrain {
namespace {

using TerrainGolden = test::GlTest;

HeightField smallTerrain() {
  ProceduralSpec spec = TerrainSource::defaultProcedural();
  spec.frequency = 1.0f / 300.0f;
  spec.heightScale = 160.0f;
  return generate(spec, 0.0, 0.0, 129, 129, 6.0f);
}

/**
 * A fixed camera across the terrain from its south-west, and fog reaching ~70 % at the far side: the goldens
 * (llvmpipe and NVIDIA) were made with it, so they do not follow changes to the default framing.
 */
render::Camera goldenCamera(const TerrainScene& scene) {
  const float ex = scene.field().extentX();
  const float ez = scene.field().extentZ();
  const float span = std::max(ex, ez);
  const float relief = std::max(scene.maxHeight() - scene.minHeight(), 1.0f);
  render::Camera camera;
  camera.position = {0.02f * ex, scene.maxHeight() + 0.4f * relief + 0.1f * span, 1.0f * ez};
  camera.target = {0.5f * ex, scene.minHeight(), 0.42f * ez};
  camera.nearPlane = std::max(0.1f, 0.0005f * span);
  camera.farPlane = 4.0f * span + 4.0f * relief;
  camera.fovY = glm::radians(55.0f);
  return camera;
}

Image renderScene(TerrainScene& scene, TerrainView view, bool wireframe = false) {
  render::RenderTarget target(320, 240);
  TerrainDrawOptions options;
  options.view = view;
  options.wireframe = wireframe;
  options.environment.fogDensity = 0.9f / std::max(scene.field().extentX(), scene.field().extentZ());
  target.begin(glm::vec4(options.environment.fogColor, 1.0f));
  const render::Camera camera = goldenCamera(scene);
  scene.update(camera, target.aspect());
  scene.draw(camera, 320, 240, 0.0, nullptr, options);
  return target.readColor();
}

QuadtreeConfig smallConfig() {
  QuadtreeConfig config;
  config.rootSize = 256.0f;
  config.maxDepth = 4;
  config.patchTessLevel = 8;
  return config;
}

// Tolerance: texture minification (mip selection from derivatives) and transcendental functions may differ by
// a step between LLVM versions; 2 steps on at most 0.5 % of pixels, edges of wireframe lines 1 %.
TEST_F(TerrainGolden, ProceduralShaded) {
  TerrainScene scene(shaders(), smallTerrain(), smallConfig());
  test::expectGolden(renderScene(scene, TerrainView::Shaded), "terrain_shaded", {2, 0.005});
}

TEST_F(TerrainGolden, ProceduralLodColoursWireframe) {
  TerrainScene scene(shaders(), smallTerrain(), smallConfig());
  test::expectGolden(renderScene(scene, TerrainView::LodColours, true), "terrain_lod_wireframe", {2, 0.01});
}

TEST_F(TerrainGolden, ProceduralNormalsAndSplat) {
  TerrainScene scene(shaders(), smallTerrain(), smallConfig());
  test::expectGolden(renderScene(scene, TerrainView::Normals), "terrain_normals", {2, 0.005});
  test::expectGolden(renderScene(scene, TerrainView::Splat), "terrain_splat", {2, 0.005});
}

TEST_F(TerrainGolden, JacksboroShaded) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  HeightField field = loadHeightField(test::externalData("jacksboro_fault_dem.npz"));
  const QuadtreeConfig config = QuadtreeConfig::forRootCount(16, field.extentX(), field.extentZ());
  TerrainScene scene(shaders(), std::move(field), config);
  test::expectGolden(renderScene(scene, TerrainView::Shaded), "terrain_jacksboro", {2, 0.005});
}

} // namespace
} // namespace sylva::terrain
