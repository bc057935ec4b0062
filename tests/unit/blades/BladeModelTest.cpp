// Blade-model files: exact round trips, every validation error naming the file and the JSON path at fault,
// broken and missing files, and the model helpers (length, widest knot, level choice).
#include <sylva/blades/BladeModel.hpp>

#include <sylva/core/Error.hpp>

#include "TempDir.hpp"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <utility>

namespace sylva::blades {
namespace {

using nlohmann::json;

/** Every field of two blade-model files is equal (floats exactly: files round-trip bit for bit). */
void expectEqual(const BladeModelFile& a, const BladeModelFile& b) {
  EXPECT_EQ(a.generator, b.generator);
  ASSERT_EQ(a.blades.size(), b.blades.size());
  for (std::size_t i = 0; i < a.blades.size(); ++i) {
    const BladeModel& x = a.blades[i];
    const BladeModel& y = b.blades[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.bendAxis, y.bendAxis);
    EXPECT_EQ(x.hasColour, y.hasColour);
    EXPECT_EQ(x.colour, y.colour);
    EXPECT_EQ(x.source.file, y.source.file);
    EXPECT_EQ(x.source.kind, y.source.kind);
    EXPECT_EQ(x.source.frame, y.source.frame);
    EXPECT_EQ(x.source.cluster, y.source.cluster);
    EXPECT_EQ(x.source.blade, y.source.blade);
    EXPECT_EQ(x.source.intrinsics, y.source.intrinsics);
    EXPECT_EQ(x.source.relativeDepth, y.source.relativeDepth);
    EXPECT_EQ(x.source.medialAxis, y.source.medialAxis);
    EXPECT_EQ(x.source.motionFrames, y.source.motionFrames);
    EXPECT_EQ(x.source.mu, y.source.mu);
    ASSERT_EQ(x.lods.size(), y.lods.size());
    for (std::size_t l = 0; l < x.lods.size(); ++l) {
      EXPECT_EQ(x.lods[l].positions, y.lods[l].positions);
      EXPECT_EQ(x.lods[l].widths, y.lods[l].widths);
      EXPECT_EQ(x.lods[l].normals, y.lods[l].normals);
    }
  }
}

/** A straight blade of `knots` knots along +Y, tapering to the tip, facing +Z. */
BladeLod straightLod(int knots, float length) {
  BladeLod lod;
  for (int k = 0; k < knots; ++k) {
    const float s = static_cast<float>(k) / static_cast<float>(knots - 1);
    lod.positions.emplace_back(0.0f, s * length, 0.0f);
    lod.widths.push_back(0.01f * (1.0f - s));
    lod.normals.emplace_back(0.0f, 0.0f, 1.0f);
  }
  return lod;
}

BladeModelFile sampleFile() {
  BladeModelFile file;
  file.generator = "sylva capture test: aloeGT.png";
  BladeModel a;
  a.name = "aloe-0";
  // Values that do not have short decimal forms, to prove floats round-trip exactly.
  BladeLod fine = straightLod(16, 0.3f);
  fine.positions[3] = {0.1f / 3.0f, 0.7f / 3.0f, -1e-7f};
  fine.normals[3] = glm::normalize(glm::vec3(0.1f, 0.2f, 0.97f));
  a.lods = {fine, straightLod(8, 0.3f), straightLod(4, 0.3f)};
  a.bendAxis = glm::normalize(glm::vec3(1.0f, 0.0f, 0.1f));
  a.hasColour = true;
  a.colour = {0.2f, 0.55f, 1.0f / 7.0f};
  a.source.file = "aloeGT.png";
  a.source.kind = "middlebury";
  a.source.frame = 3;
  a.source.cluster = 1;
  a.source.blade = 2;
  a.source.intrinsics = CameraIntrinsics::kinectV1();
  a.source.relativeDepth = true;
  a.source.medialAxis = true;
  a.source.motionFrames = 60;
  a.source.mu = 0.25;
  BladeModel b;
  b.name = "synthetic-1";
  b.lods = {straightLod(2, 0.1f)};
  file.blades = {a, b};
  return file;
}

/** Parsing `doc` must fail with exactly `message` (after the "test.json: " prefix). */
void expectRejected(const json& doc, const std::string& message) {
  try {
    (void)parseBladeModels(doc, "test.json");
    ADD_FAILURE() << "accepted; expected: " << message;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "test.json: " + message);
  }
}

/** The sample document edited by `edit`. */
json edited(const std::function<void(json&)>& edit) {
  json doc = toJson(sampleFile());
  edit(doc);
  return doc;
}

TEST(BladeModelFile, SaveLoadRoundTripIsExact) {
  const test::TempDir dir;
  const BladeModelFile file = sampleFile();
  saveBladeModels(dir / "grass.json", file);
  expectEqual(loadBladeModels(dir / "grass.json"), file);
  // And the document itself is stable: load → save gives the same text.
  saveBladeModels(dir / "again.json", loadBladeModels(dir / "grass.json"));
  std::ifstream first(dir / "grass.json");
  std::ifstream second(dir / "again.json");
  const std::string a((std::istreambuf_iterator<char>(first)), std::istreambuf_iterator<char>());
  const std::string b((std::istreambuf_iterator<char>(second)), std::istreambuf_iterator<char>());
  EXPECT_EQ(a, b);
  EXPECT_NE(a.find("\"kind\": \"sylva-blade-models\""), std::string::npos);
}

TEST(BladeModelFile, OptionalFieldsMayBeLeftOut) {
  const json doc = edited([](json& d) {
    d.erase("generator");
    d["blades"][0].erase("colour");
    d["blades"][0].erase("source");
  });
  const BladeModelFile file = parseBladeModels(doc, "test.json");
  EXPECT_EQ(file.generator, "");
  EXPECT_FALSE(file.blades[0].hasColour);
  EXPECT_EQ(file.blades[0].source.file, "");
  EXPECT_EQ(file.blades[0].source.motionFrames, 1);
}

TEST(BladeModelFile, EnvelopeErrors) {
  expectRejected(json::array(), "/: expected an object, got array");
  expectRejected(edited([](json& d) { d.erase("version"); }), "/version: missing field");
  expectRejected(edited([](json& d) { d["version"] = 2; }), "/version: must be 1");
  expectRejected(edited([](json& d) { d["kind"] = "sylva-project"; }),
                 "/kind: expected \"sylva-blade-models\", got \"sylva-project\"");
  expectRejected(edited([](json& d) { d.erase("kind"); }), "/kind: missing field");
  expectRejected(edited([](json& d) { d["extra"] = 1; }), "/extra: unknown field");
  expectRejected(edited([](json& d) { d["generator"] = 3; }), "/generator: expected a string, got number");
  expectRejected(edited([](json& d) { d["blades"] = json::array(); }),
                 "/blades: expected at least 1 entries, got 0");
  expectRejected(edited([](json& d) { d["blades"] = json::object(); }),
                 "/blades: expected an array, got object");
}

TEST(BladeModelFile, TooManyBladesAreRejected) {
  json doc = toJson(sampleFile());
  const json blade = doc["blades"][1];
  doc["blades"] = json::array();
  for (int i = 0; i < 65537; ++i) {
    doc["blades"].push_back(blade);
  }
  expectRejected(doc, "/blades: 65537 entries is more than 65536");
}

TEST(BladeModelFile, BladeErrorsNameTheirPath) {
  expectRejected(edited([](json& d) { d["blades"][1]["wind"] = 1; }), "/blades/1/wind: unknown field");
  expectRejected(edited([](json& d) { d["blades"][1].erase("name"); }), "/blades/1/name: missing field");
  expectRejected(edited([](json& d) { d["blades"][1]["name"] = ""; }), "/blades/1/name: must not be empty");
  expectRejected(edited([](json& d) {
                   d["blades"][0]["bendAxis"] = {1.0, 0.0, 0.5};
                 }),
                 "/blades/0/bendAxis: expected a unit vector (length 1 ± 0.001), got length 1.11803");
  expectRejected(edited([](json& d) {
                   d["blades"][0]["bendAxis"] = {1.0, 0.0};
                 }),
                 "/blades/0/bendAxis: expected [x, y, z]");
  expectRejected(edited([](json& d) { d["blades"][0]["colour"][1] = 1.5; }),
                 "/blades/0/colour/1: 1.5 is more than 1");
  expectRejected(edited([](json& d) { d["blades"][0]["source"]["camera"] = 1; }),
                 "/blades/0/source/camera: unknown field");
  expectRejected(edited([](json& d) { d["blades"][0]["source"].erase("mu"); }),
                 "/blades/0/source/mu: missing field");
  expectRejected(edited([](json& d) { d["blades"][0]["source"]["mu"] = 2; }),
                 "/blades/0/source/mu: 2 is more than 1");
  expectRejected(edited([](json& d) { d["blades"][0]["source"]["frame"] = 1.5; }),
                 "/blades/0/source/frame: expected a whole number, got 1.5");
  expectRejected(edited([](json& d) { d["blades"][0]["source"]["motionFrames"] = 0; }),
                 "/blades/0/source/motionFrames: 0 is less than 1");
  expectRejected(edited([](json& d) { d["blades"][0]["source"]["intrinsics"]["fx"] = 0; }),
                 "/blades/0/source/intrinsics/fx: 0 is less than 1e-06");
  expectRejected(edited([](json& d) { d["blades"][0]["source"]["relativeDepth"] = 1; }),
                 "/blades/0/source/relativeDepth: expected true or false, got number");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"] = json::array(); }),
                 "/blades/0/lods: expected at least 1 entries, got 0");
}

TEST(BladeModelFile, LevelErrorsNameTheirPath) {
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][1]["uv"] = 1; }),
                 "/blades/0/lods/1/uv: unknown field");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][2]["knots"] = 5; }),
                 "/blades/0/lods/2/positions: expected 5 entries ('knots'), got 4");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][2]["widths"].erase(0); }),
                 "/blades/0/lods/2/widths: expected 4 entries ('knots'), got 3");
  expectRejected(edited([](json& d) {
                   d["blades"][0]["lods"][2]["normals"].push_back({0, 0, 1});
                 }),
                 "/blades/0/lods/2/normals: expected 4 entries ('knots'), got 5");
  expectRejected(edited([](json& d) { d["blades"][1]["lods"][0]["knots"] = 1; }),
                 "/blades/1/lods/0/knots: 1 is less than 2");
  expectRejected(edited([](json& d) { d["blades"][1]["lods"][0]["knots"] = 4097; }),
                 "/blades/1/lods/0/knots: 4097 is more than 4096");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][1] = d["blades"][0]["lods"][0]; }),
                 "/blades/0/lods/1/knots: knot counts must decrease from level to level (16 after 16)");
  expectRejected(edited([](json& d) { std::swap(d["blades"][0]["lods"][1], d["blades"][0]["lods"][2]); }),
                 "/blades/0/lods/2/knots: knot counts must decrease from level to level (8 after 4)");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][0]["widths"][5] = -0.001; }),
                 "/blades/0/lods/0/widths/5: -0.001 is less than 0");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][0]["widths"][5] = "wide"; }),
                 "/blades/0/lods/0/widths/5: expected a number, got string");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][0]["widths"][5] = 1e300; }),
                 "/blades/0/lods/0/widths/5: expected a finite number ≥ 0");
  expectRejected(edited([](json& d) {
                   d["blades"][0]["lods"][0]["widths"][5] = std::numeric_limits<double>::quiet_NaN();
                 }),
                 "/blades/0/lods/0/widths/5: expected a finite number");
  expectRejected(edited([](json& d) {
                   d["blades"][0]["lods"][0]["positions"][2][1] = std::numeric_limits<double>::infinity();
                 }),
                 "/blades/0/lods/0/positions/2/1: expected a finite number");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][0]["positions"][2][0] = 5000; }),
                 "/blades/0/lods/0/positions/2/0: 5000 is more than 1000");
  expectRejected(edited([](json& d) { d["blades"][0]["lods"][0]["positions"][2] = "up"; }),
                 "/blades/0/lods/0/positions/2: expected [x, y, z]");
  expectRejected(edited([](json& d) {
                   d["blades"][0]["lods"][0]["normals"][7] = {0.0, 0.0, 0.99};
                 }),
                 "/blades/0/lods/0/normals/7: expected a unit vector (length 1 ± 0.001), got length 0.99");
  expectRejected(edited([](json& d) {
                   d["blades"][0]["lods"][0]["normals"][7] = {0.0, 0.0, 0.0};
                 }),
                 "/blades/0/lods/0/normals/7: expected a unit vector (length 1 ± 0.001), got length 0");
}

TEST(BladeModelFile, SaveRefusesWhatCouldNotBeLoaded) {
  const test::TempDir dir;
  BladeModelFile file = sampleFile();
  file.blades[0].lods[0].widths[2] = std::numeric_limits<float>::quiet_NaN();
  try {
    saveBladeModels(dir / "bad.json", file);
    FAIL() << "saved a NaN width";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "bad.json").string() + ": /blades/0/lods/0/widths/2: expected a finite number");
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.json"));
}

TEST(BladeModelFile, BrokenAndMissingFiles) {
  const test::TempDir dir;
  { std::ofstream(dir / "broken.json") << "{\"version\": 1,\n  \"kind\": "; }
  try {
    (void)loadBladeModels(dir / "broken.json");
    FAIL() << "loaded broken JSON";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind((dir / "broken.json").string() + ":2:", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("invalid JSON"), std::string::npos) << e.what();
  }
  try {
    (void)loadBladeModels(dir / "missing.json");
    FAIL() << "loaded a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "missing.json").string() + ": cannot open file (missing or unreadable)");
  }
  // A valid JSON document of the wrong kind names the file too.
  { std::ofstream(dir / "other.json") << "{\"version\": 1, \"kind\": \"sylva-project\", \"blades\": []}"; }
  try {
    (void)loadBladeModels(dir / "other.json");
    FAIL() << "loaded another kind of file";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "other.json").string() +
                                         ": /kind: expected \"sylva-blade-models\", got \"sylva-project\"");
  }
}

TEST(BladeModelFile, FuzzSeedsAreWhatTheirNamesSay) {
  // The fuzz corpus (fuzz/corpus/blade_models) starts from one valid file; the others fail for their reason.
  const std::string dir = "fuzz/corpus/blade_models/";
  const BladeModelFile valid = loadBladeModels(test::sourcePath(dir + "valid-two-blades.json"));
  ASSERT_EQ(valid.blades.size(), 2u);
  EXPECT_EQ(valid.blades[0].lods.size(), 3u);
  const std::pair<const char*, const char*> broken[] = {
      {"non-unit-normal.json", "/blades/0/lods/1/normals/2: expected a unit vector"},
      {"knots-not-decreasing.json", "/blades/0/lods/2/positions: expected 4 entries"},
      {"version-2.json", "/version: must be 1"},
      {"truncated.json", "invalid JSON"}};
  for (const auto& [name, message] : broken) {
    try {
      (void)loadBladeModels(test::sourcePath(dir + name));
      ADD_FAILURE() << name << " loaded";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

TEST(BladeModel, LengthMaxWidthAndLevelChoice) {
  const BladeModel blade = sampleFile().blades[0];
  // The finest level: straight 0.3 m except knot 3, moved off the line.
  double expected = 0.0;
  for (std::size_t k = 1; k < 16; ++k) {
    expected += glm::length(glm::dvec3(blade.lods[0].positions[k] - blade.lods[0].positions[k - 1]));
  }
  EXPECT_NEAR(blade.length(), expected, 1e-6);
  EXPECT_GT(blade.length(), 0.3f);
  EXPECT_FLOAT_EQ(blade.maxWidth(), 0.01f);
  EXPECT_EQ(blade.lodForKnots(100).knotCount(), 16u);
  EXPECT_EQ(blade.lodForKnots(16).knotCount(), 16u);
  EXPECT_EQ(blade.lodForKnots(15).knotCount(), 8u);
  EXPECT_EQ(blade.lodForKnots(8).knotCount(), 8u);
  EXPECT_EQ(blade.lodForKnots(5).knotCount(), 4u);
  EXPECT_EQ(blade.lodForKnots(2).knotCount(), 4u) << "the coarsest level when every level has more";
  EXPECT_EQ(blade.lodForKnots(0).knotCount(), 4u);
  BladeModel empty;
  empty.name = "empty";
  EXPECT_EQ(empty.length(), 0.0f);
  EXPECT_EQ(empty.maxWidth(), 0.0f);
  EXPECT_THROW((void)empty.lodForKnots(4), Error);
}

} // namespace
} // namespace sylva::blades
