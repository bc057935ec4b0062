// sylva tree measure (issue 29): the measures of a tree follow its geometry.
#include <sylva/trees/Measure.hpp>

#include <sylva/trees/Skeleton.hpp>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>

#include <algorithm>

namespace sylva::trees {
namespace {

std::size_t capNodes(const PieceSet& pieces, const TreeTopology& tree) {
  return static_cast<std::size_t>(std::count_if(tree.nodes.begin(), tree.nodes.end(), [&](const TreeNode& n) {
    return pieces[static_cast<std::size_t>(n.piece)].leafRims() == 0;
  }));
}

TEST(TreeMeasure, HeightTipsAndCrownFollowTheTreesGeometry) {
  const PieceSet pieces = standardPieces();
  const Species species = speciesPreset("almond");
  const TreeTopology tree = generateTree(pieces, species, 3);
  const TreeMeasures straight = measureTree(pieces, tree, species, {});
  // The rest pose's height from the pieces' vertices (treeStats), in metres.
  const float restHeight = treeStats(pieces, tree).height * species.trunkRadius;
  EXPECT_NEAR(straight.height, restHeight, 0.02f * restHeight);
  EXPECT_FLOAT_EQ(straight.trunkRadius, species.trunkRadius);
  EXPECT_FLOAT_EQ(straight.slenderness, straight.height / species.trunkRadius);
  EXPECT_EQ(straight.tips, capNodes(pieces, tree));
  EXPECT_EQ(straight.pieces, tree.nodes.size());
  EXPECT_GT(straight.crownBase, 0.0f);
  EXPECT_LT(straight.crownBase, straight.height);
  EXPECT_FLOAT_EQ(straight.crownHeight, straight.height - straight.crownBase);
  // No band of the silhouette is wider than the crown above the crown base.
  for (int b = 0; b < kProfileBins; ++b) {
    const float bandBottom = straight.height * static_cast<float>(b) / kProfileBins;
    if (bandBottom >= straight.crownBase) {
      EXPECT_LE(straight.profile[static_cast<std::size_t>(b)], straight.crownWidth * 1.0001f) << b;
    }
  }

  // Turned upside down above the foot, the tips that pointed up point down and the other way round.
  std::vector<glm::vec2> flip(tree.jointCount(), glm::vec2(0.0f));
  for (std::size_t j = 1; j < tree.jointCount(); ++j) {
    if (tree.jointParent[j] == 0) {
      flip[j] = glm::vec2(glm::pi<float>(), 0.0f);
    }
  }
  const TreeMeasures flipped = measureTree(pieces, tree, species, flip);
  EXPECT_EQ(flipped.tips, straight.tips);
  EXPECT_EQ(flipped.droopingTips + straight.droopingTips, straight.tips);
  EXPECT_GT(flipped.droopingFraction, 0.5f);
  EXPECT_LT(straight.droopingFraction, 0.5f);
  EXPECT_LT(flipped.height, 0.5f * straight.height);
}

TEST(TreeMeasure, AColumnIsNarrowerThanASpreadingCrownAndSummariesBracketTheTrees) {
  const PieceSet pieces = standardPieces();
  std::vector<TreeMeasures> poplars;
  std::vector<TreeMeasures> oaks;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    poplars.push_back(measureSpecies(pieces, speciesPreset("lombardy-poplar"), seed));
    oaks.push_back(measureSpecies(pieces, speciesPreset("california-black-oak"), seed));
  }
  const MeasureSummary poplar = summarise(poplars);
  const MeasureSummary oak = summarise(oaks);
  EXPECT_LT(poplar.mean.crownRatio, oak.mean.crownRatio);
  for (const MeasureSummary* s : {&poplar, &oak}) {
    ASSERT_EQ(s->trees.size(), 5u);
    for (const TreeMeasures& t : s->trees) {
      EXPECT_LE(s->min.height, t.height);
      EXPECT_GE(s->max.height, t.height);
      EXPECT_LE(s->min.crownRatio, t.crownRatio);
      EXPECT_GE(s->max.crownRatio, t.crownRatio);
    }
    EXPECT_LE(s->min.droopingFraction, s->mean.droopingFraction);
    EXPECT_LE(s->mean.droopingFraction, s->max.droopingFraction);
    float sum = 0.0f;
    for (const TreeMeasures& t : s->trees) {
      sum += t.height;
    }
    EXPECT_NEAR(s->mean.height, sum / 5.0f, 1e-4f);
  }
  // The same tree measures the same (the seed and the pose are deterministic).
  EXPECT_EQ(measureSpecies(pieces, speciesPreset("lombardy-poplar"), 1).height, poplars.front().height);
  const nlohmann::json json = describeMeasuresJson("lombardy-poplar", 1, poplar);
  EXPECT_EQ(json.at("trees").size(), 5u);
  EXPECT_EQ(json.at("trees").at(2).at("seed"), 3);
  EXPECT_NE(describeMeasures("lombardy-poplar", 1, poplar).find("mean"), std::string::npos);
}

TEST(TreeSpeciesTargets, EveryRealSpeciesFallsInsideItsTargetsForTwentySeeds) {
  // docs/trees.md "Species targets": height, slenderness, spread, crown base and drooping tips of each preset
  // of a real species, seeds 1 … 20, in the pose the renderer draws.
  const PieceSet pieces = standardPieces();
  const std::vector<std::string> names = realSpeciesPresetNames();
  ASSERT_GE(names.size(), 8u);
  for (const std::string& name : names) {
    const std::optional<SpeciesTargets> targets = speciesTargets(name);
    ASSERT_TRUE(targets.has_value()) << name << " has no targets";
    const Species species = speciesPreset(name);
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      const std::string miss = targetMisses(measureSpecies(pieces, species, seed), *targets);
      EXPECT_TRUE(miss.empty()) << name << " seed " << seed << ": " << miss;
    }
  }
  // The targets tell species apart: a poplar is no oak, a willow no poplar.
  EXPECT_FALSE(targetMisses(measureSpecies(pieces, speciesPreset("lombardy-poplar"), 1),
                            *speciesTargets("california-black-oak"))
                   .empty());
  EXPECT_FALSE(targetMisses(measureSpecies(pieces, speciesPreset("weeping-willow"), 1),
                            *speciesTargets("lombardy-poplar"))
                   .empty());
  EXPECT_FALSE(speciesTargets("paper-alternate").has_value());
}

TEST(TreeMeasure, SpreadCountsTheLeafClusters) {
  // The leafy width holds the wood's crown and grows with the clusters' radius by about twice the change.
  const PieceSet pieces = standardPieces();
  Species species = speciesPreset("quaking-aspen");
  const TreeMeasures a = measureSpecies(pieces, species, 4);
  species.leafCluster += 1.0f;
  const TreeMeasures b = measureSpecies(pieces, species, 4);
  EXPECT_GE(a.leafyWidth, a.crownWidth);
  EXPECT_NEAR(b.leafyWidth - a.leafyWidth, 2.0f, 0.2f);
  EXPECT_FLOAT_EQ(a.crownWidth, b.crownWidth);
  EXPECT_NEAR(a.spread, a.leafyWidth / a.height, 1e-6f);
}

} // namespace
} // namespace sylva::trees
