// Runs the built `sylva` binary as a user would: exit codes, stdout/stderr, and the files it writes.
#include "CliRun.hpp"
#include "TempDir.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/TerrainMaps.hpp>

#include <gtest/gtest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>

namespace sylva {
namespace {

using test::lineCount;
using test::runSylva;

namespace fs = std::filesystem;

using test::quote;
using test::readAll;
using test::RunResult;

/** Runs `sylva <args>` (args already shell-quoted where needed) with stdout and stderr captured. */
std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    result.push_back(line);
  }
  return result;
}

/** Regular files anywhere under `root` (none if it does not exist). */
std::vector<fs::path> filesUnder(const fs::path& root) {
  std::vector<fs::path> files;
  if (!fs::exists(root)) {
    return files;
  }
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (entry.is_regular_file()) {
      files.push_back(entry.path());
    }
  }
  return files;
}

/** The spec `sylva terrain` uses for --seed/--type/--height-scale: the default landscape's other fields. */
terrain::ProceduralSpec specFor(std::uint64_t seed, terrain::ProceduralSpec::Type type, float heightScale) {
  terrain::ProceduralSpec spec = terrain::defaultLandscapeSpec(seed);
  spec.type = type;
  spec.heightScale = heightScale;
  return spec;
}

/** The EXR written by `sylva terrain heightmap` must hold exactly generate()'s heights. */
void expectSameHeights(const fs::path& exr, const terrain::HeightField& expected) {
  const Image image = loadImage(exr);
  ASSERT_EQ(image.width(), expected.width());
  ASSERT_EQ(image.height(), expected.height());
  ASSERT_EQ(image.channels(), 1);
  ASSERT_EQ(image.type(), PixelType::F32);
  const auto values = image.values<float>();
  ASSERT_EQ(values.size(), expected.samples().size());
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    mismatches += values[k] != expected.samples()[k] ? 1 : 0;
  }
  EXPECT_EQ(mismatches, 0u);
}

const fs::path kElevTif = test::sourcePath("data/external/elev.tif");
const fs::path kJacksboro = test::sourcePath("data/external/jacksboro_fault_dem.npz");

// ----------------------------------------------------------------------------------------------------------
// General commands

TEST(CliGeneral, HelpListsCommands) {
  const test::TempDir dir;
  const RunResult r = runSylva(dir, "--help");
  EXPECT_EQ(r.status, 0) << r.err;
  for (const char* command : {"info", "render", "imgdiff", "terrain"}) {
    EXPECT_NE(r.out.find(command), std::string::npos) << command << " missing from:\n" << r.out;
  }
}

// `sylva --version` names the release (the project() version) and the git revision it was built from, so a
// report from a user or a render node says exactly which code ran (CHANGELOG.md).
TEST(CliGeneral, VersionNamesReleaseAndRevision) {
  const test::TempDir dir;
  const RunResult r = runSylva(dir, "--version");
  EXPECT_EQ(r.status, 0) << r.err;
  std::smatch project;
  const std::string cmake = readAll(test::sourcePath("CMakeLists.txt"));
  ASSERT_TRUE(
      std::regex_search(cmake, project, std::regex(R"(project\(Sylva VERSION ([0-9]+\.[0-9]+\.[0-9]+))")));
  // A tree without .git (an unpacked archive) has no revision to name.
  const bool git = fs::exists(test::sourcePath(".git"));
  const std::string revision = git ? "[0-9a-f]{7,}(-dirty)?" : "unknown";
  EXPECT_TRUE(std::regex_match(
      r.out, std::regex("sylva " + std::regex_replace(project[1].str(), std::regex(R"(\.)"), R"(\.)") +
                        " \\(git " + revision + "\\)\n")))
      << r.out;
}

TEST(CliGeneral, UnknownCommandExitsTwoWithOneLine) {
  const test::TempDir dir;
  const RunResult r = runSylva(dir, "no-such-command");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(lineCount(r.err), 1u) << r.err;
  EXPECT_EQ(r.err.rfind("sylva: error:", 0), 0u) << r.err;
}

TEST(CliGeneral, ImgdiffExitCodes) {
  const test::TempDir dir;
  Image a(32, 16, 3, PixelType::U8);
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      a.set(x, y, 0, static_cast<float>(x) / 31.0f);
      a.set(x, y, 1, static_cast<float>(y) / 15.0f);
    }
  }
  Image b = a;
  for (int x = 0; x < 8; ++x) {
    b.set(x, 3, 2, 1.0f);
  }
  saveImage(dir / "a.png", a);
  saveImage(dir / "a_copy.png", a);
  saveImage(dir / "b.png", b);

  const RunResult same = runSylva(dir, "imgdiff " + quote((dir / "a.png").string()) + " " +
                                           quote((dir / "a_copy.png").string()));
  EXPECT_EQ(same.status, 0) << same.out << same.err;
  EXPECT_NE(same.out.find("MATCH"), std::string::npos) << same.out;

  const RunResult differ =
      runSylva(dir, "imgdiff " + quote((dir / "a.png").string()) + " " + quote((dir / "b.png").string()) +
                        " --diff " + quote((dir / "diff.png").string()));
  EXPECT_EQ(differ.status, 1) << differ.out << differ.err;
  EXPECT_NE(differ.out.find("DIFFER: 8 of 512"), std::string::npos) << differ.out;
  EXPECT_TRUE(fs::exists(dir / "diff.png"));

  const RunResult missing =
      runSylva(dir, "imgdiff " + quote((dir / "a.png").string()) + " " + quote((dir / "nope.png").string()));
  EXPECT_EQ(missing.status, 2);
  EXPECT_EQ(lineCount(missing.err), 1u) << missing.err;
  EXPECT_NE(missing.err.find("nope.png"), std::string::npos) << missing.err;
}

// ----------------------------------------------------------------------------------------------------------
// sylva terrain: help and outputs

TEST(CliTerrain, HelpOfEverySubcommand) {
  const test::TempDir dir;
  const RunResult top = runSylva(dir, "terrain --help");
  EXPECT_EQ(top.status, 0) << top.err;
  for (const char* sub : {"heightmap", "normals", "splat", "info", "query"}) {
    EXPECT_NE(top.out.find(sub), std::string::npos) << sub;
    const RunResult r = runSylva(dir, std::string("terrain ") + sub + " --help");
    EXPECT_EQ(r.status, 0) << sub << ": " << r.err;
    EXPECT_TRUE(r.err.empty()) << sub << ": " << r.err;
    for (const char* option : {"--dem", "--seed", "--type", "--size", "--spacing", "--height-scale", "--spec",
                               "--png-scale", "--npz-array"}) {
      EXPECT_NE(r.out.find(option), std::string::npos) << sub << " --help lacks " << option;
    }
  }
  EXPECT_NE(runSylva(dir, "terrain normals --help").out.find("[0, 1]"), std::string::npos);
  EXPECT_NE(runSylva(dir, "terrain splat --help").out.find("--write-default-layers"), std::string::npos);
  EXPECT_NE(runSylva(dir, "terrain query --help").out.find("--bicubic"), std::string::npos);
  // Without a subcommand: an error, not silence.
  const RunResult bare = runSylva(dir, "terrain");
  EXPECT_EQ(bare.status, 2);
  EXPECT_EQ(lineCount(bare.err), 1u) << bare.err;
}

TEST(CliTerrain, HeightmapFromSeedToPngAndExr) {
  const test::TempDir dir;
  const fs::path png = dir / "out" / "h.png";
  const RunResult r = runSylva(dir, "terrain heightmap --seed 7 --type ridged --size 65 --spacing 2 "
                                    "--height-scale 150 -o " +
                                        quote(png.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const std::vector<std::string> out = lines(r.out);
  ASSERT_EQ(out.size(), 3u) << r.out;
  EXPECT_EQ(out[0], png.string());
  EXPECT_EQ(out[1], png.string() + ".json");
  EXPECT_NE(out[2].find("65x65 samples, spacing 2 x 2 m"), std::string::npos) << out[2];
  EXPECT_NE(out[2].find("0 absent"), std::string::npos) << out[2];

  const Image image = loadImage(png);
  EXPECT_EQ(image.width(), 65);
  EXPECT_EQ(image.height(), 65);
  EXPECT_EQ(image.channels(), 1);
  EXPECT_EQ(image.type(), PixelType::U16);
  const nlohmann::json sidecar = loadJsonFile(png.string() + ".json");
  EXPECT_EQ(sidecar.at("spacingX").get<float>(), 2.0f);

  const fs::path exr = dir / "out" / "h.exr";
  const RunResult e = runSylva(dir, "terrain heightmap --seed 7 --type ridged --size 65 --spacing 2 "
                                    "--height-scale 150 -o " +
                                        quote(exr.string()));
  ASSERT_EQ(e.status, 0) << e.err;
  const terrain::HeightField expected =
      terrain::generate(specFor(7, terrain::ProceduralSpec::Type::Ridged, 150.0f), 0.0, 0.0, 65, 65, 2.0f);
  expectSameHeights(exr, expected);

  // The PNG, read back through its sidecar, is the same terrain to 16-bit precision.
  const terrain::HeightField fromPng = terrain::loadHeightField(png);
  const terrain::HeightFieldInfo info = terrain::heightFieldInfo(expected);
  const float step = (info.maxHeight - info.minHeight) / 65535.0f;
  for (std::size_t k = 0; k < expected.samples().size(); ++k) {
    ASSERT_NEAR(fromPng.samples()[k], expected.samples()[k], step) << k;
  }
}

TEST(CliTerrain, LargeHeightmapIsGeneratedInStripsWithIdenticalHeights) {
  // 1100² samples exceeds the progress threshold (2^20), so the command generates row strips.
  const test::TempDir dir;
  const fs::path exr = dir / "big.exr";
  const RunResult r = runSylva(
      dir, "terrain heightmap --seed 99 --type warped --size 1100 --spacing 0.5 -o " + quote(exr.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const terrain::HeightField expected = terrain::generate(
      specFor(99, terrain::ProceduralSpec::Type::Warped, 400.0f), 0.0, 0.0, 1100, 1100, 0.5f);
  expectSameHeights(exr, expected);
}

TEST(CliTerrain, HeightmapFromSpecFileWithOverrides) {
  const test::TempDir dir;
  terrain::ProceduralSpec spec;
  spec.seed = 3;
  spec.octaves = 4;
  spec.frequency = 1.0f / 64.0f;
  spec.heightScale = 80.0f;
  terrain::saveProceduralSpec(dir / "spec.json", spec);

  const RunResult r = runSylva(dir, "terrain heightmap --spec " + quote((dir / "spec.json").string()) +
                                        " --size 33 -o " + quote((dir / "a.exr").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  expectSameHeights(dir / "a.exr",
                    terrain::generate(spec, 0.0, 0.0, 33, 33, terrain::kDefaultProceduralSpacing));

  // --seed overrides the file's seed; the other fields stay.
  const RunResult o = runSylva(dir, "terrain heightmap --spec " + quote((dir / "spec.json").string()) +
                                        " --seed 11 --size 33 -o " + quote((dir / "b.exr").string()));
  ASSERT_EQ(o.status, 0) << o.err;
  spec.seed = 11;
  expectSameHeights(dir / "b.exr",
                    terrain::generate(spec, 0.0, 0.0, 33, 33, terrain::kDefaultProceduralSpacing));
}

TEST(CliTerrain, HeightmapFromDemRoundTrips) {
  const test::TempDir dir;
  const terrain::HeightField field =
      terrain::generate(specFor(5, terrain::ProceduralSpec::Type::Fbm, 120.0f), 0.0, 0.0, 40, 30, 3.0f);
  terrain::saveHeightField(dir / "dem.exr", field);
  const RunResult r = runSylva(dir, "terrain heightmap --dem " + quote((dir / "dem.exr").string()) + " -o " +
                                        quote((dir / "copy.exr").string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("40x30 samples, spacing 3 x 3 m"), std::string::npos) << r.out;
  expectSameHeights(dir / "copy.exr", field);

  // --spacing overrides the sidecar's spacing for a DEM.
  const RunResult s =
      runSylva(dir, "terrain info --dem " + quote((dir / "dem.exr").string()) + " --spacing 10");
  ASSERT_EQ(s.status, 0) << s.err;
  EXPECT_NE(s.out.find("extent    390 x 290 m"), std::string::npos) << s.out;
}

TEST(CliTerrain, NormalsPngAndExr) {
  const test::TempDir dir;
  const std::string source = "--seed 4 --size 48 --spacing 1.5 --height-scale 90";
  const RunResult e = runSylva(dir, "terrain normals " + source + " -o " + quote((dir / "n.exr").string()));
  ASSERT_EQ(e.status, 0) << e.err;
  EXPECT_EQ(lines(e.out).at(0), (dir / "n.exr").string());
  const RunResult p = runSylva(dir, "terrain normals " + source + " -o " + quote((dir / "n.png").string()));
  ASSERT_EQ(p.status, 0) << p.err;

  const terrain::HeightField field =
      terrain::generate(specFor(4, terrain::ProceduralSpec::Type::Warped, 90.0f), 0.0, 0.0, 48, 48, 1.5f);
  const Image expected = terrain::sobelNormalMap(field);
  const Image exr = loadImage(dir / "n.exr");
  ASSERT_EQ(exr.width(), 48);
  ASSERT_EQ(exr.height(), 48);
  ASSERT_EQ(exr.channels(), 3);
  EXPECT_TRUE(exr == expected) << "EXR normals differ from sobelNormalMap";

  const Image png = loadImage(dir / "n.png");
  ASSERT_EQ(png.width(), 48);
  ASSERT_EQ(png.height(), 48);
  ASSERT_EQ(png.channels(), 3);
  EXPECT_EQ(png.type(), PixelType::U16);
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 48; ++x) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(png.get(x, y, c), expected.get(x, y, c) * 0.5f + 0.5f, 1.0f / 65535.0f) << x << "," << y;
      }
    }
  }

  // --border constant reads 0 m outside the grid: the edge normals change, the interior does not.
  const RunResult b =
      runSylva(dir, "terrain normals " + source + " --border constant -o " + quote((dir / "c.exr").string()));
  ASSERT_EQ(b.status, 0) << b.err;
  terrain::SobelOptions constant;
  constant.border = terrain::BorderMode::Constant;
  const Image borderExpected = terrain::sobelNormalMap(field, constant);
  const Image border = loadImage(dir / "c.exr");
  EXPECT_TRUE(border == borderExpected);
  EXPECT_NE(border.get(0, 10, 0), exr.get(0, 10, 0));
  EXPECT_EQ(border.get(10, 10, 0), exr.get(10, 10, 0));

  // 8-bit PNG on request.
  const RunResult eight =
      runSylva(dir, "terrain normals " + source + " --bits 8 -o " + quote((dir / "n8.png").string()));
  ASSERT_EQ(eight.status, 0) << eight.err;
  EXPECT_EQ(loadImage(dir / "n8.png").type(), PixelType::U8);
}

TEST(CliTerrain, SplatOnePageWithDefaultLayers) {
  const test::TempDir dir;
  const fs::path out = dir / "splat.png";
  const RunResult r = runSylva(dir, "terrain splat --seed 2 --size 40 -o " + quote(out.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> outLines = lines(r.out);
  ASSERT_EQ(outLines.size(), 2u) << r.out;
  EXPECT_EQ(outLines[0], out.string());
  EXPECT_NE(outLines[1].find("4 layers on 1 page (sand, grass, snow, rock)"), std::string::npos) << r.out;
  const Image page = loadImage(out);
  EXPECT_EQ(page.width(), 40);
  EXPECT_EQ(page.height(), 40);
  EXPECT_EQ(page.channels(), 4);
  EXPECT_EQ(page.type(), PixelType::U8);
  EXPECT_FALSE(fs::exists(dir / "splat_0.png"));
  // Weights sum to 1 (up to 8-bit rounding of each channel).
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) {
      const float sum = page.get(x, y, 0) + page.get(x, y, 1) + page.get(x, y, 2) + page.get(x, y, 3);
      ASSERT_NEAR(sum, 1.0f, 2.0f / 255.0f) << x << "," << y;
    }
  }
}

TEST(CliTerrain, SplatSeveralPagesAndDefaultLayersFile) {
  const test::TempDir dir;
  // Write the default rules for this terrain, then add a fifth layer: two pages.
  const fs::path rules = dir / "rules.json";
  const RunResult w =
      runSylva(dir, "terrain splat --seed 2 --size 40 --write-default-layers " + quote(rules.string()));
  ASSERT_EQ(w.status, 0) << w.err;
  EXPECT_EQ(lines(w.out).at(0), rules.string());
  std::vector<terrain::SplatLayer> layers = terrain::loadSplatLayers(rules);
  ASSERT_EQ(layers.size(), 4u);
  EXPECT_EQ(layers[0].name, "sand");
  EXPECT_EQ(layers[3].name, "rock");
  terrain::SplatLayer cliff;
  cliff.name = "cliff";
  cliff.minSlope = 60.0f;
  layers.push_back(cliff);
  terrain::saveSplatLayers(rules, layers);

  const fs::path out = dir / "maps" / "splat.png";
  const RunResult r = runSylva(dir, "terrain splat --seed 2 --size 40 --layers " + quote(rules.string()) +
                                        " -o " + quote(out.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const char* name : {"splat_0.png", "splat_1.png"}) {
    const fs::path page = dir / "maps" / name;
    ASSERT_TRUE(fs::exists(page)) << name;
    EXPECT_NE(r.out.find(page.string()), std::string::npos) << r.out;
    const Image image = loadImage(page);
    EXPECT_EQ(image.width(), 40);
    EXPECT_EQ(image.channels(), 4);
  }
  EXPECT_FALSE(fs::exists(dir / "maps" / "splat_2.png"));
  EXPECT_NE(r.out.find("5 layers on 2 pages"), std::string::npos) << r.out;
}

TEST(CliTerrain, InfoOfProceduralField) {
  const test::TempDir dir;
  const RunResult r = runSylva(dir, "terrain info --seed 1 --size 257 --spacing 2");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("size      257 x 257 samples"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("extent    512 x 512 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("absent    0 of 66049 samples"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("quadtree  16 roots as 4 x 4 of 128 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("min/max memory"), std::string::npos) << r.out;

  const RunResult j = runSylva(dir, "terrain info --seed 1 --size 257 --spacing 2 --json");
  ASSERT_EQ(j.status, 0) << j.err;
  const nlohmann::json json = nlohmann::json::parse(j.out);
  EXPECT_EQ(json.at("width").get<int>(), 257);
  EXPECT_EQ(json.at("absentSamples").get<int>(), 0);
  EXPECT_EQ(json.at("quadtree").at("rootsX").get<int>() * json.at("quadtree").at("rootsZ").get<int>(), 16);
  EXPECT_GT(json.at("quadtree").at("minMaxBytes").get<long long>(), 0);
}

TEST(CliTerrain, QueryHeightNormalAndRayOnAPlane) {
  const test::TempDir dir;
  // h = 0.5·x + 0.25·z on a 2 m grid: bilinear and (inside) bicubic interpolation are exact.
  terrain::HeightField plane(33, 33, 2.0f, 2.0f);
  for (int j = 0; j < 33; ++j) {
    for (int i = 0; i < 33; ++i) {
      plane.at(i, j) = 0.5f * static_cast<float>(2 * i) + 0.25f * static_cast<float>(2 * j);
    }
  }
  terrain::saveHeightField(dir / "plane.exr", plane);
  const std::string dem = "--dem " + quote((dir / "plane.exr").string());

  for (const char* mode : {"", " --bicubic"}) {
    const RunResult r = runSylva(dir, "terrain query " + dem + " --at 21,30.5" + mode);
    ASSERT_EQ(r.status, 0) << r.err;
    float x = 0, z = 0, h = 0, nx = 0, ny = 0, nz = 0;
    ASSERT_EQ(std::sscanf(r.out.c_str(), "at (%f, %f) m: height %f m, normal (%f, %f, %f)", &x, &z, &h, &nx,
                          &ny, &nz),
              6)
        << r.out;
    EXPECT_FLOAT_EQ(x, 21.0f);
    EXPECT_FLOAT_EQ(z, 30.5f);
    EXPECT_NEAR(h, 0.5f * 21.0f + 0.25f * 30.5f, 1e-3f) << mode;
    const float len = std::sqrt(0.25f + 1.0f + 0.0625f);
    EXPECT_NEAR(nx, -0.5f / len, 1e-4f) << mode;
    EXPECT_NEAR(ny, 1.0f / len, 1e-4f) << mode;
    EXPECT_NEAR(nz, -0.25f / len, 1e-4f) << mode;
  }

  // Straight down at (10, 20): hits h = 10 at distance 90.
  const RunResult down = runSylva(dir, "terrain query " + dem + " --ray 10,100,20,0,-1,0");
  ASSERT_EQ(down.status, 0) << down.err;
  float hx = 0, hy = 0, hz = 0, dist = 0;
  ASSERT_EQ(std::sscanf(down.out.c_str(), "hit at (%f, %f, %f) m, distance %f m", &hx, &hy, &hz, &dist), 4)
      << down.out;
  EXPECT_NEAR(hx, 10.0f, 1e-3f);
  EXPECT_NEAR(hy, 10.0f, 1e-3f);
  EXPECT_NEAR(hz, 20.0f, 1e-3f);
  EXPECT_NEAR(dist, 90.0f, 1e-3f);

  const RunResult up = runSylva(dir, "terrain query " + dem + " --ray 10,100,20,0,1,0");
  ASSERT_EQ(up.status, 0) << up.err;
  EXPECT_EQ(up.out, "miss\n");

  // Negative coordinates: outside the footprint, edge heights continue.
  const RunResult outside = runSylva(dir, "terrain query " + dem + " --at -5,0");
  ASSERT_EQ(outside.status, 0) << outside.err;
  EXPECT_NE(outside.out.find("height 0.000 m"), std::string::npos) << outside.out;
  EXPECT_NE(outside.out.find("outside the footprint"), std::string::npos) << outside.out;
}

// ----------------------------------------------------------------------------------------------------------
// Real data (scripts/fetch-sample-data.sh)

TEST(CliTerrain, InfoOfElevTifReportsNodata) {
  if (!fs::exists(kElevTif)) {
    GTEST_SKIP() << kElevTif << " not found; run scripts/fetch-sample-data.sh";
  }
  const test::TempDir dir;
  const RunResult r = runSylva(dir, "terrain info --dem " + quote(kElevTif.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const RunResult j = runSylva(dir, "terrain info --json --dem " + quote(kElevTif.string()));
  ASSERT_EQ(j.status, 0) << j.err;
  const nlohmann::json json = nlohmann::json::parse(j.out);
  EXPECT_GT(json.at("absentSamples").get<long long>(), 0) << r.out;
  EXPECT_GT(json.at("validSamples").get<long long>(), 0) << r.out;
  EXPECT_NE(r.out.find("absent    " + std::to_string(json.at("absentSamples").get<long long>()) + " of"),
            std::string::npos)
      << r.out;
}

TEST(CliTerrain, JacksboroNpzInfoAndMaps) {
  if (!fs::exists(kJacksboro)) {
    GTEST_SKIP() << kJacksboro << " not found; run scripts/fetch-sample-data.sh";
  }
  const test::TempDir dir;
  const std::string dem = "--dem " + quote(kJacksboro.string());
  const RunResult r = runSylva(dir, "terrain info " + dem);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("quadtree  16 roots"), std::string::npos) << r.out;
  const terrain::HeightField field = terrain::loadHeightField(kJacksboro);
  EXPECT_NE(r.out.find("size      " + std::to_string(field.width()) + " x " + std::to_string(field.height())),
            std::string::npos)
      << r.out;

  const RunResult n = runSylva(dir, "terrain normals " + dem + " -o " + quote((dir / "n.png").string()));
  ASSERT_EQ(n.status, 0) << n.err;
  EXPECT_EQ(loadImage(dir / "n.png").width(), field.width());

  const RunResult bad = runSylva(dir, "terrain info " + dem + " --npz-array no_such_array");
  EXPECT_NE(bad.status, 0);
  EXPECT_EQ(lineCount(bad.err), 1u) << bad.err;
  EXPECT_NE(bad.err.find("jacksboro_fault_dem.npz"), std::string::npos) << bad.err;
}

// ----------------------------------------------------------------------------------------------------------
// Bad input: one line on stderr naming the file or option, non-zero exit, no output file.

struct BadInput {
  const char* name;
  std::string args; // "{in}" is replaced by the input directory, "{out}" by the output directory
  const char* mentions;
};

std::string expand(std::string text, const fs::path& in, const fs::path& out) {
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{in}", in.string()},
                                   std::pair<std::string, std::string>{"{out}", out.string()}}) {
    for (std::size_t p = text.find(key); p != std::string::npos; p = text.find(key, p + value.size())) {
      text.replace(p, key.size(), value);
    }
  }
  return text;
}

// `sylva view --grass`: bad grass and simulation options fail with one line naming the option before any
// window opens (so these need no display; the viewer itself is tested under xvfb in RenderCliTests.cpp).
TEST(CliView, BadGrassOptionsFailBeforeOpeningAWindow) {
  const test::TempDir dir;
  struct Case {
    std::string args;
    std::string names;
  };
  for (const Case& c :
       {Case{"--grass --scene demo", "--grass"}, Case{"--grass --grass-lod 40,10", "--grass-lod"},
        Case{"--grass-lod 1,x", "--grass-lod"},
        Case{"--grass --grass-blades 64 --grass-per-tile 128", "--grass-per-tile"},
        Case{"--grass --grass-density 2", "--grass-density"}, Case{"--physics balls", "--physics"},
        Case{"--grass --physics balls --balls 0", "--balls"}}) {
    const RunResult r = runSylva(dir, "view --frames 1 " + c.args);
    EXPECT_EQ(r.status, 2) << c.args << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << c.args << ": " << r.err;
  }
}

TEST(CliTerrain, BadInputFailsWithOneLineAndNoOutput) {
  const test::TempDir dir;
  const fs::path in = dir / "in";
  const fs::path out = dir / "out";
  fs::create_directories(in);

  // Inputs: corrupt, truncated and 1×1 images; invalid rules; a valid DEM to combine with bad options.
  writeTextFile(in / "corrupt.png", "this is not a PNG file at all, just text pretending to be one\n");
  Image valid(64, 64, 1, PixelType::U16);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      valid.set(x, y, 0, static_cast<float>((x * 7 + y * 13) % 64) / 63.0f);
    }
  }
  saveImage(in / "valid.png", valid);
  const std::string bytes = readAll(in / "valid.png");
  writeTextFile(in / "truncated.png", bytes.substr(0, bytes.size() / 2));
  saveImage(in / "one.png", Image(1, 1, 1, PixelType::U16));
  writeTextFile(in / "syntax_rules.json", "{\"version\": 1, \"layers\": [ {\"name\": \"a\", }\n");
  writeTextFile(in / "field_rules.json",
                "{\"version\": 1, \"layers\": [{\"name\": \"a\", \"maxSlope\": \"steep\"}]}\n");
  writeTextFile(in / "empty_rules.json", "{\"version\": 1, \"layers\": []}\n");
  writeTextFile(in / "bad_spec.json", "{\"version\": 1, \"octaves\": 99}\n");

  const std::string seed = "--seed 1 --size 33";
  const std::vector<BadInput> cases = {
      {"missing DEM", "terrain heightmap --dem {in}/missing.tif -o {out}/h.png", "missing.tif"},
      {"missing PNG DEM", "terrain normals --dem {in}/missing.png -o {out}/n.png", "missing.png"},
      {"corrupt DEM", "terrain heightmap --dem {in}/corrupt.png -o {out}/h.png", "corrupt.png"},
      {"truncated DEM", "terrain heightmap --dem {in}/truncated.png -o {out}/h.exr", "truncated.png"},
      {"1x1 DEM", "terrain splat --dem {in}/one.png -o {out}/s.png", "one.png"},
      {"NaN size", "terrain heightmap --seed 1 --size nan -o {out}/h.png", "--size"},
      {"zero size", "terrain heightmap --seed 1 --size 0 -o {out}/h.png", "--size"},
      {"1x1 size", "terrain heightmap --seed 1 --size 1 -o {out}/h.png", "--size"},
      {"absurd size", "terrain heightmap --seed 1 --size 1000000 -o {out}/h.png", "--size"},
      {"NaN spacing", "terrain heightmap " + seed + " --spacing nan -o {out}/h.png", "--spacing"},
      {"negative spacing", "terrain heightmap " + seed + " --spacing=-2 -o {out}/h.png", "--spacing"},
      {"absurd spacing", "terrain normals " + seed + " --spacing 1e30 -o {out}/n.png", "--spacing"},
      {"NaN DEM spacing", "terrain info --dem {in}/valid.png --spacing nan", "--spacing"},
      {"NaN height scale", "terrain heightmap " + seed + " --height-scale nan -o {out}/h.png",
       "--height-scale"},
      {"inf height scale", "terrain heightmap " + seed + " --height-scale inf -o {out}/h.png",
       "--height-scale"},
      {"zero height scale", "terrain heightmap " + seed + " --height-scale 0 -o {out}/h.png",
       "--height-scale"},
      {"absurd height scale", "terrain heightmap " + seed + " --height-scale 1e12 -o {out}/h.png",
       "--height-scale"},
      {"NaN PNG scale", "terrain heightmap --dem {in}/valid.png --png-scale nan -o {out}/h.png",
       "--png-scale"},
      {"both sources", "terrain heightmap --dem {in}/valid.png --seed 3 -o {out}/h.png", "--dem"},
      {"no source", "terrain heightmap --size 33 -o {out}/h.png", "--dem"},
      {"no source (info)", "terrain info", "--dem"},
      {"negative seed", "terrain heightmap --seed -1 --size 33 -o {out}/h.png", "--seed"},
      {"unknown type", "terrain heightmap " + seed + " --type perlin -o {out}/h.png", "--type"},
      {"type with DEM", "terrain heightmap --dem {in}/valid.png --type ridged -o {out}/h.png", "--type"},
      {"PNG scale with seed", "terrain heightmap " + seed + " --png-scale 10 -o {out}/h.png", "--png-scale"},
      {"bad spec", "terrain heightmap --spec {in}/bad_spec.json --size 33 -o {out}/h.png", "bad_spec.json"},
      {"missing spec", "terrain heightmap --spec {in}/nospec.json --size 33 -o {out}/h.png", "nospec.json"},
      {"rules syntax", "terrain splat " + seed + " --layers {in}/syntax_rules.json -o {out}/s.png",
       "syntax_rules.json"},
      {"rules field", "terrain splat " + seed + " --layers {in}/field_rules.json -o {out}/s.png",
       "field_rules.json"},
      {"rules empty", "terrain splat " + seed + " --layers {in}/empty_rules.json -o {out}/s.png",
       "empty_rules.json"},
      {"missing rules", "terrain splat " + seed + " --layers {in}/none.json -o {out}/s.png", "none.json"},
      {"output extension", "terrain heightmap " + seed + " -o {out}/h.jpg", "-o"},
      {"normals extension", "terrain normals " + seed + " -o {out}/n.tif", "-o"},
      {"splat without -o", "terrain splat " + seed, "-o"},
      {"missing -o", "terrain heightmap " + seed, "-o"},
      {"bad border", "terrain normals " + seed + " --border wrap -o {out}/n.png", "--border"},
      {"query without --at", "terrain query " + seed, "--at"},
      {"query bad --at", "terrain query " + seed + " --at 1,nan", "--at"},
      {"query short --at", "terrain query " + seed + " --at 1", "--at"},
      {"query zero ray", "terrain query " + seed + " --ray 1,2,3,0,0,0", "--ray"},
      // render shares the source options and adds its own; no context is created before they are checked.
      {"render NaN time", "render " + seed + " --time nan -o {out}/r.png", "--time"},
      {"render inf LOD factor", "render " + seed + " --lod-factor inf -o {out}/r.png", "--lod-factor"},
      {"render corrupt DEM", "render --dem {in}/corrupt.png -o {out}/r.png", "corrupt.png"},
      {"render two sources", "render --dem {in}/valid.png " + seed + " -o {out}/r.png", "--dem"},
      {"query bad ray", "terrain query " + seed + " --ray 1,2,3,4,5", "--ray"},
  };
  for (const BadInput& c : cases) {
    SCOPED_TRACE(c.name);
    const RunResult r = runSylva(dir, expand(c.args, in, out));
    EXPECT_NE(r.status, 0) << r.out;
    EXPECT_NE(r.status, 3) << "internal error: " << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("sylva: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.mentions), std::string::npos)
        << "stderr does not name " << c.mentions << ": " << r.err;
    const std::vector<fs::path> written = filesUnder(out);
    EXPECT_TRUE(written.empty()) << "left " << written.front();
    fs::remove_all(out);
  }
}

} // namespace
} // namespace sylva

namespace sylva {
namespace {

// docs/cli.md ends with the `--help` of every command, generated from the binary: this test fails when they
// drift apart. `SYLVA_UPDATE_DOCS=1` (scripts/update-cli-docs.sh) rewrites the section instead.
TEST(CliDocs, ReferenceMatchesHelp) {
  static const char* const kCommands[] = {"",
                                          "info",
                                          "render",
                                          "view",
                                          "bench",
                                          "imgdiff",
                                          "terrain",
                                          "terrain heightmap",
                                          "terrain normals",
                                          "terrain splat",
                                          "terrain info",
                                          "terrain query",
                                          "fold",
                                          "fold synth",
                                          "fold render",
                                          "fold view",
                                          "fold export-shader",
                                          "fold export-web",
                                          "fold info",
                                          "fold template",
                                          "fold flow",
                                          "fold edit",
                                          "capture",
                                          "capture synth",
                                          "tree",
                                          "tree generate",
                                          "tree info",
                                          "tree species",
                                          "tree pieces",
                                          "tree import-piece",
                                          "tree export",
                                          "texsynth",
                                          "texsynth quilt",
                                          "texsynth tiles",
                                          "texsynth wang",
                                          "scene",
                                          "scene check"};
  const test::TempDir dir;
  std::string reference = "<!-- generated by scripts/update-cli-docs.sh from --help; do not edit -->\n";
  for (const char* command : kCommands) {
    const test::RunResult r = runSylva(dir, std::string(command) + " --help");
    ASSERT_EQ(r.status, 0) << command;
    reference += fmt::format("\n### `sylva{}{} --help`\n\n```text\n{}```\n", *command != '\0' ? " " : "",
                             command, r.out);
  }
  const fs::path doc = fs::path(SYLVA_SOURCE_DIR) / "docs" / "cli.md";
  const std::string marker = "## Reference (every command's --help)\n";
  std::string text = readAll(doc);
  const std::size_t at = text.find(marker);
  ASSERT_NE(at, std::string::npos) << doc << " lacks the section '" << marker << "'";
  const std::string current = text.substr(at + marker.size());
  if (std::getenv("SYLVA_UPDATE_DOCS") != nullptr) {
    writeTextFile(doc, text.substr(0, at + marker.size()) + reference);
    return;
  }
  EXPECT_EQ(current, reference) << "docs/cli.md is out of date with --help: run scripts/update-cli-docs.sh";
}

TEST(CliBench, EveryPassOfEveryAreaReportsItsWork) {
  // The areas share one measuring loop, which counts each pass's work (pipeline statistics) beside its times:
  // the demo's compute pass runs one invocation per height sample and draws nothing; its surface pass draws.
  test::TempDir dir;
  const fs::path report = dir / "demo.json";
  const RunResult r =
      runSylva(dir, "bench demo --frames 1 --warmup 0 --width 64 --height 64 -o " + quote(report.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = loadJsonFile(report);
  ASSERT_EQ(json.at("passes").size(), 2u);
  const nlohmann::json& heights = json.at("passes")[0];
  const nlohmann::json& surface = json.at("passes")[1];
  EXPECT_EQ(heights.at("name"), "heights");
  EXPECT_GT(heights.at("counts").at("compute_invocations").get<long long>(), 0);
  EXPECT_EQ(heights.at("counts").at("fragment_invocations"), 0);
  EXPECT_EQ(surface.at("name"), "surface");
  EXPECT_GT(surface.at("counts").at("clipped_primitives").get<long long>(), 0);
  EXPECT_GT(surface.at("counts").at("fragment_invocations").get<long long>(), 0);
  EXPECT_EQ(surface.at("counts").at("compute_invocations"), 0);
}

// `bench terrain-error` end to end on tiny fields: four fields, both methods tuned, a measured worst error at
// or under 1 px for every method that reached the goal, vertices counted. Bad sizes are refused up front.
TEST(CliBench, TerrainErrorComparesBothMethodsAtEqualError) {
  test::TempDir dir;
  const fs::path report = dir / "error.json";
  const RunResult r =
      runSylva(dir, "bench terrain-error --frames 2 --field-size 129 --width 96 --height 64 -o " +
                        quote(report.string()));
  if (r.status != 0 && r.err.find("fetch-sample-data") != std::string::npos) {
    GTEST_SKIP() << "sample data missing: " << r.err;
  }
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = loadJsonFile(report);
  ASSERT_EQ(json.at("fields").size(), 4u);
  for (const nlohmann::json& field : json.at("fields")) {
    for (const char* method : {"distance", "error"}) {
      const nlohmann::json& m = field.at(method);
      if (m.at("goal_reached").get<bool>()) {
        EXPECT_LE(m.at("worst_px").get<double>(), 1.0) << field.at("field") << " " << method;
      }
      EXPECT_GT(m.at("vertices_mean").get<double>(), 0.0) << field.at("field") << " " << method;
      EXPECT_GT(m.at("probes").get<int>(), 0);
    }
    EXPECT_GT(field.at("vertex_ratio").get<double>(), 0.0);
  }
  const RunResult bad = runSylva(dir, "bench terrain-error --field-size 5");
  EXPECT_NE(bad.status, 0);
  EXPECT_NE(bad.err.find("--field-size"), std::string::npos) << bad.err;
}

TEST(CliBench, TerrainStreamFliesWithinItsBudgets) {
  // docs/terrain-data.md "Streaming": small budgets force evictions and stand-ins; memory stays within them
  // and the drawn vertices keep matching the height query.
  test::TempDir dir;
  const fs::path report = dir / "stream.json";
  const RunResult r =
      runSylva(dir, "bench terrain-stream --distance 1.5 --width 96 --height 64 --gpu-budget 4 "
                    "--ram-budget 8 -o " +
                        quote(report.string()));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("frames that waited for a tile"), std::string::npos) << r.out;
  const nlohmann::json json = loadJsonFile(report);
  EXPECT_TRUE(json.at("within_budgets").get<bool>());
  EXPECT_LE(json.at("ram_peak_mb").get<double>(), 8.0);
  EXPECT_LE(json.at("gpu_tiles_mb").get<double>(), 4.0);
  EXPECT_GT(json.at("tiles_loaded").get<double>(), 300.0);
  EXPECT_LE(json.at("height_query_worst_m").get<double>(), 0.01);
  EXPECT_GT(json.at("height_query_checks").get<int>(), 3);
  EXPECT_NEAR(json.at("flight_km").get<double>(), 1.5, 1e-9);
  const RunResult tight = runSylva(dir, "bench terrain-stream --gpu-budget 8 --ram-budget 2");
  EXPECT_NE(tight.status, 0);
  EXPECT_NE(tight.err.find("--ram-budget"), std::string::npos) << tight.err;
}

TEST(CliBench, GpuBenchScriptRefusesSoftwareAndStoresEveryReport) {
  // scripts/gpu-bench.sh is for NVIDIA machines, which CI never has: here it must refuse llvmpipe in one line
  // before any work, and with --allow-software run what it is given and store each report.
  test::TempDir dir;
  const fs::path script = fs::path(SYLVA_SOURCE_DIR) / "scripts" / "gpu-bench.sh";
  const fs::path build = fs::path(SYLVA_EXE).parent_path().parent_path();
  const fs::path results = dir / "results";
  const std::string common =
      quote(script.string()) + " --build " + quote(build.string()) + " --results " + quote(results.string());
  const RunResult refused = test::runProgram("bash", dir.path(), common + " --areas demo --no-tests");
  if (refused.status == 0) {
    GTEST_SKIP() << "a GPU renders here; the software-renderer refusal is not testable";
  }
  EXPECT_EQ(refused.status, 2);
  EXPECT_EQ(lineCount(refused.err), 1u) << refused.err;
  EXPECT_NE(refused.err.find("--allow-software"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(results)) << "nothing written before the renderer was checked";
  const RunResult bad = test::runProgram("bash", dir.path(), common + " --areas nonsense --allow-software");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("unknown area 'nonsense'"), std::string::npos) << bad.err;

  const RunResult r =
      test::runProgram("bash", dir.path(), common + " --areas demo --quick --no-tests --allow-software");
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  const nlohmann::json info = loadJsonFile(results / "info.json");
  EXPECT_FALSE(info.at("renderer").get<std::string>().empty());
  const nlohmann::json demo = loadJsonFile(results / "demo.json");
  EXPECT_EQ(demo.at("passes").size(), 2u);
  const nlohmann::json summary = loadJsonFile(results / "summary.json");
  ASSERT_EQ(summary.at("runs").size(), 1u);
  EXPECT_EQ(summary.at("runs")[0].at("name"), "demo");
  EXPECT_EQ(summary.at("runs")[0].at("status"), 0);
  EXPECT_TRUE(summary.at("quick").get<bool>());
  EXPECT_TRUE(summary.at("gl_tests_status").is_null());
}

} // namespace
} // namespace sylva
