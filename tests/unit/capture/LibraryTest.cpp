// The committed blade library (data/blades/, made by scripts/make-blade-library.sh) is what the grass field
// instances: every file must load, and its blades must look like grass and leaves.
#include "TempDir.hpp"

#include <sylva/blades/BladeModel.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

namespace sylva::capture {
namespace {

TEST(BladeLibrary, EveryFileLoadsWithPlausibleBlades) {
  const std::filesystem::path dir = test::sourcePath("data/blades");
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") {
      continue;
    }
    names.insert(entry.path().stem().string());
    const blades::BladeModelFile file = blades::loadBladeModels(entry.path());
    ASSERT_FALSE(file.blades.empty()) << entry.path();
    for (const blades::BladeModel& blade : file.blades) {
      SCOPED_TRACE(blade.name);
      ASSERT_EQ(blade.lods.size(), 3u);
      EXPECT_EQ(blade.lods[0].knotCount(), 64u);
      EXPECT_EQ(blade.lods[1].knotCount(), 32u);
      EXPECT_EQ(blade.lods[2].knotCount(), 16u);
      // Real grass blades and leaves: 5 cm to 70 cm long, at most 12 cm wide, longer than wide.
      EXPECT_GE(blade.length(), 0.05f);
      EXPECT_LE(blade.length(), 0.7f);
      EXPECT_GT(blade.maxWidth(), 0.0f);
      EXPECT_LE(blade.maxWidth(), 0.12f);
      EXPECT_GE(blade.length() / blade.maxWidth(), 2.5f);
      for (const blades::BladeLod& lod : blade.lods) {
        EXPECT_EQ(lod.positions.front(), glm::vec3(0.0f));
        // Grass grows upwards from its root (+Y up in blade space); an aloe's lower leaves droop below their
        // root, but not by more than half their length.
        if (entry.path().stem() != "aloe") {
          EXPECT_GT(lod.positions.back().y, 0.0f);
        } else {
          EXPECT_GT(lod.positions.back().y, -0.5f * blade.length());
        }
      }
    }
  }
  for (const char* expected : {"slim", "quadratic", "slender", "bamboo", "sharp", "aloe"}) {
    EXPECT_TRUE(names.count(expected)) << "data/blades/" << expected << ".json is missing";
  }
}

} // namespace
} // namespace sylva::capture
