// A scene file's forest reaches the trees module's descriptions: every field of scene::ForestDesc shows in
// the placement settings or the look, a forest without a region grows over the whole terrain (it once grew
// within 150 m of the terrain's corner, a default of `sylva render --trees`), and errors name the file and
// field.
#include <sylva/core/Error.hpp>
#include <sylva/scene/SceneForest.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/TerrainMaps.hpp>

#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace sylva::scene {
namespace {

const FieldName kName = sceneForestFieldName("/scenes/wood.json", 2);

TEST(SceneForest, EveryFieldReachesThePlacementOrTheLook) {
  ForestDesc f;
  f.species = {{"silver-birch", 2.0f}, {"almond", 1.0f}};
  f.count = 77;
  f.seed = 5;
  f.spacing = 7.5f;
  f.maxSlope = 21.0f;
  f.minHeight = 3.0f;
  f.maxHeight = 90.0f;
  f.clusterSize = 44.0f;
  f.bare = 0.5f;
  f.autumn = 0.75f;
  f.leafFall = 0.4f;
  f.regionCentre = glm::vec2(100.0f, 200.0f);
  f.regionRadius = 60.0f;
  f.bark = "procedural";
  f.foliage = false;
  f.farDistance = 300.0f;
  f.farBand = 40.0f;
  f.farCount = 12;
  const trees::ForestSettings s = forestSettings(f, 2.0f, 10.0f, kName);
  ASSERT_EQ(s.species.size(), 2u);
  EXPECT_EQ(s.species[0], "almond"); // the file's map, in name order
  EXPECT_FLOAT_EQ(s.speciesWeights[0], 1.0f);
  EXPECT_FLOAT_EQ(s.speciesWeights[1], 2.0f);
  EXPECT_EQ(s.count, 77);
  EXPECT_EQ(s.seed, 5u);
  EXPECT_FLOAT_EQ(s.spacing, 7.5f);
  EXPECT_FLOAT_EQ(s.maxSlope, 21.0f);
  EXPECT_FLOAT_EQ(s.minHeight, 3.0f); // the file's band wins over the sea
  EXPECT_FLOAT_EQ(s.maxHeight, 90.0f);
  EXPECT_FLOAT_EQ(s.clusterSize, 44.0f);
  EXPECT_FLOAT_EQ(s.bare, 0.5f);
  EXPECT_FLOAT_EQ(s.autumn, 0.75f);
  EXPECT_FLOAT_EQ(s.leafFall, 0.4f);
  EXPECT_EQ(s.regionCentre, glm::vec2(100.0f, 200.0f));
  EXPECT_FLOAT_EQ(s.regionRadius, 60.0f);
  EXPECT_FLOAT_EQ(s.verticalScale, 1.0f); // placement reads drawn heights
  const trees::ForestLook look = forestLook(f, kName);
  EXPECT_EQ(look.bark, "procedural");
  EXPECT_FALSE(look.foliage);
  EXPECT_FLOAT_EQ(look.farDistance, 300.0f);
  EXPECT_FLOAT_EQ(look.farBand, 40.0f);
  EXPECT_EQ(look.farCount, 12);
}

TEST(SceneForest, NoRegionIsTheWholeTerrainAndTheSeaSetsTheFloor) {
  ForestDesc f;
  f.species = {{"silver-birch", 1.0f}};
  const trees::ForestSettings s = forestSettings(f, 2.0f, 10.0f, kName);
  EXPECT_FLOAT_EQ(s.regionRadius, 0.0f);
  EXPECT_FLOAT_EQ(s.minHeight, (10.0f + 0.5f) * 2.0f); // drawn metres
  EXPECT_TRUE(std::isnan(forestSettings(f, 2.0f, std::nullopt, kName).minHeight));
}

// Without a max_height the forest stops where the terrain's snow starts (issue 30: the forest of `render
// --trees` stood on snow): the tree line is read from the splat rules, in true metres, drawn × exaggeration.
TEST(SceneForest, WithoutATopTheForestStopsBelowTheSnow) {
  const std::vector<terrain::SplatLayer> layers = terrain::defaultSplatLayers(0.0f, 100.0f);
  const std::optional<float> line = terrain::snowLine(layers);
  ASSERT_TRUE(line.has_value());
  EXPECT_FLOAT_EQ(*line, 70.0f - 0.5f * 4.0f); // snow from 70 m with a 4 m soft edge
  EXPECT_FALSE(terrain::snowLine(std::vector<terrain::SplatLayer>{{"grass", 0.0f, 50.0f}}).has_value());
  // With a sea: the snow line of the land above it.
  const std::optional<float> coast = terrain::snowLine(terrain::defaultSplatLayers(-20.0f, 100.0f, 0.0f));
  ASSERT_TRUE(coast.has_value());
  EXPECT_NEAR(*coast, 70.0f - 2.0f, 1e-4f);

  ForestDesc f;
  f.species = {{"almond", 1.0f}};
  f.count = 400;
  f.spacing = 3.0f;
  f.bare = 0.0f;
  const float exaggeration = 1.5f;
  EXPECT_FLOAT_EQ(forestSettings(f, exaggeration, std::nullopt, kName, {}, line).maxHeight,
                  *line * exaggeration);
  EXPECT_TRUE(std::isnan(forestSettings(f, exaggeration, std::nullopt, kName).maxHeight));
  // A tree line below the floor is no band: the file's floor stays, no empty band.
  f.minHeight = 200.0f;
  EXPECT_TRUE(std::isnan(forestSettings(f, exaggeration, std::nullopt, kName, {}, line).maxHeight));
  f.minHeight.reset();
  f.maxHeight = 140.0f; // the file's top wins
  EXPECT_FLOAT_EQ(forestSettings(f, exaggeration, std::nullopt, kName, {}, line).maxHeight, 140.0f);
  f.maxHeight.reset();

  // Placed on a slope rising 0 → 150 drawn metres (true 0 → 100): no tree on the snow, some without the line.
  terrain::HeightField field(65, 65, 8.0f, 8.0f); // 512 m: a 16° slope
  for (int j = 0; j < field.height(); ++j) {
    for (int i = 0; i < field.width(); ++i) {
      field.at(i, j) = 150.0f * static_cast<float>(i) / 64.0f;
    }
  }
  auto highest = [&](const trees::Forest& forest) {
    float top = -1.0f;
    for (const trees::ForestTree& t : forest.trees) {
      top = std::max(top, t.base[3].y);
    }
    return top;
  };
  const trees::Forest bounded =
      trees::placeForest(field, forestSettings(f, exaggeration, std::nullopt, kName, {}, line));
  const trees::Forest unbounded =
      trees::placeForest(field, forestSettings(f, exaggeration, std::nullopt, kName));
  ASSERT_GT(bounded.trees.size(), 20u);
  EXPECT_LE(highest(bounded), *line * exaggeration);
  EXPECT_GT(highest(unbounded), *line * exaggeration);
}

TEST(SceneForest, TheSeasonReachesEachSpeciesOfThePlacedForest) {
  // Autumn colours and leaf fall apply to the forest's copies of its species: a deciduous oak turns and goes
  // bare, the evergreen spruce keeps its green needles.
  ForestDesc f;
  f.species = {{"california-black-oak", 1.0f}, {"norway-spruce", 1.0f}};
  f.count = 4;
  f.autumn = 1.0f;
  f.leafFall = 1.0f;
  terrain::HeightField field(33, 33, 4.0f, 4.0f);
  const trees::Forest forest = trees::placeForest(field, forestSettings(f, 1.0f, std::nullopt, kName));
  ASSERT_EQ(forest.species.size(), 2u);
  const trees::Species& oak = forest.species[0];
  const trees::Species& spruce = forest.species[1];
  ASSERT_EQ(oak.name, "california-black-oak");
  EXPECT_EQ(oak.leafColour, trees::speciesPreset("california-black-oak").autumnColour);
  EXPECT_FLOAT_EQ(oak.leafDensity, 0.0f);
  EXPECT_EQ(spruce.leafColour, trees::speciesPreset("norway-spruce").leafColour);
  EXPECT_FLOAT_EQ(spruce.leafDensity, 1.0f);
  f.leafFall = 0.25f;
  const trees::Forest early = trees::placeForest(field, forestSettings(f, 1.0f, std::nullopt, kName));
  EXPECT_FLOAT_EQ(early.species[0].leafDensity, 0.75f);
}

TEST(SceneForest, ErrorsNameTheFileAndField) {
  ForestDesc f;
  f.species = {{"no-such-tree", 1.0f}};
  std::string message = test::errorOf([&] { (void)forestSettings(f, 1.0f, std::nullopt, kName); });
  EXPECT_NE(message.find("/scenes/wood.json: /forests/2/species/no-such-tree"), std::string::npos) << message;
  f.species = {{"silver-birch", 1.0f}};
  f.bark = "/no/such/tiles";
  message = test::errorOf([&] { (void)forestLook(f, kName); });
  EXPECT_NE(message.find("/scenes/wood.json: /forests/2/bark"), std::string::npos) << message;
  f.bark = "auto";
  f.maxSlope = 95.0f;
  message = test::errorOf([&] { (void)forestSettings(f, 1.0f, std::nullopt, kName); });
  EXPECT_NE(message.find("/scenes/wood.json: /forests/2"), std::string::npos) << message;
}

} // namespace
} // namespace sylva::scene
