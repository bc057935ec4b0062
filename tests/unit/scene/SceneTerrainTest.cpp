// A scene file's terrain reaches the terrain setup the engine builds from (the same builder as
// `sylva render --dem/--seed`): every field of scene::TerrainDesc shows in the setup, values the quadtree
// cannot take are refused when the file is read, and setup errors name the file and field.
#include <sylva/core/Error.hpp>
#include <sylva/scene/SceneTerrain.hpp>

#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <string>

namespace sylva::scene {
namespace {

/** A scene file with one camera and `terrain` as its terrain object's members. */
SceneDesc sceneWithTerrain(const std::string& terrain, const char* file) {
  return parseScene(R"({"sylva_scene": 1, "cameras": {"main": {"position": [0, 10, 0], "target": [1, 10, 0]}},
      "terrain": {)" + terrain +
                        "}}",
                    file);
}

TEST(SceneTerrain, EveryProceduralFieldReachesTheSetup) {
  const SceneDesc scene = sceneWithTerrain(R"("seed": 42, "size": 129, "spacing": 3.5, "relief": 77,
      "exaggeration": 1.5, "sea_level": 12, "tess_level": 8, "lod_factor": 3, "max_depth": 4, "geomorph": false)",
                                           "/scenes/hill.json");
  const terrain::TerrainSetup s = terrainSetup(scene.terrain);
  EXPECT_TRUE(s.source.dem.empty());
  EXPECT_EQ(s.source.procedural.seed, 42u);
  EXPECT_EQ(s.source.proceduralSize, 129);
  EXPECT_FLOAT_EQ(s.source.proceduralSpacing, 3.5f);
  EXPECT_FLOAT_EQ(s.source.procedural.heightScale, 77.0f);
  // The rest of the spec is the demo landscape's (what `sylva render --seed` draws).
  const terrain::ProceduralSpec demo = terrain::TerrainSource::defaultProcedural();
  EXPECT_EQ(s.source.procedural.type, demo.type);
  EXPECT_EQ(s.source.procedural.octaves, demo.octaves);
  EXPECT_FLOAT_EQ(s.exaggeration, 1.5f);
  EXPECT_EQ(s.seaLevel.kind, terrain::SeaLevelRule::Kind::Metres);
  EXPECT_FLOAT_EQ(s.seaLevel.metres, 12.0f);
  EXPECT_EQ(s.quadtree.patchTessLevel, 8);
  EXPECT_FLOAT_EQ(s.quadtree.lodDistanceFactor, 3.0f);
  ASSERT_TRUE(s.maxDepth.has_value());
  EXPECT_EQ(*s.maxDepth, 4);
  EXPECT_FALSE(s.geomorph);
  EXPECT_TRUE(s.layersFile.empty());
}

TEST(SceneTerrain, DefaultsGiveNoSeaAnAutomaticDepthAndGeomorphing) {
  const SceneDesc scene = sceneWithTerrain("", "/scenes/flat.json");
  const terrain::TerrainSetup s = terrainSetup(scene.terrain);
  EXPECT_EQ(s.seaLevel.kind, terrain::SeaLevelRule::Kind::None);
  EXPECT_FALSE(s.maxDepth.has_value());
  EXPECT_TRUE(s.geomorph);
  EXPECT_EQ(s.quadtree.patchTessLevel, 16);
}

TEST(SceneTerrain, ADemKeepsItsSpacingUnlessTheFileSetsOne) {
  TerrainDesc t;
  t.dem = "/data/dem.tif";
  EXPECT_EQ(terrainSetup(t).source.dem, "/data/dem.tif");
  EXPECT_FLOAT_EQ(terrainSetup(t).source.load.spacing, 0.0f); // 0: the file's own
  t.spacing = 30.0f;
  t.spacingSet = true;
  EXPECT_FLOAT_EQ(terrainSetup(t).source.load.spacing, 30.0f);
}

TEST(SceneTerrain, ValuesTheQuadtreeCannotTakeAreRefusedWhenTheFileIsRead) {
  // tess_level 64 once passed the file and failed later as a command-line option (`--tess`).
  for (const char* field : {"tess_level", "lod_factor", "max_depth"}) {
    (void)sceneWithTerrain(std::string("\"") + field + "\": 16", "/scenes/good.json"); // in range for each
  }
  for (const std::string field : {"tess_level\": 33", "lod_factor\": 1.01", "max_depth\": 17"}) {
    const std::string message =
        test::errorOf([&] { (void)sceneWithTerrain("\"" + field, "/scenes/bad.json"); });
    const std::string name = field.substr(0, field.find('"'));
    EXPECT_NE(message.find("/scenes/bad.json"), std::string::npos) << message;
    EXPECT_NE(message.find("/terrain/" + name), std::string::npos) << message;
  }
}

TEST(SceneTerrain, SetupErrorsNameTheFileAndField) {
  const terrain::TerrainFieldName name = sceneTerrainFieldName("/scenes/hill.json");
  EXPECT_EQ(name("size"), "/scenes/hill.json: /terrain/size");
  TerrainDesc t;
  t.tessLevel = 40; // a description built in code, not read from a file
  const terrain::TerrainSetup s = terrainSetup(t);
  const std::string message = test::errorOf(
      [&] { (void)terrain::quadtreeFor(s, terrain::HeightField(65, 65, 1.0f, 1.0f, 0.0f), name); });
  EXPECT_NE(message.find("/scenes/hill.json: /terrain/tess_level"), std::string::npos) << message;
}

} // namespace
} // namespace sylva::scene
