// The terrain setup shared by the command line and scene files: the quadtree layout derived from the heights,
// the sea-level rule, and a large procedural field generated in strips identical to one generate() call.
#include <sylva/terrain/TerrainSetup.hpp>

#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <string>

namespace sylva::terrain {
namespace {

TEST(TerrainSetup, TheDemoLayoutIsFourRootsAcrossAndLeavesOfTwoVerticesPerSample) {
  // The demo: 1025 samples 2 m apart (2048 m) → 512 m roots; level 16 → 16 m leaves → depth 5.
  const HeightField field(1025, 1025, 2.0f, 2.0f, 0.0f);
  const QuadtreeConfig c = quadtreeFor(TerrainSetup{}, field);
  EXPECT_FLOAT_EQ(c.rootSize, 512.0f);
  EXPECT_EQ(c.maxDepth, 5);
  EXPECT_EQ(c.patchTessLevel, 16);
  // A coarser tessellation needs one level more for the same vertex spacing.
  TerrainSetup coarse;
  coarse.quadtree.patchTessLevel = 8;
  EXPECT_EQ(quadtreeFor(coarse, field).maxDepth, 6);
}

TEST(TerrainSetup, RootsAndDepthAreTakenWhenGiven) {
  const HeightField field(257, 129, 1.0f, 1.0f, 0.0f);
  TerrainSetup s;
  s.roots = 8;
  s.maxDepth = 2;
  const QuadtreeConfig c = quadtreeFor(s, field);
  EXPECT_EQ(c.rootsX * c.rootsZ, 8);
  EXPECT_EQ(c.maxDepth, 2);
}

TEST(TerrainSetup, OutOfRangeValuesNameTheirField) {
  const HeightField field(65, 65, 1.0f, 1.0f, 0.0f);
  const TerrainFieldName option = [](std::string_view f) { return "--" + std::string(f); };
  TerrainSetup s;
  s.quadtree.patchTessLevel = kMaxPatchTessLevel + 1;
  EXPECT_NE(test::errorOf([&] { (void)quadtreeFor(s, field, option); }).find("--tess_level"),
            std::string::npos);
  s = TerrainSetup{};
  s.quadtree.lodDistanceFactor = 1.0f;
  EXPECT_NE(test::errorOf([&] { (void)quadtreeFor(s, field, option); }).find("--lod_factor"),
            std::string::npos);
  s = TerrainSetup{};
  s.maxDepth = 17;
  EXPECT_NE(test::errorOf([&] { (void)quadtreeFor(s, field, option); }).find("--max_depth"),
            std::string::npos);
}

TEST(TerrainSetup, SeaLevelRules) {
  SeaLevelRule rule;
  EXPECT_EQ(rule.resolve(-3.0f), std::optional<float>(0.0f)); // auto: bathymetry has a sea at 0 m
  EXPECT_FALSE(rule.resolve(3.0f).has_value());
  rule.kind = SeaLevelRule::Kind::None;
  EXPECT_FALSE(rule.resolve(-3.0f).has_value());
  rule.kind = SeaLevelRule::Kind::Metres;
  rule.metres = 7.5f;
  EXPECT_EQ(rule.resolve(100.0f), std::optional<float>(7.5f));
}

TEST(TerrainSetup, ALargeProceduralFieldIsGeneratedInIdenticalStrips) {
  TerrainSource source;
  source.proceduralSize = 1100; // > kProgressSamples samples: generated in strips
  source.proceduralSpacing = 2.0f;
  ASSERT_GT(static_cast<std::size_t>(source.proceduralSize) * source.proceduralSize, kProgressSamples);
  const HeightField strips = loadTerrainSource(source);
  const HeightField whole = generate(source.procedural, 0.0, 0.0, 1100, 1100, 2.0f);
  ASSERT_EQ(strips.samples().size(), whole.samples().size());
  EXPECT_TRUE(std::equal(strips.samples().begin(), strips.samples().end(), whole.samples().begin()));
}

TEST(TerrainSetup, ARectangularProceduralFieldHasItsRowsAlongZ) {
  TerrainSource source;
  source.proceduralSize = 9;
  source.proceduralRows = 33;
  source.proceduralSpacing = 1.0f;
  const HeightField field = loadTerrainSource(source);
  EXPECT_EQ(field.width(), 9);
  EXPECT_EQ(field.height(), 33);
  const HeightField whole = generate(source.procedural, 0.0, 0.0, 9, 33, 1.0f);
  EXPECT_TRUE(std::equal(field.samples().begin(), field.samples().end(), whole.samples().begin()));
  // Tall and narrow past kProgressSamples: generated in strips of whole rows, identical to one call.
  source.proceduralSize = 64;
  source.proceduralRows = 17000;
  ASSERT_GT(static_cast<std::size_t>(source.proceduralSize) * source.rows(), kProgressSamples);
  const HeightField strips = loadTerrainSource(source);
  const HeightField one = generate(source.procedural, 0.0, 0.0, 64, 17000, 1.0f);
  ASSERT_EQ(strips.height(), 17000);
  EXPECT_TRUE(std::equal(strips.samples().begin(), strips.samples().end(), one.samples().begin()));
}

} // namespace
} // namespace sylva::terrain
