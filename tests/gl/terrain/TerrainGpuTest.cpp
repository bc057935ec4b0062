// The terrain's compute passes against their CPU references, and the drawn surface against the CPU ground
// query.
#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>

#include <sylva/render/gpu/RenderTarget.hpp>

#include "GlTest.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cstdlib>
#include <optional>

#include <algorithm>
#include <cmath>

namespace sylva::terrain {
namespace {

using TerrainGpu = test::GlTest;

/** A rough procedural field with scattered absent samples and a non-square, non-power-of-two size. */
HeightField testField() {
  ProceduralSpec spec;
  spec.seed = 99;
  spec.type = ProceduralSpec::Type::Ridged;
  spec.frequency = 1.0f / 60.0f;
  spec.heightScale = 80.0f;
  HeightField field = generate(spec, 0.0, 0.0, 97, 61, 3.0f);
  Rng rng(5);
  for (int k = 0; k < 40; ++k) {
    field.at(static_cast<int>(rng.below(97)), static_cast<int>(rng.below(61))) = std::nanf("");
  }
  return field;
}

float maxDifference(const Image& a, const Image& b, int channels) {
  float worst = 0.0f;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      for (int c = 0; c < channels; ++c) {
        worst = std::max(worst, std::abs(a.get(x, y, c) - b.get(x, y, c)));
      }
    }
  }
  return worst;
}

/** CPU normals as the GPU stores them: x and z in 16-bit snorm, y rebuilt from them. */
Image snorm16Normals(Image normals) {
  const auto q = [](float v) { return std::round(std::clamp(v, -1.0f, 1.0f) * 32767.0f) / 32767.0f; };
  for (int y = 0; y < normals.height(); ++y) {
    for (int x = 0; x < normals.width(); ++x) {
      const float nx = q(normals.get(x, y, 0));
      const float nz = q(normals.get(x, y, 2));
      normals.set(x, y, 0, nx);
      normals.set(x, y, 1, std::sqrt(std::max(0.0f, 1.0f - nx * nx - nz * nz)));
      normals.set(x, y, 2, nz);
    }
  }
  return normals;
}

TEST_F(TerrainGpu, SobelNormalsMatchCpuForBothBorders) {
  const HeightField field = testField();
  for (BorderMode border : {BorderMode::Clamp, BorderMode::Constant}) {
    SobelOptions options;
    options.border = border;
    options.constantHeight = 12.5f;
    const TerrainRenderer renderer(shaders(), field, defaultSplatLayers(0.0f, 80.0f), options);
    const Image gpu = renderer.downloadNormals();
    const Image cpu = snorm16Normals(sobelNormalMap(field, options));
    ASSERT_EQ(gpu.width(), cpu.width());
    ASSERT_EQ(gpu.height(), cpu.height());
    // Same formula in float, stored in 16-bit: one quantisation step (3e-5) where rounding tips the other way
    // (GPU normalize() may use an approximate inverse square root), amplified in y rebuilt on steep slopes.
    EXPECT_LT(maxDifference(gpu, cpu, 3), 5e-4f) << "border mode " << static_cast<int>(border);
  }
}

TEST_F(TerrainGpu, SplatWeightsMatchCpuForManyLayers) {
  const HeightField field = testField();
  // Six layers: two pages, the second half-filled; soft edges in height and slope.
  std::vector<SplatLayer> layers = defaultSplatLayers(0.0f, 80.0f);
  layers.push_back({"dirt", 10.0f, 30.0f, 5.0f, 25.0f, 4.0f, 3.0f});
  layers.push_back({"meadow", 20.0f, 60.0f, 0.0f, 15.0f, 6.0f, 5.0f});
  const TerrainRenderer renderer(shaders(), field, layers);
  const std::vector<Image> gpu = renderer.downloadSplat();
  const std::vector<Image> cpu = splatMap(field, sobelNormalMap(field), layers);
  ASSERT_EQ(gpu.size(), 2u);
  ASSERT_EQ(cpu.size(), 2u);
  for (std::size_t page = 0; page < 2; ++page) {
    // Weights are stored in 8 bits (half a step: 0.002); acos and the 16-bit normal add a little.
    EXPECT_LT(maxDifference(gpu[page], cpu[page], 4), 3e-3f) << "page " << page;
  }
}

TEST_F(TerrainGpu, SplatWithVerticalScaleMatchesCpu) {
  HeightField field = testField();
  for (float& h : field.samples()) {
    h *= 6.0f; // drawn 6x taller; the rules stay in true metres and degrees
  }
  const std::vector<SplatLayer> layers = defaultSplatLayers(0.0f, 80.0f, 20.0f);
  const TerrainRenderer renderer(shaders(), field, layers, SobelOptions{}, 6.0f);
  const std::vector<Image> gpu = renderer.downloadSplat();
  const std::vector<Image> cpu = splatMap(field, sobelNormalMap(field), layers, 6.0f);
  ASSERT_EQ(gpu.size(), 1u);
  EXPECT_LT(maxDifference(gpu[0], cpu[0], 4), 5e-3f); // slopes x6: the 16-bit normal weighs more
}

// The water surface: drawn over samples below the sea level, never over dry ground or nodata.
TEST_F(TerrainGpu, WaterCoversExactlyTheSamplesBelowSeaLevel) {
  // A ramp from -30 m (west) to +30 m (east), seen from straight above: the west half is sea.
  HeightField field(129, 129, 2.0f, 2.0f);
  for (int j = 0; j < 129; ++j) {
    for (int i = 0; i < 129; ++i) {
      field.at(i, j) = -30.0f + 60.0f * static_cast<float>(i) / 128.0f;
    }
  }
  for (int j = 100; j < 129; ++j) {
    for (int i = 0; i < 30; ++i) {
      field.at(i, j) = std::nanf(""); // a nodata corner in the sea: no water there either
    }
  }
  QuadtreeConfig config;
  config.rootSize = 64.0f;
  config.maxDepth = 2;
  Quadtree quadtree(config, field);
  TerrainRenderer renderer(shaders(), field, defaultSplatLayers(-30.0f, 30.0f, 0.0f));
  render::Camera camera;
  camera.position = {128.0f, 900.0f, 128.0f};
  camera.target = {128.0f, 0.0f, 128.0f};
  camera.up = {0.0f, 0.0f, -1.0f};
  camera.fovY = glm::radians(20.0f);
  camera.nearPlane = 100.0f;
  camera.farPlane = 2000.0f;
  QuadtreeSelection selection;
  quadtree.select(camera.position, nullptr, selection);
  const auto render = [&](std::optional<float> water) {
    render::RenderTarget target(128, 128);
    target.begin(glm::vec4(1.0f, 0.0f, 1.0f, 1.0f));
    TerrainDrawOptions options;
    options.environment.fogDensity = 0.0f;
    options.waterLevel = water;
    renderer.draw(selection, camera, 128, 128, 0.0, nullptr, options);
    return target.readColor();
  };
  const Image dry = render(std::nullopt);
  const Image wet = render(0.0f);
  if (std::getenv("SYLVA_DUMP") != nullptr) {
    saveImage("/tmp/exp/dry.png", dry);
    saveImage("/tmp/exp/wet.png", wet);
  }
  // World x of a pixel column: the view spans 2·900·tan(10°) = 317 m around x = 128 m.
  const float span = 2.0f * 900.0f * std::tan(glm::radians(10.0f));
  int waterPixels = 0;
  for (int y = 0; y < 128; ++y) {
    for (int x = 0; x < 128; ++x) {
      // Offsets at y = 0, then scaled to the ground's depth below the camera (the ramp's height there).
      const float ox = (static_cast<float>(x) + 0.5f - 64.0f) / 128.0f * span;
      const float oz = (static_cast<float>(y) + 0.5f - 64.0f) / 128.0f * span;
      const float depthScale = (900.0f - (-30.0f + 60.0f * (128.0f + ox) / 256.0f)) / 900.0f;
      const float wx = 128.0f + ox * depthScale;
      const float wz = 128.0f + oz * depthScale;
      if (wx < 8.0f || wz < 8.0f || wx > 248.0f || wz > 248.0f) {
        continue; // outside the footprint, or on its edge
      }
      const bool changed =
          std::abs(wet.get(x, y, 0) - dry.get(x, y, 0)) + std::abs(wet.get(x, y, 2) - dry.get(x, y, 2)) >
          0.02f;
      // Fragments are cut by their nearest sample: absent columns 0..29 and rows 100.. end at x = 59, z =
      // 199.
      if ((std::abs(wx - 59.0f) < 3.0f && wz > 196.0f) || (std::abs(wz - 199.0f) < 3.0f && wx < 62.0f)) {
        continue;
      }
      const bool nodata = wx < 59.0f && wz > 199.0f;
      const float ground = -30.0f + 60.0f * wx / 256.0f;
      if (nodata) {
        EXPECT_FALSE(changed) << "water over nodata at " << wx << ", " << wz;
      } else if (ground < -2.0f) {
        EXPECT_TRUE(changed) << "no water over the sea floor at " << ground << " m";
        EXPECT_GT(wet.get(x, y, 2), wet.get(x, y, 0)) << "water is blue";
        ++waterPixels;
      } else if (ground > 2.0f) {
        EXPECT_FALSE(changed) << "water over dry ground at " << ground << " m";
      }
    }
  }
  EXPECT_GT(waterPixels, 3000);
}

// What is drawn agrees with heightAt: render world positions into a float target from a camera standing on
// the ground, and compare each pixel's height with the CPU query at that pixel's xz.
TEST_F(TerrainGpu, DrawnSurfaceMatchesGroundQuery) {
  ProceduralSpec spec;
  spec.seed = 3;
  spec.frequency = 1.0f / 180.0f;
  spec.heightScale = 60.0f;
  const HeightField field = generate(spec, 0.0, 0.0, 257, 257, 2.0f);
  QuadtreeConfig config;
  config.rootSize = 128.0f;
  config.maxDepth = 4;        // 8 m leaves near the camera
  config.patchTessLevel = 32; // 0.25 m between vertices, 8 per height sample
  Quadtree quadtree(config, field);
  TerrainRenderer renderer(shaders(), field, defaultSplatLayers(0.0f, 60.0f));

  render::Camera camera;
  const float x = 260.0f;
  const float z = 250.0f;
  camera.position = {x, heightAt(field, x, z) + 1.8f, z};
  camera.target = {x + 30.0f, heightAt(field, x + 30.0f, z + 20.0f), z + 20.0f};
  camera.nearPlane = 0.1f;
  camera.farPlane = 800.0f;
  const int w = 256;
  const int h = 160;
  gl::Texture position = gl::Texture::create2D(GL_RGBA32F, w, h);
  gl::Texture depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, w, h);
  gl::Framebuffer fb;
  fb.attachColor(0, position);
  fb.attachDepth(depth);
  fb.checkComplete();
  fb.bindForDraw(w, h);
  fb.clearColor(0, glm::vec4(0.0f));
  fb.clearDepth();
  glEnable(GL_DEPTH_TEST);
  const float aspect = static_cast<float>(w) / static_cast<float>(h);
  const Frustum frustum = camera.frustum(aspect);
  const QuadtreeSelection selection = quadtree.select(camera.position, &frustum);
  TerrainDrawOptions options;
  options.view = TerrainView::WorldPosition;
  renderer.draw(selection, camera, w, h, 0.0, nullptr, options);
  const Image image = position.download(4, PixelType::F32);

  float nearWorst = 0.0f;
  int nearPixels = 0;
  for (int py = 0; py < h; ++py) {
    for (int px = 0; px < w; ++px) {
      if (image.get(px, py, 3) == 0.0f) {
        continue;
      }
      const glm::vec3 p(image.get(px, py, 0), image.get(px, py, 1), image.get(px, py, 2));
      if (glm::length(p - camera.position) > 40.0f) {
        continue; // coarser LOD further away: the mesh approximates the surface more loosely there
      }
      nearWorst = std::max(nearWorst, std::abs(p.y - heightAt(field, p.x, p.z)));
      ++nearPixels;
    }
  }
  EXPECT_GT(nearPixels, w * h / 10);
  RecordProperty("near_pixels", nearPixels);
  RecordProperty("worst_difference_mm", std::to_string(nearWorst * 1000.0f));
  // The target: ≤ 1 cm between the CPU query and the drawn surface around the viewer.
  EXPECT_LE(nearWorst, 0.01f) << "over " << nearPixels << " pixels within 40 m";
}

TEST_F(TerrainGpu, RejectsDegenerateFields) {
  auto make = [&](const HeightField& field) {
    TerrainRenderer(shaders(), field, defaultSplatLayers(0.0f, 1.0f));
  };
  EXPECT_THROW(make(HeightField(1, 1)), Error);
  EXPECT_THROW(make(HeightField(4, 4, 1.0f, 1.0f, std::nanf(""))), Error);
}

TEST(TerrainNodes, SkirtsOnlyOnInteriorEdges) {
  QuadtreeSelection selection;
  SelectedNode a;
  a.x = 0.0f;
  a.z = 0.0f;
  a.size = 10.0f;
  a.tessOuter = {4, 4, 8, 4};
  a.tessInner = 4;
  SelectedNode b = a;
  b.x = 10.0f;
  selection.nodes = {a, b};
  const auto packed = packTerrainNodes(selection, 20.0f, 10.0f, true);
  // a: only its east edge is interior; b: only its west edge.
  ASSERT_EQ(packed.size(), 4u);
  EXPECT_EQ(packed[2].grid.w, kEdgeEast);
  EXPECT_EQ(packed[3].grid.w, kEdgeWest);
  EXPECT_EQ(packed[0].tessOuter.z, 8.0f);
  EXPECT_EQ(packTerrainNodes(selection, 20.0f, 10.0f, false).size(), 2u);
}

} // namespace
} // namespace sylva::terrain
