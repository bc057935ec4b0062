// The grass field's CPU side: blade types, the patch, tiles and density over the terrain, and the blade
// expansion that the vertex shader will mirror.
#include <sylva/core/Error.hpp>
#include <sylva/grass/BladeType.hpp>
#include <sylva/grass/Expand.hpp>
#include <sylva/grass/Field.hpp>
#include <sylva/grass/Patch.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/Noise.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <set>

namespace sylva::grass {
namespace {

float lineLength(const std::vector<glm::vec3>& line) {
  float length = 0.0f;
  for (std::size_t i = 1; i < line.size(); ++i) {
    length += glm::length(line[i] - line[i - 1]);
  }
  return length;
}

terrain::HeightField hills() {
  terrain::ProceduralSpec spec = terrain::defaultLandscapeSpec(5);
  spec.heightScale = 12.0f;
  return terrain::generate(spec, 0.0, 0.0, 65, 49, 1.0f);
}

TEST(BladeTypes, ProceduralTypesHaveThreeLevels) {
  const std::vector<BladeType> types = proceduralBladeTypes();
  ASSERT_EQ(types.size(), 3u);
  for (const BladeType& t : types) {
    for (std::size_t l = 0; l < kLodKnots.size(); ++l) {
      ASSERT_EQ(t.lods[l].knots.size(), static_cast<std::size_t>(kLodKnots[l])) << t.name;
      ASSERT_EQ(t.lods[l].widths.size(), t.lods[l].knots.size());
      EXPECT_EQ(t.lods[l].knots.front(), glm::vec3(0.0f));
      EXPECT_GT(t.lods[l].knots.back().y, 0.5f * t.length()) << t.name;
      // Coarser levels keep the ends and lose a little length on the curve, never gain.
      EXPECT_LE(lineLength(t.lods[l].knots), t.length() + 1e-6f);
      EXPECT_GT(lineLength(t.lods[l].knots), 0.95f * t.length());
    }
  }
  EXPECT_NEAR(types[0].length(), 0.35f, 0.01f);
}

TEST(BladeTypes, FromTheCapturedLibrary) {
  const std::vector<BladeType> types = loadBladeTypes(test::sourcePath("data/blades/slim.json"));
  ASSERT_FALSE(types.empty());
  const blades::BladeModelFile file = blades::loadBladeModels(test::sourcePath("data/blades/slim.json"));
  ASSERT_EQ(types.size(), file.blades.size());
  for (std::size_t i = 0; i < types.size(); ++i) {
    EXPECT_EQ(types[i].lods[0].knots.front(), file.blades[i].lods[0].positions.front());
    EXPECT_EQ(types[i].lods[0].knots.back(), file.blades[i].lods[0].positions.back());
    EXPECT_NEAR(types[i].length(), file.blades[i].length(), 0.02f * file.blades[i].length());
    EXPECT_EQ(types[i].colour, file.blades[i].colour);
  }
  EXPECT_THROW(loadBladeTypes("no-such-blades.json"), Error);
}

TEST(BladeTypes, EveryBladeOfTheLibraryIsAPlausibleSize) {
  for (const char* name : {"aloe", "bamboo", "quadratic", "sharp", "slender", "slim"}) {
    const std::filesystem::path path = test::sourcePath(std::string("data/blades/") + name + ".json");
    EXPECT_NO_THROW(loadBladeTypes(path)) << name;
  }
}

// The class of mistakes: a model in the wrong unit (millimetres read as metres: a 350 m blade), widths that
// all came out 0 (a field that draws nothing), a blade with no length. Each fails naming the file, the blade
// and the way to allow it; the deliberate extreme loads with `extreme`.
TEST(BladeTypes, ImplausibleSizesFailNamingTheFileAndTheBlade) {
  const test::TempDir dir;
  const blades::BladeModelFile slim = blades::loadBladeModels(test::sourcePath("data/blades/slim.json"));
  ASSERT_GE(slim.blades.size(), 2u);
  struct Case {
    const char* name;
    float positionScale;
    float widthScale;
    const char* message;
  };
  for (const Case& c :
       {Case{"millimetres", 1000.0f, 1000.0f, "m long"}, Case{"invisible", 1.0f, 0.0f, "draw nothing"},
        Case{"sprout", 1e-3f, 1e-3f, "m long"}, Case{"point", 0.0f, 1.0f, "m long"}}) {
    blades::BladeModelFile file = slim;
    for (blades::BladeLod& lod : file.blades[1].lods) {
      for (glm::vec3& p : lod.positions) {
        p *= c.positionScale;
      }
      for (float& w : lod.widths) {
        w *= c.widthScale;
      }
    }
    const std::filesystem::path path = dir.path() / (std::string(c.name) + ".json");
    blades::saveBladeModels(path, file);
    try {
      loadBladeTypes(path);
      ADD_FAILURE() << c.name << " loaded";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path.string() + ": /blades/1: blade model '" + file.blades[1].name + "'"),
                std::string::npos)
          << message;
      EXPECT_NE(message.find(c.message), std::string::npos) << message;
      EXPECT_NE(message.find("--grass-extreme-blades"), std::string::npos) << message;
    }
    if (c.positionScale > 0.0f && c.widthScale > 0.0f) {
      EXPECT_EQ(loadBladeTypes(path, BladeType{}.colour, BladeType{}.stiffness, true).size(),
                file.blades.size())
          << c.name;
    }
  }
}

TEST(Patch, DeterministicEvenAndShuffled) {
  PatchSettings s;
  s.blades = 4096;
  s.tileSize = 2.0f;
  s.typeWeights = {3.0f, 1.0f};
  const std::vector<gpu::GrassBlade> a = makePatch(s, 2);
  const std::vector<gpu::GrassBlade> b = makePatch(s, 2);
  ASSERT_EQ(a.size(), 4096u);
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(gpu::GrassBlade)));
  int type0 = 0;
  for (const gpu::GrassBlade& g : a) {
    EXPECT_GE(g.placement.x, 0.0f);
    EXPECT_LT(g.placement.x, 2.0f);
    EXPECT_GE(g.placement.y, 0.0f);
    EXPECT_LT(g.placement.y, 2.0f);
    EXPECT_GE(g.placement.w, s.minScale);
    EXPECT_LE(g.placement.w, s.maxScale);
    type0 += g.info.x == 0 ? 1 : 0;
  }
  // Weights 3:1 → 75 % ± 3σ (σ ≈ 0.68 %).
  EXPECT_NEAR(type0 / 4096.0, 0.75, 0.021);
  // Any contiguous range covers the tile evenly: quadrant counts of the first 400 blades.
  int quadrant[4] = {0, 0, 0, 0};
  for (int i = 0; i < 400; ++i) {
    quadrant[(a[i].placement.x >= 1.0f ? 1 : 0) + (a[i].placement.y >= 1.0f ? 2 : 0)]++;
  }
  for (int q : quadrant) {
    EXPECT_NEAR(q, 100, 30);
  }
  s.seed = 2;
  EXPECT_NE(0, std::memcmp(a.data(), makePatch(s, 2).data(), a.size() * sizeof(gpu::GrassBlade)));
}

TEST(Patch, RejectsBadSettings) {
  PatchSettings s;
  s.blades = 0;
  EXPECT_THROW(makePatch(s, 1), Error);
  s = {};
  s.tileSize = std::nanf("");
  EXPECT_THROW(makePatch(s, 1), Error);
  s = {};
  s.typeWeights = {1.0f};
  EXPECT_THROW(makePatch(s, 2), Error);
  s.typeWeights = {0.0f, 0.0f};
  EXPECT_THROW(makePatch(s, 2), Error);
}

TEST(Patch, MemoryAgainstThePaper) {
  // The paper: 24 MB for a 16,384-blade patch, ~4 GB for 4 M stored blades.
  const std::size_t patch = patchBytes(16384, 3);
  EXPECT_LT(patch, 1u << 20);
  EXPECT_GT(perBladeFieldBytes(4u << 20), 1000u * patch);
}

TEST(Field, TilesDrawRangesThatStartFromTheirPosition) {
  std::set<std::uint32_t> starts;
  for (int tz = 0; tz < 16; ++tz) {
    for (int tx = 0; tx < 16; ++tx) {
      const std::uint32_t s = tileStart(tx, tz, 16384);
      EXPECT_LT(s, 16384u);
      EXPECT_EQ(s, tileStart(tx, tz, 16384));
      starts.insert(s);
    }
  }
  EXPECT_GT(starts.size(), 240u);
}

TEST(Field, RootsSitOnTheTerrainAndFollowTheDensity) {
  const terrain::HeightField field = hills();
  PatchSettings ps;
  ps.blades = 2048;
  const std::vector<gpu::GrassBlade> patch = makePatch(ps, 3);
  const FieldLayout layout = layoutOver(field, ps.tileSize, 256);
  EXPECT_EQ(layout.tilesX, 32);
  EXPECT_EQ(layout.tilesZ, 24);
  DensitySettings full;
  full.coverage = 1.0f;
  full.contrast = 100.0f;
  full.maxSlopeDegrees = 90.0f;
  const DensityGrid everywhere(DensityMap(full), field);
  std::size_t interior = 0;
  forEachTileBlade(layout, patch, field, everywhere, 5, 7, [&](const FieldBlade& b) {
    // The tessellation shader's float bilinear height: within 1 mm of the double-precision query.
    EXPECT_NEAR(b.root.y, terrain::heightAt(field, b.root.x, b.root.z), 1e-3f);
    EXPECT_GE(b.root.x, 5 * 2.0f);
    EXPECT_LT(b.root.x, 6 * 2.0f);
    EXPECT_GE(b.root.z, 7 * 2.0f);
    EXPECT_LT(b.root.z, 8 * 2.0f);
    ++interior;
  });
  EXPECT_EQ(interior, 256u);
  DensitySettings none = full;
  none.maxHeight = -100.0f;
  none.minHeight = -200.0f;
  EXPECT_EQ(countFieldBlades(layout, patch, field, DensityGrid(DensityMap(none), field)), 0u);
  const std::size_t all = countFieldBlades(layout, patch, field, everywhere);
  const DensityGrid patchy(DensityMap(DensitySettings{}), field);
  const std::size_t some = countFieldBlades(layout, patch, field, patchy);
  EXPECT_GT(some, all / 5);
  EXPECT_LT(some, all);
  EXPECT_EQ(some, countFieldBlades(layout, patch, field, DensityGrid(DensityMap(DensitySettings{}), field)));
  // The grid reproduces the rules at its samples and interpolates between them.
  const DensityMap rules{DensitySettings{}};
  for (int i = 0; i < 20; ++i) {
    const float x = static_cast<float>(i) * patchy.spacing().x;
    const float z = static_cast<float>(i % 7) * patchy.spacing().y;
    const glm::vec3 n = terrain::normalAt(field, x, z);
    EXPECT_NEAR(patchy.at(x, z), rules.at(x, z, terrain::heightAt(field, x, z), std::acos(n.y) * 57.29578f),
                1e-5f);
  }
  // Absent terrain: no root there.
  terrain::HeightField holed = field;
  for (int j = 0; j < field.height(); ++j) {
    for (int i = 0; i < 20; ++i) {
      holed.at(i, j) = std::nanf("");
    }
  }
  EXPECT_TRUE(std::isnan(rootHeight(holed, 5.0f, 5.0f)));
  EXPECT_FALSE(std::isnan(rootHeight(holed, 40.0f, 5.0f)));
  const std::size_t fewer = countFieldBlades(layout, patch, holed, DensityGrid(DensityMap(full), holed));
  EXPECT_LT(fewer, all * 3 / 4);
  EXPECT_GT(fewer, all / 2);
}

TEST(Field, DensityRules) {
  DensitySettings s;
  s.maxSlopeDegrees = 30.0f;
  s.slopeFade = 5.0f;
  s.coverage = 1.0f;
  s.contrast = 100.0f;
  const DensityMap map(s);
  EXPECT_EQ(map.at(3.0f, 4.0f, 0.0f, 31.0f), 0.0f);
  EXPECT_EQ(map.at(3.0f, 4.0f, 0.0f, 10.0f), 1.0f);
  EXPECT_EQ(map.at(3.0f, 4.0f, std::nanf(""), 10.0f), 0.0f);
  // A paint mask with a black left half.
  auto paint = std::make_shared<Image>(8, 8, 1, PixelType::U8);
  for (int y = 0; y < 8; ++y) {
    for (int x = 4; x < 8; ++x) {
      paint->set(x, y, 0, 1.0f);
    }
  }
  s.paint = paint;
  s.paintMin = {0.0f, 0.0f};
  s.paintMax = {8.0f, 8.0f};
  const DensityMap painted(s);
  EXPECT_EQ(painted.at(1.0f, 4.0f, 0.0f, 0.0f), 0.0f);
  EXPECT_EQ(painted.at(7.0f, 4.0f, 0.0f, 0.0f), 1.0f);
  EXPECT_EQ(painted.at(20.0f, 4.0f, 0.0f, 0.0f), 1.0f);
  // The terrain's grass splat layer as a rule, in true metres under a vertical exaggeration of 2.
  DensitySettings layered;
  layered.coverage = 1.0f;
  layered.contrast = 100.0f;
  layered.maxSlopeDegrees = 90.0f;
  terrain::SplatLayer grassLayer;
  grassLayer.name = "grass";
  grassLayer.minHeight = 0.0f;
  grassLayer.maxHeight = 50.0f;
  grassLayer.maxSlope = 30.0f;
  layered.layer = grassLayer;
  layered.verticalScale = 2.0f;
  const DensityMap onLayer(layered);
  EXPECT_EQ(onLayer.at(3.0f, 4.0f, 80.0f, 10.0f), 1.0f);  // 40 m true
  EXPECT_EQ(onLayer.at(3.0f, 4.0f, 120.0f, 10.0f), 0.0f); // 60 m true
  EXPECT_EQ(onLayer.at(3.0f, 4.0f, 80.0f, 45.0f), 1.0f);  // atan(tan 45° / 2) = 26.6° true
  EXPECT_EQ(onLayer.at(3.0f, 4.0f, 80.0f, 60.0f), 0.0f);  // 40.9° true
  DensitySettings bad;
  bad.coverage = std::nanf("");
  EXPECT_THROW(DensityMap{bad}, Error);
  // The Perlin map makes patches: both bare and covered ground over a 200 m square.
  const DensityMap patches{DensitySettings{}};
  int bare = 0;
  int covered = 0;
  int overHalf = 0;
  for (int i = 0; i < 400; ++i) {
    const float v = patches.noise(static_cast<float>(i % 20) * 10.0f, static_cast<float>(i / 20) * 10.0f);
    bare += v < 0.05f ? 1 : 0;
    covered += v > 0.95f ? 1 : 0;
    overHalf += v > 0.5f ? 1 : 0;
  }
  EXPECT_GT(bare, 10);
  EXPECT_GT(covered, 100);
  // `coverage` (0.7 by default) is about the fraction of ground with density over one half.
  EXPECT_NEAR(overHalf / 400.0, 0.7, 0.15);
}

TEST(Expand, StripFollowsTheKnotsWidthsAndWind) {
  const BladeType type = proceduralBladeTypes()[0];
  gpu::GrassBlade blade{};
  blade.placement = {0.0f, 0.0f, 0.6f, 1.2f};
  const glm::vec3 root(3.0f, 1.5f, -2.0f);
  const std::vector<BladeVertex> calm = expandBlade(type, 0, blade, root, {0.0f, 0.0f});
  ASSERT_EQ(calm.size(), 32u);
  std::vector<glm::vec3> centre;
  for (std::size_t k = 0; k < 16; ++k) {
    const BladeVertex& l = calm[2 * k];
    const BladeVertex& r = calm[2 * k + 1];
    centre.push_back(0.5f * (l.position + r.position));
    EXPECT_NEAR(glm::length(l.position - r.position), type.lods[0].widths[k] * 1.2f, 1e-5f);
    EXPECT_NEAR(glm::length(l.normal), 1.0f, 1e-5f);
    EXPECT_EQ(l.side, -1.0f);
    EXPECT_EQ(r.side, 1.0f);
  }
  EXPECT_LT(glm::length(centre.front() - root), 1e-6f);
  EXPECT_NEAR(lineLength(centre), lineLength(type.lods[0].knots) * 1.2f, 1e-4f);
  EXPECT_FLOAT_EQ(calm.back().along, 1.0f);
  // Wind along +x bends the tip downwind, keeps the length and lowers the tip.
  const std::vector<BladeVertex> windy = expandBlade(type, 0, blade, root, {8.0f, 0.0f});
  std::vector<glm::vec3> bent;
  for (std::size_t k = 0; k < 16; ++k) {
    bent.push_back(0.5f * (windy[2 * k].position + windy[2 * k + 1].position));
  }
  EXPECT_NEAR(lineLength(bent), lineLength(centre), 1e-4f);
  EXPECT_GT(bent.back().x - root.x, centre.back().x - root.x + 0.05f);
  EXPECT_LT(bent.back().y, centre.back().y);
  EXPECT_NEAR(bendAngle(100.0f, 0.1f), 1.3f, 1e-6f);
  EXPECT_THROW(expandBlade(type, 3, blade, root, {}), Error);
}

} // namespace
} // namespace sylva::grass
