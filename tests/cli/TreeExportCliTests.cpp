// `sylva tree export` as a user runs it: .gltf and .glb of two species (one with a bark atlas and an impostor
// atlas made from small generated PNGs) pass the Khronos gltf-validator (tests/support/validate-gltf.mjs,
// installed by scripts/fetch-node-tools.sh) with 0 errors, the validator does catch a broken file, OBJ comes
// with its .mtl and atlas, and bad options fail with one line and no file left behind.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace sylva {
namespace {

using test::at;
using test::quote;
using test::runSylva;
using testing::HasSubstr;

namespace fs = std::filesystem;

/** Runs the validator on `file`; fails the test when node or the validator is missing. */
test::RunResult validate(const test::TempDir& dir, const fs::path& file) {
  EXPECT_FALSE(findOnPath("node").empty())
      << "node not found: install nodejs, then run scripts/fetch-node-tools.sh";
  const fs::path script = fs::path(SYLVA_SOURCE_DIR) / "tests" / "support" / "validate-gltf.mjs";
  return test::runProgram("node", dir.path(), quote(script.string()) + " " + quote(file.string()));
}

void writePattern(const fs::path& path, int size, int views) {
  Image image(size, size, 4, PixelType::U8);
  const int cell = size / views;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const int c = (x / cell + y / cell) % 3;
      image.set(x, y, 0, c == 0 ? 0.8f : 0.3f);
      image.set(x, y, 1, c == 1 ? 0.7f : 0.25f);
      image.set(x, y, 2, static_cast<float>(x % cell) / static_cast<float>(cell));
      image.set(x, y, 3, (x % cell - cell / 2) * (x % cell - cell / 2) < cell * cell / 9 ? 1.0f : 0.0f);
    }
  }
  savePng(path, image);
}

void expectValid(const test::TempDir& dir, const std::string& name) {
  const test::RunResult r = validate(dir, dir / name);
  EXPECT_EQ(r.status, 0) << name << ":\n" << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("numErrors 0 ")) << name << ":\n" << r.out << r.err;
}

TEST(TreeExportCli, HelpNamesTheOptions) {
  const test::TempDir dir;
  const test::RunResult r = runSylva(dir, "tree export --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* option : {"--species", "--seed", "--out", "--levels", "--bark-atlas", "--impostor-atlas",
                             "--impostor-views", "--straight", "validate-gltf.mjs"}) {
    EXPECT_THAT(r.out, HasSubstr(option));
  }
}

TEST(TreeExportCli, AlmondGltfAndGlbPassTheValidator) {
  const test::TempDir dir;
  for (const char* name : {"almond.gltf", "almond.glb"}) {
    const test::RunResult r = runSylva(dir, "tree export --species almond --seed 42 -o " + at(dir, name));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("LOD0 level 8: "));
    EXPECT_THAT(r.out, HasSubstr("LOD2 level 1: "));
    expectValid(dir, name);
  }
  // Binary and text hold the same document.
  const std::string glb = test::readAll(dir / "almond.glb");
  ASSERT_GT(glb.size(), 20u);
  EXPECT_EQ(glb.substr(0, 4), "glTF");
}

TEST(TreeExportCli, AspenWithBarkAndImpostorAtlasesPassesTheValidator) {
  const test::TempDir dir;
  writePattern(dir / "bark.png", 64, 4);
  writePattern(dir / "impostor.png", 128, 8);
  for (const char* name : {"aspen.gltf", "aspen.glb"}) {
    const test::RunResult r =
        runSylva(dir, "tree export --species quaking-aspen --seed 7 --levels 4,2,1 --bark-atlas " +
                          at(dir, "bark.png") + " --impostor-atlas " + at(dir, "impostor.png") +
                          " --impostor-views 8 -o " + at(dir, name));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr("impostor quad"));
    expectValid(dir, name);
  }
  const nlohmann::json gltf = loadJsonFile(dir / "aspen.gltf");
  EXPECT_EQ(gltf.at("images").size(), 2u);
  EXPECT_EQ(gltf.at("meshes").size(), 4u); // three levels and the impostor
  EXPECT_EQ(gltf.at("nodes").at(0).at("extensions").at("MSFT_lod").at("ids").size(), 3u);
}

TEST(TreeExportCli, TheValidatorCatchesABrokenFile) {
  const test::TempDir dir;
  ASSERT_EQ(runSylva(dir, "tree export --species almond --seed 1 --levels 1 -o " + at(dir, "a.gltf")).status,
            0);
  nlohmann::json gltf = loadJsonFile(dir / "a.gltf");
  gltf["accessors"][0]["count"] = gltf["accessors"][0]["count"].get<int>() * 2; // past its buffer view
  gltf["skins"][0]["joints"].push_back(0);                                      // the mesh node as a joint
  saveJsonFile(dir / "broken.gltf", gltf);
  const test::RunResult r = validate(dir, dir / "broken.gltf");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_THAT(r.out, testing::Not(HasSubstr("numErrors 0 ")));
  EXPECT_THAT(r.out, HasSubstr("error "));
}

TEST(TreeExportCli, ObjWritesMaterialAndAtlas) {
  const test::TempDir dir;
  writePattern(dir / "bark.png", 32, 2);
  const test::RunResult r =
      runSylva(dir, "tree export --species weeping-willow --seed 3 --levels 3 --bark-atlas " +
                        at(dir, "bark.png") + " -o " + at(dir, "willow.obj"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(readTextFile(dir / "willow.obj"), HasSubstr("mtllib willow.mtl\n"));
  EXPECT_THAT(readTextFile(dir / "willow.mtl"), HasSubstr("map_Kd willow_bark.png\n"));
  EXPECT_EQ(loadImage(dir / "willow_bark.png"), loadImage(dir / "bark.png"));
}

TEST(TreeExportCli, BadOptionsFailWithOneLineAndNoFile) {
  const test::TempDir dir;
  struct Case {
    std::string args;
    std::string message;
  };
  const Case cases[] = {
      {"--species almond -o " + at(dir, "t.fbx"), "unsupported extension '.fbx'"},
      {"--species almond --levels 8,0 -o " + at(dir, "t.glb"),
       "--levels 8,0: '0' is not a tessellation level"},
      {"--species almond --levels 8,,1 -o " + at(dir, "t.glb"), "is not a tessellation level"},
      {"--species nonesuch -o " + at(dir, "t.glb"), "unknown species 'nonesuch'"},
      {"--species almond --impostor-atlas " + at(dir, "missing.png") + " -o " + at(dir, "t.glb"),
       "missing.png"},
      {"--species almond --impostor-atlas " + at(dir, "missing.png") + " -o " + at(dir, "t.obj"),
       "OBJ has no LOD chain"},
  };
  for (const Case& c : cases) {
    const test::RunResult r = runSylva(dir, "tree export " + c.args);
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_THAT(r.err, HasSubstr(c.message)) << c.args;
    EXPECT_EQ(test::lineCount(r.err), 1u) << r.err;
  }
  std::size_t files = 0;
  for ([[maybe_unused]] const fs::directory_entry& entry : fs::directory_iterator(dir.path())) {
    ++files;
  }
  EXPECT_EQ(files, 0u);
}

} // namespace
} // namespace sylva
