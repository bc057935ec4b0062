// A scene file's forest reaches the trees module's descriptions: every field of scene::ForestDesc shows in
// the placement settings or the look, a forest without a region grows over the whole terrain (it once grew
// within 150 m of the terrain's corner, a default of `sylva render --trees`), and errors name the file and
// field.
#include <sylva/core/Error.hpp>
#include <sylva/scene/SceneForest.hpp>

#include "TestUtil.hpp"

#include <gtest/gtest.h>

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
