// A scene's grass layer reaches the grass field the engine builds from it: every field of scene::GrassLayer
// shows in the field's settings or blades (max_slope once reached nothing, density above 1 was clamped away),
// a scene file's layer goes the same way, and errors name the scene file and the field.
#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/grass/BladeType.hpp>
#include <sylva/grass/Cull.hpp>
#include <sylva/grass/Field.hpp>
#include <sylva/scene/SceneGrass.hpp>

#include "TempDir.hpp"
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <glm/trigonometric.hpp>

#include <cmath>
#include <fstream>
#include <string>

namespace sylva::scene {
namespace {

namespace fs = std::filesystem;

/** 65 × 33 samples 1 m apart: a 64 × 32 m footprint (aspect 2), heights `h` (drawn metres). */
terrain::HeightField flatGround(float h = 5.0f) {
  return terrain::HeightField(65, 33, 1.0f, 1.0f, h);
}

std::vector<terrain::SplatLayer> splatLayers() {
  terrain::SplatLayer sand{.name = "sand", .maxHeight = 2.0f};
  terrain::SplatLayer meadow{.name = "meadow", .minHeight = 2.0f, .maxSlope = 40.0f};
  return {sand, meadow};
}

/** A grey PNG of w × h pixels. */
fs::path writePaint(const test::TempDir& dir, int w, int h) {
  Image image(w, h, 1, PixelType::U8);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.set(x, y, 0, x < w / 2 ? 1.0f : 0.0f);
    }
  }
  const fs::path file = dir / fmt::format("paint-{}x{}.png", w, h);
  saveImage(file, image);
  return file;
}

TEST(SceneGrass, EveryLayerFieldReachesTheField) {
  const test::TempDir dir;
  const terrain::HeightField field = flatGround(6.0f); // drawn metres: 3 m true at exaggeration 2
  const std::vector<terrain::SplatLayer> splat = splatLayers();
  GrassGround on{&field, 2.0f, 1.0f, splat};
  GrassLayer layer;
  layer.blades = {test::sourcePath("data/blades/aloe.json").string()};
  layer.density = 2.5f;
  layer.coverage = 0.4f;
  layer.layer = "meadow";
  layer.paint = writePaint(dir, 64, 32).string();
  layer.maxSlope = 25.0f;
  layer.seed = 42;
  layer.patchBlades = 4096;
  layer.tileSize = 1.5f;
  layer.bladesPerTile = 100;
  // distance goes to the renderer's culling and simulate to the world: neither is a field setting.
  const auto built = buildGrassField(layer, on, sceneGrassFieldName("meadow.json", 0));
  const grass::FieldSettings& s = built->settings();
  EXPECT_EQ(s.patch.blades, 4096);
  EXPECT_EQ(s.patch.tileSize, 1.5f);
  EXPECT_EQ(s.patch.seed, 42u);
  EXPECT_EQ(s.bladesPerTile, 100);
  EXPECT_EQ(s.density.base, 2.5f); // a multiplier: not clamped to 1
  EXPECT_EQ(s.density.coverage, 0.4f);
  EXPECT_EQ(s.density.seed, 43u);
  EXPECT_EQ(s.density.verticalScale, 2.0f);
  // 25 true degrees are atan(2 tan 25°) = 43.0 degrees as drawn at exaggeration 2.
  EXPECT_NEAR(s.density.maxSlopeDegrees, glm::degrees(std::atan(2.0f * std::tan(glm::radians(25.0f)))), 1e-4);
  EXPECT_NEAR(s.density.maxSlopeDegrees, 43.0f, 0.1f);
  ASSERT_TRUE(s.density.layer.has_value());
  EXPECT_EQ(s.density.layer->name, "meadow");
  ASSERT_NE(s.density.paint, nullptr);
  EXPECT_EQ(s.density.paint->width(), 64);
  EXPECT_EQ(s.density.paintMax, glm::vec2(64.0f, 32.0f));
  EXPECT_EQ(s.density.minHeight, (1.0f + 0.3f) * 2.0f); // sea level 1 m, drawn at exaggeration 2
  EXPECT_EQ(built->types().size(), grass::loadBladeTypes(layer.blades[0]).size());
  // The paint mask's white half grows grass and its black half none.
  const grass::DensityMap density(s.density);
  EXPECT_EQ(density.at(48.0f, 16.0f, 6.0f, 0.0f), 0.0f);
  // The code-only noise frequency (the paper's field: 0, one density everywhere); by default the module's.
  EXPECT_EQ(s.density.noiseFrequency, grass::DensitySettings{}.noiseFrequency);
  layer.noiseFrequency = 0.0f;
  EXPECT_EQ(grassFieldSettings(layer, on, sceneGrassFieldName("meadow.json", 0)).density.noiseFrequency,
            0.0f);
}

TEST(SceneGrass, MaxSlopeOfASceneFileThinsTheGrass) {
  const terrain::HeightField field = flatGround();
  const SceneDesc desc = parseScene(R"({"sylva_scene": 1,
      "cameras": {"main": {"position": [0, 10, 0], "target": [1, 10, 0]}},
      "grass": [{"max_slope": 20, "layer": "none", "coverage": 1, "density": 1000}]})",
                                    "meadow.json");
  ASSERT_EQ(desc.grass.size(), 1u);
  const grass::FieldSettings s =
      grassFieldSettings(desc.grass[0], {&field, 1.0f, std::nullopt, {}}, sceneGrassFieldName(desc.path, 0));
  EXPECT_EQ(s.density.maxSlopeDegrees, 20.0f);
  EXPECT_FALSE(s.density.layer.has_value());
  EXPECT_EQ(s.density.base, 1000.0f);
  const grass::DensityMap density(s.density);
  // Density 1000 fills every spot the noise leaves any grass; the slope rule still empties steep ground.
  EXPECT_EQ(density.at(10.0f, 10.0f, 5.0f, 5.0f), 1.0f);
  EXPECT_EQ(density.at(10.0f, 10.0f, 5.0f, 25.0f), 0.0f);
  // The procedural blades when the layer names no blade files.
  EXPECT_EQ(grassBladeTypes(desc.grass[0], sceneGrassFieldName(desc.path, 0)).size(),
            grass::proceduralBladeTypes().size());
}

TEST(SceneGrass, NearTuftsOfASceneFileReachTheCulling) {
  const SceneDesc desc = parseScene(R"({"sylva_scene": 1,
      "cameras": {"main": {"position": [0, 10, 0], "target": [1, 10, 0]}},
      "grass": [{"near_layers": 3, "near_distance": 5.5}, {}]})",
                                    "meadow.json");
  ASSERT_EQ(desc.grass.size(), 2u);
  const grass::CullSettings set = grassCullSettings(desc.grass[0], sceneGrassFieldName(desc.path, 0));
  EXPECT_EQ(set.nearLayers, 3);
  EXPECT_EQ(set.nearDistance, 5.5f);
  const grass::CullSettings defaults = grassCullSettings(desc.grass[1], sceneGrassFieldName(desc.path, 1));
  EXPECT_EQ(defaults.nearLayers, grass::CullSettings{}.nearLayers);
  EXPECT_EQ(defaults.nearDistance, grass::CullSettings{}.nearDistance);
  const std::string bad = test::errorOf([] {
    (void)parseScene(
        R"({"sylva_scene": 1, "cameras": {"main": {"position": [0, 10, 0], "target": [1, 10, 0]}},
                         "grass": [{"near_layers": 0}]})",
        "meadow.json");
  });
  EXPECT_NE(bad.find("/grass/0/near_layers"), std::string::npos) << bad;
}

TEST(SceneGrass, ErrorsNameTheSceneFileAndTheField) {
  const test::TempDir dir;
  const terrain::HeightField field = flatGround();
  const std::vector<terrain::SplatLayer> splat = splatLayers();
  const GrassGround on{&field, 1.0f, std::nullopt, splat};
  const GrassFieldName name = sceneGrassFieldName("dir/meadow.json", 2);
  auto failure = [&](const GrassLayer& layer) {
    return test::errorOf([&] { (void)buildGrassField(layer, on, name); });
  };
  GrassLayer layer;
  layer.layer = "rock";
  const std::string noLayer = failure(layer);
  EXPECT_NE(noLayer.find("dir/meadow.json: /grass/2/layer: the terrain has no splat layer 'rock'"),
            std::string::npos)
      << noLayer;
  EXPECT_NE(noLayer.find("sand, meadow"), std::string::npos) << noLayer;

  layer = {};
  layer.layer = "none";
  layer.paint = writePaint(dir, 40, 40).string();
  const std::string aspect = failure(layer);
  EXPECT_NE(aspect.find("dir/meadow.json: /grass/2/paint: "), std::string::npos) << aspect;
  EXPECT_NE(aspect.find("does not match the terrain's 64 x 32 m footprint"), std::string::npos) << aspect;
  layer.paint = writePaint(dir, 1, 1).string();
  EXPECT_NE(failure(layer).find("/grass/2/paint: "), std::string::npos);

  layer = {};
  layer.layer = "none";
  const fs::path empty = dir / "empty.json";
  std::ofstream(empty) << R"({"blades": []})";
  layer.blades = {empty.string()};
  EXPECT_NE(failure(layer).find("dir/meadow.json: /grass/2/blades: "), std::string::npos) << failure(layer);

  layer = {};
  layer.layer = "none";
  layer.maxSlope = 95.0f;
  EXPECT_NE(failure(layer).find("/grass/2/max_slope: "), std::string::npos);
  layer.maxSlope = 30.0f;
  layer.bladesPerTile = layer.patchBlades + 1;
  EXPECT_NE(failure(layer).find("/grass/2/blades_per_tile: "), std::string::npos);
}

} // namespace
} // namespace sylva::scene
