// The shore water on the GPU, seen from straight above a plane that slopes up to the east, half under water:
// dry ground beyond the wet strip keeps the background, deep water is drawn, the band weight the shader
// writes (debug view) matches the CPU shoreBand per pixel, the swash animates in the band only, and equal
// times give equal pixels.
#include <sylva/core/Error.hpp>
#include <sylva/render/ImageCompare.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/gpu/ShoreWater.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>

#include "GlTest.hpp"
#include "TempDir.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

namespace sylva::scene {
namespace {

using ShoreWaterTest = test::GlTest;

constexpr int kSize = 128;       // pixels
constexpr float kExtent = 64.0f; // metres, 65 × 65 samples 1 m apart
constexpr float kScale = 2.0f;   // vertical exaggeration of the drawn field
const glm::vec4 kBackground(0.5f, 0.2f, 0.6f, 1.0f);

/** True heights 0.1 · (x − 32) + 0.3 · sin(z / 5) (the waterline wobbles around x = 32), times kScale. */
terrain::HeightField slope() {
  terrain::HeightField field(65, 65, 1.0f, 1.0f);
  for (int j = 0; j < 65; ++j) {
    for (int i = 0; i < 65; ++i) {
      field.at(i, j) =
          kScale * (0.1f * (static_cast<float>(i) - 32.0f) + 0.3f * std::sin(static_cast<float>(j) / 5.0f));
    }
  }
  return field;
}

ShoreSettings settings() {
  ShoreSettings s;
  s.level = 0.0f;
  s.band = 2.0f;
  s.wet = 0.5f;
  s.tile = 12.0f;
  s.folding = test::sourcePath("data/folding/beach.json").string();
  return s;
}

/** Straight down on the footprint, north up: pixel (x, y) (file order) shows world (x + ½, y + ½) · ½ m. */
render::Camera topCamera() {
  render::Camera c;
  c.position = glm::vec3(0.5f * kExtent, 100.0f, 0.5f * kExtent);
  c.target = glm::vec3(0.5f * kExtent, 0.0f, 0.5f * kExtent);
  c.up = glm::vec3(0.0f, 0.0f, -1.0f);
  c.orthoHeight = 0.5f * kExtent;
  c.nearPlane = 1.0f;
  c.farPlane = 200.0f;
  return c;
}

glm::vec2 pixelWorld(int x, int y) {
  const float m = kExtent / static_cast<float>(kSize);
  return {(static_cast<float>(x) + 0.5f) * m, (static_cast<float>(y) + 0.5f) * m};
}

Image render(ShoreWater& water, render::RenderTarget& target, double time, ShoreWaterView view) {
  water.update(time);
  target.begin(kBackground);
  water.setView(view);
  water.draw(topCamera(), kSize, kSize, time, render::Environment{});
  return target.readColor();
}

bool isBackground(const Image& image, int x, int y) {
  for (int c = 0; c < 4; ++c) {
    if (std::lround(image.get(x, y, c) * 255.0f) != std::lround(kBackground[c] * 255.0f)) {
      return false;
    }
  }
  return true;
}

TEST_F(ShoreWaterTest, BandWeightMatchesTheCpuRule) {
  const terrain::HeightField field = slope();
  const ShoreSettings s = settings();
  ShoreWater water(shaders(), field, kScale, s);
  render::RenderTarget target(kSize, kSize);
  const Image image = render(water, target, 0.0, ShoreWaterView::Band);
  int compared = 0;
  int fading = 0;
  int dry = 0;
  float worst = 0.0f;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const glm::vec2 p = pixelWorld(x, y);
      const float depth = waterDepth(field, kScale, s.level, p.x, p.y);
      if (std::abs(depth + s.wet) < 0.01f) {
        continue; // on the edge of the wet strip
      }
      if (depth < -s.wet) {
        EXPECT_TRUE(isBackground(image, x, y)) << "dry pixel " << x << ", " << y << " was drawn";
        ++dry;
        continue;
      }
      const float expected = shoreBand(depth, s);
      const float got = image.get(x, y, 0);
      worst = std::max(worst, std::abs(got - expected));
      EXPECT_NEAR(got, expected, 2.5f / 255.0f) << x << ", " << y << " depth " << depth;
      ++compared;
      fading += expected > 0.05f && expected < 0.95f ? 1 : 0;
    }
  }
  std::printf("band: %d pixels compared (%d fading), %d dry; worst difference %.4f\n", compared, fading, dry,
              worst);
  EXPECT_GT(fading, 1500);
  EXPECT_GT(dry, 5000);
}

TEST_F(ShoreWaterTest, DrawsWaterKeepsDryGroundAndAnimatesTheBandOnly) {
  const terrain::HeightField field = slope();
  const ShoreSettings s = settings();
  ShoreWater water(shaders(), field, kScale, s);
  render::RenderTarget target(kSize, kSize);
  // 1.3 s into the 4 s swash the water has run up the beach; at 0 s it rests.
  const Image rest = render(water, target, 0.0, ShoreWaterView::Shaded);
  const Image up = render(water, target, 1.3, ShoreWaterView::Shaded);
  const Image other = render(water, target, 2.9, ShoreWaterView::Shaded);
  const Image again = render(water, target, 1.3, ShoreWaterView::Shaded);
  EXPECT_TRUE(up == again) << "the same time gave different pixels";
  EXPECT_FALSE(other == up);

  int deep = 0;
  int moved = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const glm::vec2 p = pixelWorld(x, y);
      const float depth = waterDepth(field, kScale, s.level, p.x, p.y);
      if (depth < -s.wet - 0.01f) {
        EXPECT_TRUE(isBackground(up, x, y)) << "dry pixel " << x << ", " << y << " was drawn";
      }
      if (depth > s.band + 0.01f) {
        // Water, not the background: bluer than the purple behind it and identical at both times.
        EXPECT_FALSE(isBackground(up, x, y));
        EXPECT_GT(up.get(x, y, 2), up.get(x, y, 0) + 0.05f) << x << ", " << y;
        for (int c = 0; c < 4; ++c) {
          EXPECT_EQ(rest.get(x, y, c), up.get(x, y, c)) << "deep water moved at " << x << ", " << y;
        }
        ++deep;
      }
      bool differs = false;
      for (int c = 0; c < 3; ++c) {
        differs = differs || rest.get(x, y, c) != up.get(x, y, c);
      }
      if (differs) {
        EXPECT_GT(shoreBand(depth, s), 0.0f) << "pixel " << x << ", " << y << " changed outside the band";
        ++moved;
      }
    }
  }
  std::printf("deep-water pixels %d, swash pixels that moved %d\n", deep, moved);
  EXPECT_GT(deep, 2000);
  EXPECT_GT(moved, 300);
  if (const char* dir = std::getenv("SYLVA_SHORE_OUT")) {
    savePng(std::string(dir) + "/shore-rest.png", rest);
    savePng(std::string(dir) + "/shore-up.png", up);
  }
}

/** True heights of a round lake 70 m across in a 256 m square, its shore gently wobbling: the waterline runs
 * in every direction, so the swash is laid along all eight axes. */
terrain::HeightField lake() {
  terrain::HeightField field(257, 257, 1.0f, 1.0f);
  for (int j = 0; j < 257; ++j) {
    for (int i = 0; i < 257; ++i) {
      const float x = static_cast<float>(i);
      const float z = static_cast<float>(j);
      const float r = std::hypot(x - 128.0f, z - 128.0f);
      field.at(i, j) = 0.06f * (r - 70.0f) + 0.5f * std::sin(x / 11.0f) * std::cos(z / 17.0f);
    }
  }
  return field;
}

terrain::QuadtreeConfig lakeQuadtree() {
  terrain::QuadtreeConfig config;
  config.rootSize = 128.0f;
  config.maxDepth = 4;
  config.patchTessLevel = 16;
  return config;
}

/** Terrain, then (optionally) the shore water over it, as a scene would draw them. */
Image lakeFrame(terrain::TerrainScene& scene, ShoreWater* water, const render::Camera& camera, int width,
                int height, double time) {
  render::RenderTarget target(width, height);
  terrain::TerrainDrawOptions options = scene.drawOptions(camera, 0.3f);
  options.waterLevel.reset(); // the scene draws its own water
  target.begin(glm::vec4(options.environment.fogColor, 1.0f));
  scene.update(camera, target.aspect());
  scene.draw(camera, width, height, time, nullptr, options);
  if (water != nullptr) {
    water->update(time);
    water->draw(camera, width, height, time, options.environment);
  }
  return target.readColor();
}

/** Straight down on the lake's 256 m square, north up, one pixel per metre at 256 pixels. */
render::Camera lakeTopCamera() {
  render::Camera camera;
  camera.position = glm::vec3(128.0f, 200.0f, 128.0f);
  camera.target = glm::vec3(128.0f, 0.0f, 128.0f);
  camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
  camera.orthoHeight = 128.0f;
  camera.nearPlane = 10.0f;
  camera.farPlane = 400.0f;
  return camera;
}

/** Standing on the lake's south shore, looking along it (the documentation's pictures). */
render::Camera lakeShoreCamera() {
  render::Camera view;
  view.position = glm::vec3(122.0f, 3.5f, 212.0f);
  view.target = glm::vec3(150.0f, -1.0f, 190.0f);
  view.fovY = glm::radians(55.0f);
  view.nearPlane = 0.1f;
  view.farPlane = 600.0f;
  return view;
}

TEST_F(ShoreWaterTest, OverTheTerrainOnlyWaterAndTheWetStripChange) {
  const float scale = 1.5f;
  terrain::HeightField truth = lake();
  terrain::TerrainSceneOptions options;
  options.exaggeration = scale;
  options.seaLevel = 0.0f; // sand on the coast
  terrain::TerrainScene scene(shaders(), truth, lakeQuadtree(), options);
  ShoreSettings s = settings();
  s.level = 0.0f;
  ShoreWater water(shaders(), scene.field(), scale, s);
  const render::Camera camera = lakeTopCamera();
  constexpr int kLakeSize = 256; // one pixel per metre
  const Image dry = lakeFrame(scene, nullptr, camera, kLakeSize, kLakeSize, 1.0);
  const Image wet = lakeFrame(scene, &water, camera, kLakeSize, kLakeSize, 1.0);
  int changedDry = 0;
  int waterDrawn = 0;
  for (int y = 0; y < kLakeSize; ++y) {
    for (int x = 0; x < kLakeSize; ++x) {
      const float depth = waterDepth(scene.field(), scale, s.level, static_cast<float>(x) + 0.5f,
                                     static_cast<float>(y) + 0.5f);
      bool same = true;
      for (int c = 0; c < 3; ++c) {
        same = same && dry.get(x, y, c) == wet.get(x, y, c);
      }
      if (depth < -s.wet - 0.02f) {
        changedDry += same ? 0 : 1;
      } else if (depth > 0.05f) {
        waterDrawn += same ? 0 : 1;
      }
    }
  }
  std::printf("lake: %d water pixels drawn, %d dry pixels changed\n", waterDrawn, changedDry);
  EXPECT_EQ(changedDry, 0);
  EXPECT_GT(waterDrawn, 12000); // the lake is ~15,000 m²
  if (const char* dir = std::getenv("SYLVA_SHORE_OUT")) {
    // The documentation's pictures: standing on the south shore, looking along it, through one swash cycle.
    const render::Camera view = lakeShoreCamera();
    const int frames = std::getenv("SYLVA_SHORE_FRAMES") ? std::atoi(std::getenv("SYLVA_SHORE_FRAMES")) : 5;
    for (int i = 0; i < frames; ++i) {
      const double t = 4.0 * i / frames;
      char name[64];
      std::snprintf(name, sizeof(name), "/water-lake-%02d.png", i);
      savePng(std::string(dir) + name, lakeFrame(scene, &water, view, 960, 540, t));
    }
    savePng(std::string(dir) + "/water-lake-none.png", lakeFrame(scene, nullptr, view, 960, 540, 0.0));
  }
}

TEST_F(ShoreWaterTest, DrawingTheWetCellsMergedChangesNoPixelBeyondRounding) {
  // The lake from above and from its shore, looking across: the wet cells (a fraction of the grid), their
  // flat runs merged into fans (a fraction of their vertices), give the pixels of the whole grid drawn cell
  // by cell, whose dry cells the shader discards. The fans' triangles interpolate the same plane along other
  // edges: a few pixels round differently, by at most 2/255; a crack or an overlap would show far more.
  const float scale = 1.5f;
  terrain::TerrainSceneOptions options;
  options.exaggeration = scale;
  terrain::TerrainScene scene(shaders(), lake(), lakeQuadtree(), options);
  ShoreWater water(shaders(), scene.field(), scale, settings());
  EXPECT_LT(water.drawnCells(), water.gridCells() / 2);
  EXPECT_GT(water.drawnCells(), 0);
  EXPECT_LT(water.drawnVertices(), 6 * water.drawnCells() / 2);
  for (const render::Camera& camera : {lakeTopCamera(), lakeShoreCamera()}) {
    for (double time : {0.0, 1.3}) {
      water.setDrawEveryCell(false);
      const Image merged = lakeFrame(scene, &water, camera, 256, 192, time);
      water.setDrawEveryCell(true);
      const Image every = lakeFrame(scene, &water, camera, 256, 192, time);
      const render::CompareResult near = render::compareImages(merged, every, {2, 0.0});
      const render::CompareResult exact = render::compareImages(merged, every, {0, 0.001});
      EXPECT_TRUE(near.passed) << "time " << time << ": " << near.failingFraction();
      EXPECT_TRUE(exact.passed) << "time " << time << ": " << exact.failingFraction();
    }
  }
}

TEST_F(ShoreWaterTest, ACoarserSwashLevelDrawsTheSameSmallFrame) {
  // A frame at half the resolution samples the swash a mip level coarser everywhere: rendering the folding
  // frame straight into level 1 (a quarter of the work) draws it the same (the quality ladder's water).
  const float scale = 1.5f;
  terrain::TerrainSceneOptions options;
  options.exaggeration = scale;
  terrain::TerrainScene scene(shaders(), lake(), lakeQuadtree(), options);
  ShoreWater water(shaders(), scene.field(), scale, settings());
  const Image fine = lakeFrame(scene, &water, lakeShoreCamera(), 128, 96, 0.7);
  water.setSwashLevel(1);
  EXPECT_EQ(water.swashLevel(), 1);
  const Image coarse = lakeFrame(scene, &water, lakeShoreCamera(), 128, 96, 0.7);
  const render::CompareResult guard = render::compareImages(coarse, fine, {16, 0.01});
  EXPECT_TRUE(guard.passed) << guard.failingFraction();
  EXPECT_LE(guard.meanChannelDiff, 2.0);
  EXPECT_FALSE(coarse == fine) << "level 1 was not what the water sampled";
  water.setSwashLevel(99); // clamped to the coarsest level: a frame still draws
  EXPECT_GT(water.swashLevel(), 1);
  const Image coarsest = lakeFrame(scene, &water, lakeShoreCamera(), 128, 96, 0.7);
  water.setSwashLevel(0);
  EXPECT_TRUE(lakeFrame(scene, &water, lakeShoreCamera(), 128, 96, 0.7) == fine) << "back to level 0";
  EXPECT_FALSE(render::compareImages(coarsest, fine, {0, 0.0}).passed);
}

TEST_F(ShoreWaterTest, SwashTextureFollowsTheProjectClock) {
  ShoreSettings s = settings();
  s.period = 8.0f; // one 4 s project cycle every 8 s
  ShoreWater water(shaders(), slope(), kScale, s);
  EXPECT_DOUBLE_EQ(water.projectPeriod(), 4.0);
  EXPECT_NEAR(water.swashAspect(), 288.0f / 480.0f, 1e-6f);
  const auto frame = [&](double t) {
    water.update(t);
    return water.swashTexture().download(4, PixelType::U8);
  };
  const Image a = frame(2.6);
  const Image b = frame(10.6); // one period later
  const Image c = frame(4.0);
  EXPECT_TRUE(a == b);
  EXPECT_FALSE(a == c);
  EXPECT_EQ(a.width(), 480);
  EXPECT_EQ(a.height(), 288);
}

TEST_F(ShoreWaterTest, MissingProjectIsAnErrorNamingIt) {
  ShoreSettings s = settings();
  s.folding = "/nonexistent/lake-swash.json";
  try {
    ShoreWater water(shaders(), slope(), kScale, s);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lake-swash.json"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace sylva::scene
