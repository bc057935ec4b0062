// `sylva scene check`'s engine side: a scene file with one mistake of each kind (a field's typo, a missing
// blade file, a bad count, a missing folding project, an out-of-range sun, a malformed camera, two simulated
// layers, an unknown splat layer, unknown species) gives one line per mistake, none for the good items, and
// the shipped scenes check clean.
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/scene/SceneCheck.hpp>
#include <sylva/scene/SceneFile.hpp>

#include "ExternalData.hpp"
#include "TempDir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace sylva::scene {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(SceneCheck, EveryMistakeIsOneLineAndGoodItemsAreSilent) {
  const test::TempDir dir;
  writeTextFile(dir / "bad.json", R"({"sylva_scene": 1,
    "terrain": {"size": 129, "spacing": 4},
    "grass": [{"densty": 2}, {"blades": ["nope.json"]}, {"layer": "moss", "simulate": true}, {"simulate": true},
              {"density": 0.5}],
    "forests": [{"species": {"banana": 1}}, {"species": {"almond": 1}, "count": -5}, {"species": {"apple": 1}}],
    "water": [{"level": 3, "folding": "missing.json"}],
    "sun": {"elevation": 200},
    "cameras": {"main": {"position": [0, 10, 0], "target": [1, 10, 0]}, "bad": {"position": [0, 1]}}
  })");
  const SceneCheck check = checkScene(dir / "bad.json");
  const std::vector<std::vector<std::string>> expected = {
      {"/grass/0/densty", "did you mean 'density'"},
      {"/grass/1/blades/0", "nope.json"},
      {"/forests/1/count", "-5"},
      {"/water/0/folding", "missing.json"},
      {"/sun/elevation", "200"},
      {"/cameras/bad/position"},
      {"/grass/3/simulate", "only one grass layer"},
      {"/grass/2/layer", "'moss'"},
      {"/forests/0/species/banana", "unknown species"},
  };
  ASSERT_EQ(check.errors.size(), expected.size()) << ::testing::PrintToString(check.errors);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_THAT(check.errors[i], HasSubstr((dir / "bad.json").string() + ": ")) << i;
    for (const std::string& part : expected[i]) {
      EXPECT_THAT(check.errors[i], HasSubstr(part)) << i;
    }
    EXPECT_EQ(check.errors[i].find('\n'), std::string::npos) << check.errors[i];
  }
  EXPECT_EQ(check.grass, 5u);
  EXPECT_EQ(check.forests, 3u);
  EXPECT_EQ(check.terrainWidth, 129);
  // parseScene stops at the first of them, with the same message.
  try {
    (void)loadScene(dir / "bad.json");
    ADD_FAILURE() << "loadScene accepted the file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), check.errors.front());
  }
}

TEST(SceneCheck, WhatStopsReadingIsTheOnlyError) {
  const test::TempDir dir;
  writeTextFile(dir / "syntax.json", "{\"sylva_scene\": 1,, }");
  writeTextFile(dir / "newer.json", R"({"sylva_scene": 99, "banana": 1})");
  for (const char* name : {"syntax.json", "newer.json", "absent.json"}) {
    const SceneCheck check = checkScene(dir / name);
    ASSERT_EQ(check.errors.size(), 1u) << name << ": " << ::testing::PrintToString(check.errors);
    EXPECT_THAT(check.errors[0], HasSubstr(name));
  }
}

TEST(SceneCheck, TheShippedScenesAreValid) {
  for (const char* name : {"meadow.json", "jacksboro.json"}) {
    if (std::string(name) == "jacksboro.json" &&
        !fs::exists(test::sourcePath("data/external/jacksboro_fault_dem.npz")) && test::allowMissingData()) {
      continue; // its DEM is third-party data (scripts/fetch-sample-data.sh)
    }
    const SceneCheck check = checkScene(test::sourcePath(std::string("data/scenes/") + name));
    EXPECT_TRUE(check.errors.empty()) << name << ": " << ::testing::PrintToString(check.errors);
    EXPECT_GT(check.terrainWidth, 0) << name;
  }
}

} // namespace
} // namespace sylva::scene
