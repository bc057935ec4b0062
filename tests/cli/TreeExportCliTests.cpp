// `sylva tree export` as a user runs it: .gltf and .glb of two species (one with a bark atlas and an impostor
// atlas made from small generated PNGs) pass the Khronos gltf-validator (tests/support/validate-gltf.mjs,
// installed by scripts/fetch-node-tools.sh) with 0 errors, the validator does catch a broken file, OBJ comes
// with its .mtl and atlas, and bad options fail with one line and no file left behind. TreeExportImpostorCli
// bakes the tree's own impostor atlas (--impostor) on a headless GL context: those tests run from the
// gl-label executable sylva_cli_tree_export_gl (tests/cli/CMakeLists.txt), the unit executable leaves them
// out.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>

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

/** The JSON chunk and the binary chunk of a .glb file. */
struct Glb {
  nlohmann::json json;
  std::string bin;
};

Glb readGlb(const fs::path& path) {
  const std::string bytes = test::readAll(path);
  Glb glb;
  auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    if (at + 4 <= bytes.size()) {
      std::memcpy(&v, bytes.data() + at, 4);
    }
    return static_cast<std::size_t>(v);
  };
  if (bytes.size() < 20 || bytes.substr(0, 4) != "glTF" || 20 + u32(12) > bytes.size()) {
    ADD_FAILURE() << path << " is not a GLB file";
    return glb;
  }
  const std::size_t json = u32(12);
  glb.json = nlohmann::json::parse(bytes.substr(20, json));
  const std::size_t bin = 20 + json;
  if (bin + 8 <= bytes.size()) {
    glb.bin = bytes.substr(bin + 8, u32(bin));
  }
  return glb;
}

TEST(TreeExportCli, HelpNamesTheOptions) {
  const test::TempDir dir;
  const test::RunResult r = runSylva(dir, "tree export --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* option :
       {"--species", "--seed", "--out", "--levels", "--bark-atlas", "--impostor-atlas", "--impostor-views",
        "--impostor-cell", "--impostor-png", "--no-impostor-foliage", "--straight", "validate-gltf.mjs"}) {
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
      // --impostor bakes the atlas: checked before any GL work or output.
      {"--species almond --impostor --impostor-atlas " + at(dir, "missing.png") + " -o " + at(dir, "t.glb"),
       "--impostor: bakes the impostor atlas; it cannot be combined with --impostor-atlas"},
      {"--species almond --impostor -o " + at(dir, "t.obj"), "--impostor: OBJ has no LOD chain"},
      {"--species almond --impostor-png " + at(dir, "a.png") + " -o " + at(dir, "t.glb"), "needs --impostor"},
      {"--species almond --impostor --impostor-png " + at(dir, "a.jpg") + " -o " + at(dir, "t.glb"),
       "must end in .png"},
      {"--species almond --impostor --impostor-layout grid -o " + at(dir, "t.glb"),
       "--impostor bakes hemi-octahedral"},
      {"--species almond --impostor --impostor-views 1 -o " + at(dir, "t.glb"), "2-64 views"},
      {"--species almond --impostor --impostor-views 64 --impostor-cell 256 -o " + at(dir, "t.glb"),
       "at most 8192"},
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

/** Fraction of the texels of cell (i, j) (j from the top row) of `atlas` with alpha > 0. */
double cellCoverage(const Image& atlas, int views, int i, int j) {
  const int cell = atlas.width() / views;
  int covered = 0;
  for (int y = j * cell; y < (j + 1) * cell; ++y) {
    for (int x = i * cell; x < (i + 1) * cell; ++x) {
      covered += atlas.get(x, y, 3) > 0.0f ? 1 : 0;
    }
  }
  return static_cast<double>(covered) / static_cast<double>(cell * cell);
}

/** True (the test goes on) when the export ran or failed for another reason than a missing GL context. */
bool haveGl(const test::RunResult& r) {
  if (r.status == 0 || r.err.find("EGL") == std::string::npos) {
    return true;
  }
  const char* require = std::getenv("SYLVA_REQUIRE_GL");
  return require != nullptr && std::string(require) == "1";
}

// One command bakes the exported tree's atlas (small: 4 x 4 views of 32 px, for llvmpipe) and embeds it: the
// validator passes the .glb, the impostor node names the hemi-octahedral layout, 4 views and the sphere its
// quad spans, the embedded atlas is the PNG written beside it, and every view shows the tree inside its cell.
TEST(TreeExportImpostorCli, BakedAtlasIsEmbeddedAndPassesTheValidator) {
  const test::TempDir dir;
  const test::RunResult r =
      runSylva(dir, "tree export --species almond --seed 42 --impostor --impostor-views 4 --impostor-cell 32 "
                    "--impostor-png " +
                        at(dir, "atlas.png") + " -o " + at(dir, "almond.glb"));
  if (!haveGl(r)) {
    GTEST_SKIP() << "no headless GL context: " << r.err;
  }
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("impostor quad"));
  EXPECT_THAT(r.out, HasSubstr("atlas.png"));
  EXPECT_THAT(r.out, HasSubstr("impostor: baked 4 x 4 hemi-octahedral views of 32 px (128x128 px atlas"));
  expectValid(dir, "almond.glb");

  const Image atlas = loadImage(dir / "atlas.png");
  ASSERT_EQ(atlas.width(), 4 * 32);
  ASSERT_EQ(atlas.height(), 4 * 32);
  ASSERT_EQ(atlas.channels(), 4);
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const double coverage = cellCoverage(atlas, 4, i, j);
      EXPECT_GT(coverage, 0.02) << "view (" << i << ", " << j << ") shows no tree";
      EXPECT_LT(coverage, 0.95) << "view (" << i << ", " << j << ") is covered edge to edge";
      // The views frame the tree's bounding sphere with a margin: the cell's corners are empty.
      for (const auto& [x, y] : {std::pair{0, 0}, std::pair{31, 0}, std::pair{0, 31}, std::pair{31, 31}}) {
        EXPECT_EQ(atlas.get(i * 32 + x, j * 32 + y, 3), 0.0f) << "cell (" << i << ", " << j << ")";
      }
    }
  }

  const Glb glb = readGlb(dir / "almond.glb");
  const nlohmann::json& gltf = glb.json;
  const nlohmann::json* node = nullptr;
  for (const nlohmann::json& n : gltf.at("nodes")) {
    if (n.contains("extras") && n.at("extras").contains("impostor")) {
      node = &n;
    }
  }
  ASSERT_NE(node, nullptr) << "no impostor node";
  const nlohmann::json& impostor = node->at("extras").at("impostor");
  EXPECT_EQ(impostor.at("layout"), "hemi-octahedral");
  EXPECT_EQ(impostor.at("viewsPerSide"), 4);
  EXPECT_EQ(impostor.at("atlasSizePx"), nlohmann::json::array({128, 128}));
  const nlohmann::json& sphere = impostor.at("sphereM");
  ASSERT_EQ(sphere.size(), 4u);
  const double radius = sphere.at(3).get<double>();
  const nlohmann::json& bounds = impostor.at("boundsMaxM");
  EXPECT_GT(radius, 0.5 * bounds.at(1).get<double>()) << "the sphere holds the tree";
  // The quad is the sphere's square: it shows the view at the tree's size.
  const nlohmann::json& mesh = gltf.at("meshes").at(node->at("mesh").get<std::size_t>());
  const nlohmann::json& primitive = mesh.at("primitives").at(0);
  const nlohmann::json& position =
      gltf.at("accessors").at(primitive.at("attributes").at("POSITION").get<std::size_t>());
  EXPECT_NEAR(position.at("max").at(0).get<double>() - position.at("min").at(0).get<double>(), 2.0 * radius,
              1e-4);
  EXPECT_NEAR(position.at("max").at(1).get<double>() - position.at("min").at(1).get<double>(), 2.0 * radius,
              1e-4);
  // The impostor material's texture is the atlas written as --impostor-png.
  const nlohmann::json& material = gltf.at("materials").at(primitive.at("material").get<std::size_t>());
  const std::size_t texture =
      material.at("pbrMetallicRoughness").at("baseColorTexture").at("index").get<std::size_t>();
  const nlohmann::json& image =
      gltf.at("images").at(gltf.at("textures").at(texture).at("source").get<std::size_t>());
  EXPECT_EQ(image.at("mimeType"), "image/png");
  const nlohmann::json& view = gltf.at("bufferViews").at(image.at("bufferView").get<std::size_t>());
  const std::size_t offset = view.value("byteOffset", std::size_t{0});
  const std::size_t length = view.at("byteLength").get<std::size_t>();
  ASSERT_LE(offset + length, glb.bin.size());
  writeTextFile(dir / "embedded.png", glb.bin.substr(offset, length));
  EXPECT_EQ(loadImage(dir / "embedded.png"), atlas) << "the embedded atlas differs from --impostor-png";
}

// The foliage is drawn into the bake by default: without it (--no-impostor-foliage) the views cover less, and
// the export still passes the validator.
TEST(TreeExportImpostorCli, FoliageIsBakedUnlessTurnedOff) {
  const test::TempDir dir;
  auto bake = [&](const std::string& flags, const std::string& name) {
    return runSylva(dir, "tree export --species almond --seed 42 --levels 2,1 --impostor --impostor-views 4 "
                         "--impostor-cell 32 " +
                             flags + " --impostor-png " + at(dir, name + ".png") + " -o " +
                             at(dir, name + ".gltf"));
  };
  const test::RunResult leaves = bake("", "leaves");
  if (!haveGl(leaves)) {
    GTEST_SKIP() << "no headless GL context: " << leaves.err;
  }
  ASSERT_EQ(leaves.status, 0) << leaves.err;
  const test::RunResult bare = bake("--no-impostor-foliage --bark none", "bare");
  ASSERT_EQ(bare.status, 0) << bare.err;
  expectValid(dir, "bare.gltf");
  const Image a = loadImage(dir / "leaves.png");
  const Image b = loadImage(dir / "bare.png");
  double withLeaves = 0.0;
  double without = 0.0;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      withLeaves += cellCoverage(a, 4, i, j) / 16.0;
      without += cellCoverage(b, 4, i, j) / 16.0;
    }
  }
  std::printf("atlas coverage: %.3f with foliage, %.3f without\n", withLeaves, without);
  EXPECT_GT(without, 0.0) << "the bare tree's branches";
  EXPECT_GT(withLeaves, without * 1.2) << "the foliage adds coverage";
}

} // namespace
} // namespace sylva
