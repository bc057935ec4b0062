#include <sylva/terrain/TerrainMaps.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>

#include "TempDir.hpp"
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace sylva::terrain {
namespace {

using test::kNaN;

glm::vec3 normalOf(const Image& normals, int x, int y) {
  return {normals.get(x, y, 0), normals.get(x, y, 1), normals.get(x, y, 2)};
}

void expectVec(const glm::vec3& actual, const glm::vec3& expected, float tolerance,
               const std::string& where) {
  EXPECT_NEAR(actual.x, expected.x, tolerance) << where;
  EXPECT_NEAR(actual.y, expected.y, tolerance) << where;
  EXPECT_NEAR(actual.z, expected.z, tolerance) << where;
}

/** h = a + b·x + c·z sampled at x = i·sx, z = j·sz. */
HeightField planeField(int w, int h, float sx, float sz, float a, float b, float c) {
  HeightField field(w, h, sx, sz);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      field.at(i, j) = a + b * static_cast<float>(i) * sx + c * static_cast<float>(j) * sz;
    }
  }
  return field;
}

TEST(TerrainMaps, SobelIsExactForPlanesInsideAndHalvesTheSlopeAtClampedBorders) {
  const HeightField field = planeField(8, 6, 2.0f, 0.5f, 10.0f, 0.75f, -1.5f);
  const Image normals = sobelNormalMap(field);
  ASSERT_EQ(normals.width(), 8);
  ASSERT_EQ(normals.height(), 6);
  ASSERT_EQ(normals.channels(), 3);
  ASSERT_EQ(normals.type(), PixelType::F32);
  const glm::vec3 exact = glm::normalize(glm::vec3(-0.75f, 1.0f, 1.5f));
  for (int y = 1; y < 5; ++y) {
    for (int x = 1; x < 7; ++x) {
      expectVec(normalOf(normals, x, y), exact, 1e-6f, "interior");
    }
  }
  // Left column, interior row: h(−1, ·) clamps to h(0, ·), so gx = b/2 while gz stays exact.
  expectVec(normalOf(normals, 0, 3), glm::normalize(glm::vec3(-0.375f, 1.0f, 1.5f)), 1e-6f, "left edge");
  // Corner: both gradients halve.
  expectVec(normalOf(normals, 7, 5), glm::normalize(glm::vec3(-0.375f, 1.0f, 0.75f)), 1e-6f, "corner");
}

TEST(TerrainMaps, SobelConstantBorderFollowsThePaper) {
  // h = i + 3j, spacing 1; outside neighbours read 0 (the paper's constant).
  HeightField field(3, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      field.at(i, j) = static_cast<float>(i + 3 * j);
    }
  }
  SobelOptions options;
  options.border = BorderMode::Constant;
  const Image normals = sobelNormalMap(field, options);
  expectVec(normalOf(normals, 1, 1), glm::normalize(glm::vec3(-1.0f, 1.0f, -3.0f)), 1e-6f, "centre");
  // Pixel (0, 0): neighbours h(a, b) with a or b = −1 read 0.
  // gx = [h(1,−1) + 2h(1,0) + h(1,1) − 0] / 8 = [0 + 2 + 4] / 8; gz = [0 + 2·3 + 4 − 0] / 8.
  expectVec(normalOf(normals, 0, 0), glm::normalize(glm::vec3(-6.0f / 8.0f, 1.0f, -10.0f / 8.0f)), 1e-6f,
            "corner");
  options.constantHeight = 100.0f;
  const Image high = sobelNormalMap(field, options);
  EXPECT_GT(normalOf(high, 0, 0).x, 0.5f) << "a high wall outside tilts the border normal away";
}

TEST(TerrainMaps, SobelTreatsAbsentSamples) {
  HeightField field = planeField(5, 5, 1.0f, 1.0f, 0.0f, 1.0f, 0.0f); // h = x
  field.at(3, 2) = kNaN;
  const Image normals = sobelNormalMap(field);
  expectVec(normalOf(normals, 3, 2), {0.0f, 1.0f, 0.0f}, 0.0f, "absent centre is flat");
  // Pixel (2, 2): its +x neighbour (3, 2) reads the centre h = 2:
  // gx = [h(3,1) + 2·2 + h(3,3) − h(1,1) − 2h(1,2) − h(1,3)] / 8 = [3 + 4 + 3 − 1 − 2 − 1] / 8 = 6/8.
  expectVec(normalOf(normals, 2, 2), glm::normalize(glm::vec3(-0.75f, 1.0f, 0.0f)), 1e-6f, "next to a hole");
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 5; ++x) {
      EXPECT_NEAR(glm::length(normalOf(normals, x, y)), 1.0f, 1e-6f);
    }
  }
}

TEST(TerrainMaps, SplatWeightRamps) {
  SplatLayer layer{"grass", 100.0f, 200.0f, 0.0f, 30.0f, 20.0f, 10.0f};
  EXPECT_FLOAT_EQ(splatWeight(layer, 150.0f, 10.0f), 1.0f);
  EXPECT_FLOAT_EQ(splatWeight(layer, 100.0f, 10.0f), 0.5f) << "the limit is the middle of the soft edge";
  EXPECT_FLOAT_EQ(splatWeight(layer, 90.0f, 10.0f), 0.0f);
  EXPECT_FLOAT_EQ(splatWeight(layer, 110.0f, 10.0f), 1.0f);
  EXPECT_FLOAT_EQ(splatWeight(layer, 205.0f, 10.0f), 0.25f);
  EXPECT_FLOAT_EQ(splatWeight(layer, 150.0f, 30.0f), 0.5f);
  EXPECT_FLOAT_EQ(splatWeight(layer, 100.0f, 30.0f), 0.25f);
  layer.heightBlend = 0.0f;
  layer.slopeBlend = 0.0f;
  EXPECT_EQ(splatWeight(layer, 100.0f, 30.0f), 1.0f) << "hard edges include their limits";
  EXPECT_EQ(splatWeight(layer, 99.99f, 10.0f), 0.0f);
  EXPECT_EQ(splatWeight(layer, 150.0f, 30.01f), 0.0f);
}

TEST(TerrainMaps, SplatPagesHoldFourLayersEachAndSumToOne) {
  HeightField field = planeField(16, 12, 1.0f, 1.0f, 0.0f, 5.0f, 0.0f); // 0..75 m, slope atan(5) ≈ 78.7°
  field.at(3, 3) = kNaN;
  const Image normals = sobelNormalMap(field);
  for (const int count : {1, 3, 4, 5, 8, 9, 64}) {
    std::vector<SplatLayer> layers;
    for (int k = 0; k < count; ++k) {
      // Overlapping height bands so several layers mix at most samples.
      const float lo = static_cast<float>(k) * 80.0f / count - 10.0f;
      layers.push_back({"layer" + std::to_string(k), lo, lo + 30.0f, 0.0f, 90.0f, 5.0f, 0.0f});
    }
    const std::vector<Image> pages = splatMap(field, normals, layers);
    ASSERT_EQ(pages.size(), static_cast<std::size_t>((count + 3) / 4)) << count;
    for (const Image& page : pages) {
      ASSERT_EQ(page.channels(), 4);
      ASSERT_EQ(page.type(), PixelType::F32);
      ASSERT_EQ(page.width(), 16);
    }
    for (int y = 0; y < 12; ++y) {
      for (int x = 0; x < 16; ++x) {
        float sum = 0.0f;
        for (int l = 0; l < static_cast<int>(pages.size()) * 4; ++l) {
          const float w = pages[static_cast<std::size_t>(l / 4)].get(x, y, l % 4);
          if (l >= count) {
            ASSERT_EQ(w, 0.0f) << "unused channel " << l;
          }
          ASSERT_GE(w, 0.0f);
          sum += w;
        }
        if (x == 3 && y == 3) {
          EXPECT_EQ(sum, 0.0f) << "absent height has no texture";
        } else {
          ASSERT_NEAR(sum, 1.0f, 1e-5f) << count << " layers at " << x << "," << y;
        }
      }
    }
  }
}

TEST(TerrainMaps, DefaultLayersPickSandGrassSnowAndRock) {
  // Four flat terraces (0, 30, 60, 100 m) and a steep ramp between the last two.
  HeightField field(40, 8, 1.0f, 1.0f);
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 40; ++i) {
      field.at(i, j) = i < 10   ? 0.0f
                       : i < 20 ? 30.0f
                       : i < 28 ? 60.0f
                       : i < 32 ? 60.0f + (i - 27) * 8.0f
                                : 100.0f;
    }
  }
  const std::vector<SplatLayer> layers = defaultSplatLayers(0.0f, 100.0f);
  ASSERT_EQ(layers.size(), 4u);
  const std::vector<Image> pages = splatMap(field, sobelNormalMap(field), layers);
  ASSERT_EQ(pages.size(), 1u);
  const auto dominant = [&](int x) {
    int best = 0;
    for (int c = 1; c < 4; ++c) {
      best = pages[0].get(x, 4, c) > pages[0].get(x, 4, best) ? c : best;
    }
    return layers[static_cast<std::size_t>(best)].name;
  };
  EXPECT_EQ(dominant(4), "sand");
  EXPECT_EQ(dominant(15), "grass");
  EXPECT_EQ(dominant(30), "rock");
  EXPECT_EQ(dominant(36), "snow");
  EXPECT_FLOAT_EQ(pages[0].get(4, 4, 0), 1.0f);
}

TEST(TerrainMaps, UncoveredSamplesFallBackToTheFirstLayer) {
  const HeightField field(4, 4, 1.0f, 1.0f, 500.0f);
  const std::vector<SplatLayer> layers = {{"low", 0.0f, 10.0f, 0.0f, 90.0f, 0.0f, 0.0f},
                                          {"mid", 20.0f, 30.0f, 0.0f, 90.0f, 0.0f, 0.0f}};
  const std::vector<Image> pages = splatMap(field, sobelNormalMap(field), layers);
  EXPECT_EQ(pages[0].get(2, 2, 0), 1.0f);
  EXPECT_EQ(pages[0].get(2, 2, 1), 0.0f);
}

TEST(TerrainMaps, SplatRejectsBadInputs) {
  const HeightField field(4, 4);
  const Image normals = sobelNormalMap(field);
  EXPECT_THROW(splatMap(field, normals, {}), Error);
  EXPECT_THROW(splatMap(field, normals, std::vector<SplatLayer>(65, SplatLayer{"x"})), Error);
  const std::vector<SplatLayer> one = {{"a"}};
  EXPECT_THROW(splatMap(field, Image(3, 4, 3, PixelType::F32), one), Error);
  EXPECT_THROW(splatMap(field, Image(4, 4, 3, PixelType::U8), one), Error);
  EXPECT_NO_THROW(splatMap(field, normals, one));
}

TEST(TerrainMaps, LayerJsonRoundTripAndFieldErrors) {
  test::TempDir dir;
  const std::vector<SplatLayer> layers = defaultSplatLayers(236.0f, 1076.0f);
  saveSplatLayers(dir / "layers.json", layers);
  EXPECT_EQ(loadSplatLayers(dir / "layers.json"), layers);
  const nlohmann::json json = loadJsonFile(dir / "layers.json");
  EXPECT_EQ(json.at("version"), 1);

  const auto expectError = [&](const nlohmann::json& bad, const std::string& reason) {
    writeTextFile(dir / "bad.json", bad.dump());
    try {
      loadSplatLayers(dir / "bad.json");
      ADD_FAILURE() << "expected an error for " << bad.dump();
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("bad.json: "), std::string::npos) << message;
      EXPECT_NE(message.find(reason), std::string::npos) << "wanted '" << reason << "' in: " << message;
    }
  };
  nlohmann::json bad = json;
  bad["layers"][1]["maxSlope"] = -5.0;
  expectError(bad, "/layers/1/maxSlope: -5 is below minSlope");
  bad = json;
  bad["layers"][2]["colour"] = "white";
  expectError(bad, "/layers/2/colour: unknown field");
  bad = json;
  bad["layers"][0]["minHeight"] = "low";
  expectError(bad, "/layers/0/minHeight: expected a number, got string");
  bad = json;
  bad["layers"][3]["name"] = "sand";
  expectError(bad, "/layers/3/name: duplicate layer name 'sand'");
  bad = json;
  bad["layers"][3].erase("name");
  expectError(bad, "/layers/3/name: missing field");
  bad = json;
  bad["layers"][0]["heightBlend"] = -1.0;
  expectError(bad, "/layers/0/heightBlend: -1 must be >= 0 metres");
  bad = json;
  bad["layers"] = nlohmann::json::array();
  expectError(bad, "/layers: expected at least 1 entries, got 0");
  bad = json;
  bad.erase("version");
  expectError(bad, "/version: missing field");
  bad = json;
  bad["extra"] = 1;
  expectError(bad, "/extra: unknown field");
}

TEST(TerrainMaps, SeaLevelRulesPutSandOnCoastsAndNoGrassUnderWater) {
  // A coastal profile: sea floor at -200 m rising to a 900 m hill at a gentle 5.7 degrees (10 m per 100 m).
  HeightField field(111, 3, 100.0f, 100.0f);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 111; ++i) {
      field.at(i, j) = -200.0f + 10.0f * static_cast<float>(i);
    }
  }
  const std::vector<SplatLayer> layers = defaultSplatLayers(-200.0f, 900.0f, 0.0f);
  ASSERT_EQ(layers.size(), 4u);
  ASSERT_EQ(layers[0].name, "sand");
  ASSERT_EQ(layers[1].name, "grass");
  const std::vector<Image> pages = splatMap(field, sobelNormalMap(field), layers);
  for (int i = 1; i < 110; ++i) {
    const float h = field.at(i, 1);
    const float sand = pages[0].get(i, 1, 0);
    const float grass = pages[0].get(i, 1, 1);
    if (h < 0.0f) {
      EXPECT_EQ(grass, 0.0f) << "grass under water at " << h << " m";
      EXPECT_GT(sand, 0.99f) << "sea floor at " << h << " m";
    }
    if (h >= 0.0f && h <= 10.0f) {
      EXPECT_GT(sand, 0.5f) << "the beach at " << h << " m is sand";
    }
    if (h >= 100.0f && h <= 500.0f) {
      EXPECT_GT(grass, 0.99f) << "land at " << h << " m is grass";
    }
  }
  // Without a sea level the lowest 12 % are sand, wherever 0 m is.
  const std::vector<SplatLayer> inland = defaultSplatLayers(-200.0f, 900.0f);
  EXPECT_NEAR(inland[0].maxHeight, -200.0f + 0.12f * 1100.0f, 1e-3f);
}

TEST(TerrainMaps, VerticalScaleKeepsRulesInTrueMetresAndDegrees) {
  // Splat of an exaggerated field with verticalScale = e equals the splat of the true field (tolerance for
  // the float round trip through the normals): rules see true heights and true slopes.
  HeightField field(40, 30, 5.0f, 5.0f);
  for (int j = 0; j < 30; ++j) {
    for (int i = 0; i < 40; ++i) {
      field.at(i, j) =
          8.0f * std::sin(0.2f * static_cast<float>(i)) + 0.5f * static_cast<float>(j); // <= 18 degrees
    }
  }
  const std::vector<SplatLayer> layers = defaultSplatLayers(-8.0f, 23.0f, 0.0f);
  const std::vector<Image> truth = splatMap(field, sobelNormalMap(field), layers);
  for (const float e : {0.5f, 4.0f}) {
    HeightField tall = field;
    for (float& h : tall.samples()) {
      h *= e;
    }
    const std::vector<Image> scaled = splatMap(tall, sobelNormalMap(tall), layers, e);
    float worst = 0.0f;
    for (int j = 0; j < 30; ++j) {
      for (int i = 0; i < 40; ++i) {
        for (int c = 0; c < 4; ++c) {
          worst = std::max(worst, std::abs(scaled[0].get(i, j, c) - truth[0].get(i, j, c)));
        }
      }
    }
    EXPECT_LT(worst, 2e-3f) << "exaggeration " << e;
    // Without the scale the exaggerated slopes would turn far more of it to rock.
    const std::vector<Image> naive = splatMap(tall, sobelNormalMap(tall), layers);
    double rockTruth = 0.0;
    double rockNaive = 0.0;
    for (int j = 0; j < 30; ++j) {
      for (int i = 0; i < 40; ++i) {
        rockTruth += truth[0].get(i, j, 3);
        rockNaive += naive[0].get(i, j, 3);
      }
    }
    if (e > 1.0f) {
      EXPECT_GT(rockNaive, rockTruth + 10.0) << "the test field must have slopes the scale changes";
    }
  }
  EXPECT_THROW(splatMap(field, sobelNormalMap(field), layers, 0.0f), Error);
}

} // namespace
} // namespace sylva::terrain
