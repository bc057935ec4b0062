#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/scene/SceneFile.hpp>

#include "ExternalData.hpp"
#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <string>

namespace sylva::scene {
namespace {

namespace fs = std::filesystem;

/** The smallest valid scene: a version and one camera. */
const std::string kMinimal =
    R"({"sylva_scene": 1, "cameras": {"main": {"position": [0, 10, 0], "target": [1, 10, 0]}}})";

/** A minimal scene with `extra` top-level members (text starting with a comma). */
std::string with(const std::string& extra) {
  return R"({"sylva_scene": 1, "cameras": {"main": {"position": [0, 10, 0], "target": [1, 10, 0]}})" + extra +
         "}";
}

/** The message parseScene throws for `json` (fails the test when it does not throw). */
std::string errorOf(const std::string& json, const fs::path& file = "meadow.json") {
  try {
    (void)parseScene(json, file);
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    return message;
  }
  ADD_FAILURE() << "no error for: " << json;
  return {};
}

TEST(SceneFile, EveryExampleSceneLoads) {
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(test::sourcePath("data/scenes"))) {
    if (entry.path().extension() != ".json") {
      continue;
    }
    if (entry.path().filename() == "jacksboro.json" && test::allowMissingData() &&
        !fs::exists(test::externalData("jacksboro_fault_dem.npz"))) {
      continue; // its DEM comes from scripts/fetch-sample-data.sh
    }
    SCOPED_TRACE(entry.path().string());
    const SceneDesc scene = loadScene(entry.path());
    EXPECT_FALSE(scene.name.empty());
    EXPECT_TRUE(scene.cameras.contains(scene.output.camera));
    ++loaded;
  }
  EXPECT_GE(loaded, 2);
}

TEST(SceneFile, MeadowHasEveryPart) {
  const SceneDesc s = loadScene(test::sourcePath("data/scenes/meadow.json"));
  EXPECT_TRUE(s.terrain.dem.empty());
  ASSERT_EQ(s.water.size(), 1u);
  EXPECT_TRUE(fs::path(s.water[0].folding).is_absolute());
  EXPECT_TRUE(fs::exists(s.water[0].folding));
  ASSERT_EQ(s.grass.size(), 1u);
  EXPECT_TRUE(s.grass[0].simulate);
  EXPECT_LE(s.grass[0].distance, 60.0f);
  ASSERT_EQ(s.forests.size(), 2u);
  int trees = 0;
  for (const ForestDesc& f : s.forests) {
    trees += f.count;
  }
  EXPECT_LE(trees, 300); // a frame stays a few seconds on llvmpipe
  EXPECT_FALSE(s.drops.empty());
  ASSERT_TRUE(s.cameras.contains("main"));
  ASSERT_TRUE(s.cameras.contains("flyover"));
  EXPECT_EQ(s.cameras.at("main").keys.size(), 1u);
  EXPECT_NEAR(s.cameras.at("flyover").keys.back().time - s.cameras.at("flyover").keys.front().time, 5.0, 1.0);
  EXPECT_NEAR(s.sun.elevation, 16.0f, 6.0f); // a low late-afternoon sun: long shadows, the flare in view
}

TEST(SceneFile, JacksboroUsesTheRealDem) {
  SYLVA_REQUIRE_EXTERNAL_DATA(test::externalData("jacksboro_fault_dem.npz"));
  const SceneDesc s = loadScene(test::sourcePath("data/scenes/jacksboro.json"));
  EXPECT_EQ(fs::path(s.terrain.dem).filename(), "jacksboro_fault_dem.npz");
  EXPECT_TRUE(fs::exists(s.terrain.dem));
  ASSERT_FALSE(s.forests.empty());
  EXPECT_TRUE(s.forests[0].minHeight.has_value());
  ASSERT_TRUE(s.cameras.contains("ridge"));
  EXPECT_GT(s.cameras.at("ridge").keys.size(), 1u);
}

TEST(SceneFile, DefaultsWhenKeysAreAbsent) {
  const SceneDesc s = parseScene(kMinimal, "dir/minimal.json");
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.path, "dir/minimal.json");
  EXPECT_TRUE(s.terrain.dem.empty());
  EXPECT_EQ(s.terrain.seed, 1u);
  EXPECT_EQ(s.terrain.size, 513);
  EXPECT_EQ(s.terrain.spacing, 2.0f);
  EXPECT_FALSE(s.terrain.spacingSet);
  EXPECT_EQ(s.terrain.relief, 120.0f);
  EXPECT_FALSE(s.terrain.seaLevel.has_value());
  EXPECT_EQ(s.terrain.tessLevel, 16);
  EXPECT_EQ(s.terrain.maxDepth, -1);
  EXPECT_TRUE(s.terrain.geomorph);
  EXPECT_TRUE(s.grass.empty());
  EXPECT_TRUE(s.forests.empty());
  EXPECT_EQ(s.sun.azimuth, 135.0f);
  EXPECT_EQ(s.sun.elevation, 35.0f);
  EXPECT_EQ(s.sun.intensity, 1.1f);
  EXPECT_TRUE(s.sky.enabled);
  EXPECT_EQ(s.sky.turbidity, 3.0f);
  EXPECT_EQ(s.fog.density, 0.0012f);
  EXPECT_EQ(s.wind.seed, 5u);
  EXPECT_EQ(s.shadows.cascades, 3);
  EXPECT_EQ(s.shadows.size, 2048);
  EXPECT_EQ(s.output.camera, "main");
  EXPECT_EQ(s.output.width, 1280);
  EXPECT_EQ(s.output.height, 720);
  EXPECT_EQ(s.output.fps, 24.0);
  EXPECT_EQ(s.output.firstFrame, 0);
  EXPECT_EQ(s.output.lastFrame, 0);
  const CameraDesc& main = s.cameras.at("main");
  ASSERT_EQ(main.keys.size(), 1u);
  EXPECT_EQ(main.keys[0].fov, 50.0f);
  EXPECT_FALSE(main.keys[0].position.aboveGround);
  EXPECT_EQ(main.keys[0].position.p, glm::vec3(0, 10, 0));

  const SceneDesc g =
      parseScene(with(R"(, "grass": [{}], "forests": [{"species": {"oak-ish": 1}}])"), "g.json");
  ASSERT_EQ(g.grass.size(), 1u);
  EXPECT_EQ(g.grass[0].density, 1.0f);
  EXPECT_EQ(g.grass[0].layer, "grass");
  EXPECT_EQ(g.grass[0].maxSlope, 35.0f);
  EXPECT_FALSE(g.grass[0].simulate);
  EXPECT_EQ(g.grass[0].distance, 60.0f);
  EXPECT_FALSE(g.grass[0].extremeBlades);
  EXPECT_TRUE(parseScene(with(R"(, "grass": [{"extreme_blades": true}])"), "g.json").grass[0].extremeBlades);
  ASSERT_EQ(g.forests.size(), 1u);
  EXPECT_EQ(g.forests[0].count, 100);
  EXPECT_EQ(g.forests[0].bark, "auto");
  EXPECT_EQ(g.forests[0].bare, 0.35f);
  EXPECT_FALSE(g.forests[0].regionCentre.has_value());
}

TEST(SceneFile, SunDirectionConvention) {
  SunDesc sun;
  sun.elevation = 0.0f;
  sun.azimuth = 0.0f; // north: −z
  EXPECT_NEAR(sun.direction().z, -1.0f, 1e-6f);
  sun.azimuth = 90.0f; // east: +x
  EXPECT_NEAR(sun.direction().x, 1.0f, 1e-6f);
  sun.azimuth = 180.0f; // south: +z
  EXPECT_NEAR(sun.direction().z, 1.0f, 1e-6f);
  sun.azimuth = 270.0f; // west: −x
  EXPECT_NEAR(sun.direction().x, -1.0f, 1e-6f);
  sun.elevation = 90.0f;
  EXPECT_NEAR(sun.direction().y, 1.0f, 1e-6f);
  sun.azimuth = 135.0f; // south-east, 35° up
  sun.elevation = 35.0f;
  const glm::vec3 d = sun.direction();
  EXPECT_NEAR(d.y, std::sin(glm::radians(35.0f)), 1e-6f);
  EXPECT_GT(d.x, 0.0f);
  EXPECT_GT(d.z, 0.0f);
  EXPECT_NEAR(d.x, d.z, 1e-6f);
  EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
}

TEST(SceneFile, UnknownFieldNamesPathAndSuggestsClosestKey) {
  EXPECT_EQ(errorOf(with(R"(, "forests": [{"species": {"apple": 1}, "cont": 5}])")),
            "meadow.json: /forests/0/cont: unknown field (did you mean 'count'?)");
  EXPECT_EQ(errorOf(with(R"(, "sunn": {})")), "meadow.json: /sunn: unknown field (did you mean 'sun'?)");
  EXPECT_EQ(errorOf(with(R"(, "grass": [{"densty": 2}])")),
            "meadow.json: /grass/0/densty: unknown field (did you mean 'density'?)");
  EXPECT_EQ(errorOf(with(R"(, "banana": 1)")), "meadow.json: /banana: unknown field");
  // A key with a line break still gives a one-line message (errorOf checks), the break escaped.
  EXPECT_EQ(errorOf(with(R"(, "a\nb": 1)")), "meadow.json: /a\\u000ab: unknown field");
  EXPECT_EQ(errorOf(with(R"(, "output": {"camera": "mian"})")),
            "meadow.json: /output/camera: no camera 'mian' in /cameras (did you mean 'main'?)");
}

TEST(SceneFile, WrongTypesNameThePath) {
  EXPECT_EQ(errorOf(with(R"(, "forests": [{"species": {"apple": 1}, "count": "many"}])")),
            "meadow.json: /forests/0/count: expected a number, got string");
  EXPECT_EQ(errorOf(with(R"(, "grass": [{"simulate": 1}])")),
            "meadow.json: /grass/0/simulate: expected true or false, got number");
  EXPECT_EQ(errorOf(with(R"(, "sun": [1, 2])")), "meadow.json: /sun: expected an object, got array");
  EXPECT_EQ(errorOf(with(R"(, "forests": [{"species": {"apple": 1}, "count": 2.5}])")),
            "meadow.json: /forests/0/count: expected a whole number, got 2.5");
  EXPECT_EQ(errorOf(with(R"(, "wind": {"seed": -3})")), "meadow.json: /wind/seed: -3 is less than 0");
  EXPECT_EQ(errorOf(with(R"(, "bodies": [{"position": [1, 2]}])")),
            "meadow.json: /bodies/0/position: expected an array of 3 numbers");
  EXPECT_EQ(errorOf(with(R"(, "bodies": [{"shape": "cone", "position": [1, 2, 3]}])")),
            "meadow.json: /bodies/0/shape: 'cone' is not one of: ball, box");
  EXPECT_EQ(errorOf(with(R"(, "bodies": [{"shape": "box", "radius": 1, "position": [1, 2, 3]}])")),
            "meadow.json: /bodies/0/radius: only for shape 'ball' (a box has 'half_extents')");
  EXPECT_EQ(errorOf(with(R"(, "water": [{"band": 2}])")), "meadow.json: /water/0/level: missing field");
  EXPECT_EQ(
      errorOf(with(R"(, "forests": [{"species": {"Big Oak": 1}}])")),
      "meadow.json: /forests/0/species/Big Oak: 'Big Oak' is not a name (lower-case letters, digits, '-' "
      "and '_')");
}

TEST(SceneFile, AbsurdNumbersAreRefused) {
  EXPECT_EQ(errorOf(with(R"(, "forests": [{"species": {"apple": 1}, "count": 2000000}])")),
            "meadow.json: /forests/0/count: 2000000 is more than 1000000");
  EXPECT_EQ(errorOf(with(R"(, "output": {"width": 100000})")),
            "meadow.json: /output/width: 100000 is more than 16384");
  EXPECT_EQ(errorOf(with(R"(, "output": {"height": -5})")), "meadow.json: /output/height: -5 is less than 1");
  EXPECT_EQ(errorOf(with(R"(, "output": {"last_frame": 5000000})")),
            "meadow.json: /output/last_frame: 5000000 is more than 999999");
  EXPECT_EQ(errorOf(with(R"(, "output": {"first_frame": 10, "last_frame": 5})")),
            "meadow.json: /output/last_frame: 5 is before first_frame 10");
  EXPECT_EQ(errorOf(with(R"(, "grass": [{"density": 1e9}])")),
            "meadow.json: /grass/0/density: 1000000000 is more than 1000");
  EXPECT_EQ(
      errorOf(with(R"(, "drops": [{"centre": [0, 0], "count": 6000}, {"centre": [0, 0], "count": 6000}])")),
      "meadow.json: /drops/1/count: 12000 bodies in all is more than 10000");
  EXPECT_EQ(errorOf(with(R"(, "terrain": {"spacing": 0})")),
            "meadow.json: /terrain/spacing: 0 must be more than 0");
  EXPECT_EQ(errorOf(with(R"(, "terrain": {"size": -513})")),
            "meadow.json: /terrain/size: -513 is less than 17");
  // A number too big for a double is a JSON error, not an infinity that slips through.
  const std::string huge = errorOf(with(R"(, "fog": {"density": 1e999})"));
  EXPECT_EQ(huge.rfind("meadow.json", 0), 0u) << huge;
}

TEST(SceneFile, MissingReferencedFileNamesPathAndFile) {
  test::TempDir dir;
  const fs::path file = dir / "scene.json";
  const std::string message =
      errorOf(with(R"(, "water": [{"level": 3, "folding": "nowhere/shore.json"}])"), file);
  EXPECT_EQ(message,
            file.string() + ": /water/0/folding: file not found: " + (dir / "nowhere/shore.json").string());
  EXPECT_EQ(
      errorOf(with(R"(, "terrain": {"dem": "hills.xyz"})"), file),
      file.string() +
          ": /terrain/dem: 'hills.xyz' is not a .png, .exr, .npy, .npz, .tif, .tiff, .nc, .asc, .hgt file");
  // Relative paths resolve against the scene's directory; a present file is accepted and made absolute.
  writeTextFile(dir / "blades" / "b.json", "{}");
  const SceneDesc ok = parseScene(with(R"(, "grass": [{"blades": ["blades/b.json"]}])"), file);
  ASSERT_EQ(ok.grass[0].blades.size(), 1u);
  EXPECT_EQ(fs::path(ok.grass[0].blades[0]), (dir / "blades" / "b.json").lexically_normal());
  EXPECT_EQ(errorOf(with(R"(, "forests": [{"species": {"trees/elm.json": 1}}])"), file),
            file.string() +
                ": /forests/0/species/trees~1elm.json: file not found: " + (dir / "trees/elm.json").string());
}

TEST(SceneFile, NewerVersionIsRefused) {
  EXPECT_EQ(errorOf(R"({"sylva_scene": 2, "future_field": 1})"),
            "meadow.json: /sylva_scene: version 2 was written by a newer Sylva (this one reads 1)");
  EXPECT_EQ(errorOf(R"({"cameras": {}})"), "meadow.json: /sylva_scene: missing field");
  EXPECT_EQ(errorOf(R"({"sylva_scene": 0})"), "meadow.json: /sylva_scene: 0 is less than 1");
  EXPECT_EQ(errorOf(R"([1, 2])"), "meadow.json: /: expected an object, got array");
}

TEST(SceneFile, MalformedJsonGivesLineAndColumn) {
  const std::string message = errorOf("{\n  \"sylva_scene\": 1,\n  \"cameras\": {,}\n}");
  EXPECT_EQ(message.rfind("meadow.json:3:15: invalid JSON: ", 0), 0u) << message;
  EXPECT_EQ(errorOf(R"({"sylva_scene": 1, "sylva_scene": 1})"), "meadow.json: /sylva_scene: duplicate field");
  EXPECT_EQ(errorOf(with(R"(, "grass": [{}, {"seed": 1, "seed": 2}])")),
            "meadow.json: /grass/1/seed: duplicate field");
}

TEST(SceneFile, CamerasAreValidated) {
  EXPECT_EQ(errorOf(R"({"sylva_scene": 1, "cameras": {}})"),
            "meadow.json: /cameras: expected at least one camera");
  EXPECT_EQ(
      errorOf(R"({"sylva_scene": 1, "cameras": {"main": {"position": [0, 1, 0], "target": [0, 1, 0]}}})"),
      "meadow.json: /cameras/main/target: equals the position (the camera needs a direction)");
  EXPECT_EQ(errorOf(R"({"sylva_scene": 1, "cameras": {"main": {"keys": [
                {"time": 0, "position": [0, 1, 0], "target": [1, 1, 0]},
                {"time": 0, "position": [0, 2, 0], "target": [1, 1, 0]}]}}})"),
            "meadow.json: /cameras/main/keys/1/time: 0 is not after the previous key's 0");
  EXPECT_EQ(errorOf(R"({"sylva_scene": 1, "cameras": {"main": {"keys": [
                {"position": [0, 1, 0], "target": [1, 1, 0]},
                {"time": 1, "position": [0, 2, 0], "target": [1, 1, 0]}]}}})"),
            "meadow.json: /cameras/main/keys/0/time: missing field");
  EXPECT_EQ(
      errorOf(
          R"({"sylva_scene": 1, "cameras": {"main": {"position": [0, 1, 0], "target": [1, 1, 0], "fov": 180}}})"),
      "meadow.json: /cameras/main/fov: 180 is more than 179");
  const SceneDesc s = parseScene(R"({"sylva_scene": 1, "cameras": {"main": {"loop": true, "keys": [
      {"time": 0, "position": {"at": [0, 2, 0], "above_ground": true}, "target": [5, 1, 0]},
      {"time": 2, "position": [4, 2, 0], "target": [5, 1, 0], "fov": 30}]}}})",
                                 "c.json");
  const CameraDesc& c = s.cameras.at("main");
  EXPECT_TRUE(c.loop);
  ASSERT_EQ(c.keys.size(), 2u);
  EXPECT_TRUE(c.keys[0].position.aboveGround);
  EXPECT_FALSE(c.keys[1].position.aboveGround);
  EXPECT_EQ(c.keys[1].fov, 30.0f);
}

} // namespace
} // namespace sylva::scene

namespace sylva::scene {
namespace {

/** The commented example in docs/scenes.md, without its `//` comments, is a valid scene (as if in
 * data/scenes). */
TEST(SceneFile, DocumentedExampleParses) {
  const std::string doc = readTextFile(test::sourcePath("docs/scenes.md"));
  const std::size_t start = doc.find("```jsonc\n");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = doc.find("```", start + 9);
  ASSERT_NE(end, std::string::npos);
  std::string json;
  std::size_t pos = start + 9;
  while (pos < end) {
    std::size_t eol = doc.find('\n', pos);
    std::string line = doc.substr(pos, eol - pos);
    const std::size_t comment = line.find("//");
    if (comment != std::string::npos) {
      line.resize(comment);
    }
    json += line + "\n";
    pos = eol + 1;
  }
  const SceneDesc s = parseScene(json, test::sourcePath("data/scenes/documented.json"));
  EXPECT_EQ(s.name, "Meadow by the lake");
  EXPECT_EQ(s.cameras.size(), 2u);
  EXPECT_EQ(s.forests.at(0).species.size(), 2u);
  EXPECT_TRUE(s.forests.at(0).regionCentre.has_value());
  EXPECT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.output.lastFrame, 119);
  EXPECT_TRUE(s.terrain.seaLevel.has_value());
}

} // namespace
} // namespace sylva::scene
