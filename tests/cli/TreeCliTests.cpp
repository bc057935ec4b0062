// `sylva tree` as a user runs it: generate is deterministic (the same seed gives a byte-identical file), info
// counts what the library counts, species presets print as JSON that generates again, the built-in pieces
// export and check again as artist files, and bad species files, tree files and pieces fail with one line
// naming the file and field, a non-zero exit and no output left behind.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/Measure.hpp>
#include <sylva/trees/Tree.hpp>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace sylva {
namespace {

using test::at;
using test::lineCount;
using test::readAll;
using test::runSylva;
using testing::HasSubstr;

namespace fs = std::filesystem;

TEST(TreeCli, GenerateIsDeterministicPerSeed) {
  const test::TempDir dir;
  const test::RunResult a = runSylva(dir, "tree generate --species almond --seed 42 -o " + at(dir, "a.json"));
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_THAT(a.out, HasSubstr((dir / "a.json").string()));
  EXPECT_THAT(a.out, HasSubstr("almond, seed 42: "));
  const test::RunResult b = runSylva(dir, "tree generate --species almond --seed 42 -o " + at(dir, "b.json"));
  ASSERT_EQ(b.status, 0) << b.err;
  const std::string first = readAll(dir / "a.json");
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first, readAll(dir / "b.json"));
  ASSERT_EQ(runSylva(dir, "tree generate --species almond --seed 43 -o " + at(dir, "c.json")).status, 0);
  EXPECT_NE(first, readAll(dir / "c.json"));
  // The file is what the library generates for the same species and seed.
  const trees::PieceSet pieces = trees::standardPieces();
  const trees::TreeTopology expected = trees::generateTree(pieces, trees::speciesPreset("almond"), 42);
  EXPECT_EQ(loadJsonFile(dir / "a.json"), trees::toJson(expected, pieces));
  // No temporary left beside it.
  std::size_t files = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir.path())) {
    EXPECT_FALSE(entry.path().filename().string().starts_with(".")) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 3u);
}

TEST(TreeCli, InfoPrintsTheCounts) {
  const test::TempDir dir;
  ASSERT_EQ(runSylva(dir, "tree generate --species quaking-aspen --seed 5 -o " + at(dir, "t.json")).status,
            0);
  const trees::PieceSet pieces = trees::standardPieces();
  const trees::TreeTopology tree = trees::loadTree(dir / "t.json", pieces);
  const trees::TreeStats stats = trees::treeStats(pieces, tree);
  const trees::Species species = trees::speciesPreset("quaking-aspen");

  const test::RunResult r = runSylva(dir, "tree info " + at(dir, "t.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr(fmt::format("pieces   {}: I {}, Y {}", stats.pieces, stats.piecesByType[0],
                                           stats.piecesByType[1])));
  EXPECT_THAT(r.out, HasSubstr(fmt::format("joints   {}\n", stats.joints)));
  EXPECT_THAT(r.out, HasSubstr(fmt::format("quads    {} ", stats.quads)));
  EXPECT_THAT(r.out, HasSubstr(fmt::format("depth    {} ", stats.maxDepth)));
  EXPECT_THAT(r.out, HasSubstr(fmt::format("order    {} ", stats.maxOrder)));
  EXPECT_THAT(r.out, HasSubstr(fmt::format("height   {:.2f} m", stats.height * species.trunkRadius)));

  const test::RunResult json = runSylva(dir, "tree info --json " + at(dir, "t.json"));
  ASSERT_EQ(json.status, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["pieces"], stats.pieces);
  EXPECT_EQ(j["joints"], stats.joints);
  EXPECT_EQ(j["quads"], stats.quads);
  EXPECT_EQ(j["piecesByType"]["Foot"], 1);
  EXPECT_NEAR(j["heightMetres"].get<double>(), stats.height * species.trunkRadius, 1e-4);
}

TEST(TreeCli, MeasurePrintsWhatTheLibraryMeasures) {
  const test::TempDir dir;
  const trees::TreeMeasures seven =
      trees::measureSpecies(trees::standardPieces(), trees::speciesPreset("silver-birch"), 7);
  const test::RunResult json = runSylva(dir, "tree measure --species silver-birch --seed 6 --seeds 3 --json");
  ASSERT_EQ(json.status, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  ASSERT_EQ(j.at("trees").size(), 3u);
  EXPECT_EQ(j["trees"][1]["seed"], 7);
  EXPECT_NEAR(j["trees"][1]["height"].get<double>(), seven.height, 1e-5);
  EXPECT_NEAR(j["trees"][1]["crownWidth"].get<double>(), seven.crownWidth, 1e-5);
  EXPECT_EQ(j["trees"][1]["tips"], seven.tips);
  EXPECT_LE(j["min"]["height"].get<double>(), j["max"]["height"].get<double>());
  const test::RunResult text = runSylva(dir, "tree measure --species silver-birch --seed 7");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr(fmt::format("{:.2f} m", seven.height)));
  EXPECT_THAT(text.out, HasSubstr("silhouette width, base to apex"));
  const test::RunResult bad = runSylva(dir, "tree measure --species bonsai");
  EXPECT_NE(bad.status, 0);
  EXPECT_THAT(bad.err, HasSubstr("unknown species 'bonsai'"));
}

TEST(TreeCli, SpeciesPresetPrintsJsonThatGeneratesAgain) {
  const test::TempDir dir;
  const test::RunResult list = runSylva(dir, "tree species");
  ASSERT_EQ(list.status, 0) << list.err;
  for (const std::string& name : trees::speciesPresetNames()) {
    EXPECT_THAT(list.out, HasSubstr(name + " "));
  }
  const test::RunResult show = runSylva(dir, "tree species --show weeping-willow");
  ASSERT_EQ(show.status, 0) << show.err;
  writeTextFile(dir / "willow.json", show.out);
  EXPECT_EQ(trees::toJson(trees::loadSpecies(dir / "willow.json")),
            trees::toJson(trees::speciesPreset("weeping-willow")));
  const test::RunResult a = runSylva(dir, "tree generate --species " + at(dir, "willow.json") +
                                              " --seed 3 -o " + at(dir, "a.json"));
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(runSylva(dir, "tree generate --species weeping-willow --seed 3 -o " + at(dir, "b.json")).status,
            0);
  EXPECT_EQ(readAll(dir / "a.json"), readAll(dir / "b.json"));
  const test::RunResult bad = runSylva(dir, "tree species --show baobab");
  EXPECT_NE(bad.status, 0);
  EXPECT_EQ(lineCount(bad.err), 1u) << bad.err;
  EXPECT_THAT(bad.err, HasSubstr("--show"));
}

TEST(TreeCli, PiecesExportAndImportAgain) {
  const test::TempDir dir;
  const test::RunResult r = runSylva(dir, "tree pieces --export " + at(dir, "pieces"));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const trees::Piece& piece : trees::standardPieces().pieces) {
    EXPECT_THAT(r.out, HasSubstr(fmt::format("{:<8} {:<10} {:<6} {:<9}", piece.name, piece.leafRims(),
                                             piece.quads.size(), piece.vertices.size())));
    for (const char* ext : {".obj", ".gltf"}) {
      const fs::path file = dir / "pieces" / (piece.name + ext);
      ASSERT_TRUE(fs::exists(file)) << file;
      const test::RunResult check = runSylva(dir, "tree import-piece " + test::quote(file.string()));
      ASSERT_EQ(check.status, 0) << check.err;
      EXPECT_THAT(check.out, HasSubstr(fmt::format("piece '{}' is valid", piece.name)));
      EXPECT_THAT(check.out, HasSubstr("root rim    centre (0, 0, 0), axis (0, 1, 0), radius 1,"));
      if (piece.leafRims() > 0) {
        EXPECT_THAT(check.out, HasSubstr(fmt::format("leaf rim {}", piece.leafRims())));
      }
    }
  }
  // Converted on the way: OBJ in, glTF out, which checks again.
  const test::RunResult convert = runSylva(dir, "tree import-piece " + at(dir, "pieces/Psi.obj") +
                                                    " --name Trident -o " + at(dir, "trident.gltf"));
  ASSERT_EQ(convert.status, 0) << convert.err;
  EXPECT_THAT(convert.out, HasSubstr("piece 'Trident' is valid"));
  EXPECT_EQ(runSylva(dir, "tree import-piece " + at(dir, "trident.gltf")).status, 0);
}

TEST(TreeCli, BadInputsFailWithOneLineAndWriteNothing) {
  const test::TempDir dir;
  ASSERT_EQ(runSylva(dir, "tree generate --species almond --seed 9 -o " + at(dir, "good.json")).status, 0);
  const trees::PieceSet pieces = trees::standardPieces();
  const nlohmann::json good = loadJsonFile(dir / "good.json");

  nlohmann::json species = trees::toJson(trees::speciesPreset("almond"));
  species["orders"][0]["fork"] = 0.9;
  species["orders"][0]["sideBranch"] = 0.9;
  writeTextFile(dir / "bad-species.json", species.dump(2));
  species = trees::toJson(trees::speciesPreset("almond"));
  species["maxDepth"] = 65;
  writeTextFile(dir / "deep-species.json", species.dump(2));
  species = trees::toJson(trees::speciesPreset("almond"));
  std::string nanSpecies = species.dump(2);
  const std::string radius = "\"trunkRadius\": ";
  const std::size_t pos = nanSpecies.find(radius) + radius.size();
  nanSpecies.replace(pos, nanSpecies.find(',', pos) - pos, "NaN");
  writeTextFile(dir / "nan-species.json", nanSpecies);

  nlohmann::json tree = good;
  tree["nodes"][1]["piece"] = "Q";
  writeTextFile(dir / "unknown-piece.json", tree.dump(2));
  tree = good;
  tree["nodes"][2]["scale"] = 0.123456;
  std::string nanTree = tree.dump(2);
  nanTree.replace(nanTree.find("0.123456"), 8, "NaN");
  writeTextFile(dir / "nan-tree.json", nanTree);
  nlohmann::json deep{
      {"version", 1}, {"species", "almond"}, {"nodes", nlohmann::json::array({{{"piece", "Foot"}}})}};
  for (int i = 1; i < 70; ++i) {
    deep["nodes"].push_back({{"piece", "I"}, {"parent", i - 1}, {"rim", 1}});
  }
  deep["nodes"].push_back({{"piece", "Cap"}, {"parent", 69}, {"rim", 1}});
  writeTextFile(dir / "deep.json", deep.dump(2));
  writeTextFile(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3\n");
  writeTextFile(dir / "lifted.obj", "v 0 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4\n");

  struct Case {
    std::string args;
    std::vector<std::string> message;
  };
  const std::string out = " -o " + test::at(dir, "out/t.json");
  const std::string piece = " -o " + test::at(dir, "out/p.gltf");
  const std::vector<Case> cases = {
      {"tree generate --species " + test::at(dir, "bad-species.json") + out,
       {"bad-species.json", "/orders/0", "fork + trifurcation + sideBranch must be"}},
      {"tree generate --species " + test::at(dir, "deep-species.json") + out,
       {"deep-species.json", "maxDepth"}},
      {"tree generate --species " + test::at(dir, "nan-species.json") + out,
       {"nan-species.json", "invalid JSON"}},
      {"tree generate --species " + test::at(dir, "none.json") + out, {"none.json"}},
      {"tree generate --species baobab" + out, {"unknown species 'baobab'"}},
      {"tree generate --species almond --seed nan" + out, {"--seed", "nan"}},
      {"tree generate --species almond --seed -1" + out, {"--seed", "-1"}},
      {"tree generate --species almond -o " + test::at(dir, "out/t.txt"), {"out/t.txt", ".json"}},
      {"tree info " + test::at(dir, "unknown-piece.json"),
       {"unknown-piece.json", "/nodes/1/piece", "unknown piece 'Q'"}},
      {"tree info " + test::at(dir, "nan-tree.json"), {"nan-tree.json", "invalid JSON"}},
      {"tree info " + test::at(dir, "deep.json"), {"deep.json", "/nodes/65", "recursion limit 64"}},
      {"tree info " + test::at(dir, "good.json") + " --species " + test::at(dir, "bad-species.json"),
       {"bad-species.json", "/orders/0"}},
      {"tree import-piece " + test::at(dir, "tri.obj") + piece,
       {"tri.obj", "not a quad mesh (face 1 has 3 corners)"}},
      {"tree import-piece " + test::at(dir, "lifted.obj") + piece, {"lifted.obj", "missing root rim"}},
      {"tree import-piece " + test::at(dir, "good.json") + piece, {"good.json", "cannot read the file"}},
      {"tree import-piece " + test::at(dir, "tri.obj") + " -o " + test::at(dir, "out/p.fbx"),
       {"out/p.fbx", ".gltf"}},
      {"tree import-piece " + test::at(dir, "tri.obj") + " --tolerance nan", {"--tolerance", "nan"}},
  };
  for (const Case& c : cases) {
    const test::RunResult r = runSylva(dir, c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(lineCount(r.err), 1u) << c.args << "\n" << r.err;
    EXPECT_TRUE(r.err.starts_with("sylva: error: ")) << r.err;
    for (const std::string& part : c.message) {
      EXPECT_THAT(r.err, HasSubstr(part)) << c.args;
    }
    EXPECT_FALSE(fs::exists(dir / "out")) << c.args;
  }
}

} // namespace
} // namespace sylva
