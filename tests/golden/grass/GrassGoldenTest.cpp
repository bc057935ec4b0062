// Grass field images: a field on a small procedural terrain (shaded and in the LOD debug view) and on the
// real Jacksboro DEM, each from a fixed ground-level camera, with wind at a fixed time.
#include <sylva/grass/gpu/GrassRenderer.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"
#include "Golden.hpp"

namespace sylva::grass {
namespace {

using GrassGolden = test::GlTest;

/** A camera `eyeHeight` metres above the ground at world (x, z), looking `ahead` metres along `angle` (rad).
 */
render::Camera groundCamera(const terrain::HeightField& field, glm::vec2 at, float angle, float eyeHeight,
                            float ahead = 20.0f) {
  const glm::vec2 to = at + ahead * glm::vec2(std::cos(angle), std::sin(angle));
  render::Camera camera;
  camera.position = {at.x, terrain::heightAt(field, at.x, at.y) + eyeHeight, at.y};
  camera.target = {to.x, terrain::heightAt(field, to.x, to.y) - 0.5f, to.y};
  camera.fovY = glm::radians(55.0f);
  camera.nearPlane = 0.05f;
  camera.farPlane = 20000.0f;
  return camera;
}

Image render(terrain::TerrainScene& scene, GrassRenderer& grass, const render::Camera& camera,
             GrassView view) {
  render::RenderTarget target(320, 240);
  terrain::TerrainDrawOptions terrainOptions = scene.drawOptions(camera);
  terrainOptions.groundTint = grass.groundTint();
  target.begin(glm::vec4(terrainOptions.environment.fogColor, 1.0f));
  scene.update(camera, target.aspect());
  scene.draw(camera, 320, 240, 0.0, nullptr, terrainOptions);
  grass.cull(camera, target.aspect());
  GrassDrawOptions options;
  options.view = view;
  options.environment = terrainOptions.environment;
  options.wind.speed = 4.0f;
  options.wind.direction = {0.8f, 0.6f};
  grass.draw(camera, 320, 240, 2.0, nullptr, options);
  return target.readColor();
}

terrain::QuadtreeConfig config(float rootSize) {
  terrain::QuadtreeConfig c;
  c.rootSize = rootSize;
  c.maxDepth = 4;
  c.patchTessLevel = 16;
  return c;
}

// Tolerance: blades are thinner than a pixel far away, so one rounding difference in the rasteriser (or a
// transcendental function one ulp off) moves whole blade pixels; up to 6 levels on at most 2 % of the pixels.
TEST_F(GrassGolden, ProceduralFieldShadedAndLod) {
  terrain::ProceduralSpec spec = terrain::TerrainSource::defaultProcedural();
  spec.frequency = 1.0f / 250.0f;
  spec.heightScale = 25.0f;
  // Meadow everywhere but on steep slopes.
  terrain::SplatLayer meadow;
  meadow.name = "grass";
  terrain::SplatLayer rock;
  rock.name = "rock";
  rock.minSlope = 35.0f;
  rock.slopeBlend = 6.0f;
  terrain::TerrainScene scene(shaders(), terrain::generate(spec, 0.0, 0.0, 129, 129, 1.5f), config(64.0f),
                              std::vector<terrain::SplatLayer>{meadow, rock});
  FieldSettings fs;
  fs.bladesPerTile = 256;
  auto field = std::make_shared<GrassField>(scene.field(), proceduralBladeTypes(), fs);
  CullSettings cull;
  cull.maxDistance = 80.0f;
  cull.farFade = 15.0f;
  GrassRenderer grass(shaders(), field, cull);
  const render::Camera camera = groundCamera(scene.field(), {60.0f, 70.0f}, 0.4f, 1.6f);
  test::expectGolden(render(scene, grass, camera, GrassView::Shaded), "grass_procedural", {6, 0.02});
  test::expectGolden(render(scene, grass, camera, GrassView::LodColours), "grass_procedural_lod", {6, 0.02});
}

TEST_F(GrassGolden, JacksboroField) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  terrain::HeightField dem = terrain::loadHeightField(test::externalData("jacksboro_fault_dem.npz"));
  const terrain::QuadtreeConfig quadtree =
      terrain::QuadtreeConfig::forRootCount(16, dem.extentX(), dem.extentZ());
  terrain::TerrainScene scene(shaders(), std::move(dem), quadtree);
  FieldSettings fs;
  fs.bladesPerTile = 128;
  // A coarse density grid: the DEM is 30 km across.
  fs.densitySpacing = 8.0f;
  auto field = std::make_shared<GrassField>(scene.field(), proceduralBladeTypes(), fs);
  GrassRenderer grass(shaders(), field);
  const render::Camera camera = groundCamera(scene.field(), {15000.0f, 16000.0f}, 2.2f, 1.7f, 40.0f);
  test::expectGolden(render(scene, grass, camera, GrassView::Shaded), "grass_jacksboro", {6, 0.02});
}

} // namespace
} // namespace sylva::grass
