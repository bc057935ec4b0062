// The grass field on the GPU against its CPU references: culling counts and the instances themselves, root
// heights, the vertex shader's blade expansion, blade counts from pipeline statistics, determinism.
#include <sylva/core/Error.hpp>
#include <sylva/grass/gpu/GrassRenderer.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/Noise.hpp>

#include "GlTest.hpp"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace sylva::grass {
namespace {

using GrassGpu = test::GlTest;

std::shared_ptr<const GrassField> smallField(int bladesPerTile = 96) {
  terrain::ProceduralSpec spec = terrain::defaultLandscapeSpec(9);
  spec.heightScale = 8.0f;
  FieldSettings fs;
  fs.patch.blades = 4096;
  fs.bladesPerTile = bladesPerTile;
  return std::make_shared<GrassField>(terrain::generate(spec, 0.0, 0.0, 97, 81, 1.0f), proceduralBladeTypes(),
                                      fs);
}

/** A camera at `eye` (y: metres above the ground there) looking at `at` (y likewise). */
render::Camera camera(const GrassField& field, const glm::vec3& eye, const glm::vec3& at,
                      float fovDegrees = 60.0f) {
  const auto ground = [&](const glm::vec3& p) {
    return glm::vec3(p.x, p.y + terrain::heightAt(field.terrain(), p.x, p.z), p.z);
  };
  render::Camera c;
  c.position = ground(eye);
  c.target = ground(at);
  c.fovY = glm::radians(fovDegrees);
  c.nearPlane = 0.1f;
  c.farPlane = 1000.0f;
  return c;
}

/** Blades near a test's plane or distance threshold may fall either way in float: allow a few per thousand.
 */
void expectNear(std::size_t gpu, std::size_t cpu, const char* what) {
  const double tolerance = 2.0 + 0.002 * static_cast<double>(cpu);
  EXPECT_NEAR(static_cast<double>(gpu), static_cast<double>(cpu), tolerance) << what;
}

TEST_F(GrassGpu, CullingMatchesTheCpuReference) {
  const auto field = smallField();
  CullSettings settings;
  settings.maxDistance = 70.0f;
  settings.farFade = 15.0f;
  settings.lodDistances = {10.0f, 28.0f};
  settings.orientationDistance = 20.0f;
  GrassRenderer renderer(shaders(), field, settings);
  const float aspect = 16.0f / 9.0f;
  const std::vector<render::Camera> cameras{
      camera(*field, {4.0f, 2.0f, 3.0f}, {60.0f, 1.0f, 55.0f}),
      camera(*field, {90.0f, 25.0f, 75.0f}, {30.0f, 0.0f, 30.0f}, 45.0f),
      camera(*field, {48.0f, 45.0f, 40.01f}, {48.0f, 0.0f, 40.0f}, 70.0f)};
  for (const render::Camera& cam : cameras) {
    std::vector<VisibleBlade> cpuList;
    const CullStats cpu = cullField(*field, cam.viewProjection(aspect), cam.position, settings, &cpuList);
    renderer.cull(cam, aspect);
    const gpu::GrassCounters c = renderer.readCounters();
    EXPECT_GT(cpu.drawn(), 500u);
    EXPECT_EQ(c.overflow.x, 0u);
    // The near tufts (the first camera stands in the grass; the others are too high for any).
    expectNear(c.overflow.w, cpu.tuftBlades, "tuft blades");
    if (&cam == &cameras.front()) {
      EXPECT_GT(cpu.tuftBlades, 1000u);
    }
    EXPECT_EQ(c.overflow.y, 0u);
    EXPECT_EQ(c.dispatch.x, cpu.tilesVisible) << "visible tiles";
    expectNear(c.blades.x, cpu.blades, "blades");
    expectNear(c.blades.y, cpu.culledFrustum, "frustum");
    expectNear(c.blades.z, cpu.culledDistance, "distance");
    expectNear(c.blades.w, cpu.culledOrientation, "orientation");
    for (int k = 0; k < 3; ++k) {
      expectNear(c.draws[k].y, cpu.bladesPerLod[static_cast<std::size_t>(k)], "level list");
      EXPECT_EQ(c.draws[k].x, 2u * static_cast<unsigned>(kLodKnots[static_cast<std::size_t>(k)]));
    }
    // The instances themselves: the same blades at the same levels and fades, roots on the terrain.
    std::map<std::tuple<std::uint32_t, int, int, int>, VisibleBlade> cpuSet;
    for (const VisibleBlade& v : cpuList) {
      cpuSet[{v.blade.patchIndex, v.lod, static_cast<int>(std::floor(v.blade.root.x * 64.0f)),
              static_cast<int>(std::floor(v.blade.root.z * 64.0f))}] = v;
    }
    std::size_t matched = 0;
    double worstHeight = 0.0;
    for (const VisibleBlade& g : renderer.readInstances()) {
      const auto it =
          cpuSet.find({g.blade.patchIndex, g.lod, static_cast<int>(std::floor(g.blade.root.x * 64.0f)),
                       static_cast<int>(std::floor(g.blade.root.z * 64.0f))});
      worstHeight = std::max<double>(
          worstHeight,
          std::abs(g.blade.root.y - terrain::heightAt(field->terrain(), g.blade.root.x, g.blade.root.z)));
      if (it == cpuSet.end()) {
        continue;
      }
      ++matched;
      EXPECT_LT(glm::length(g.blade.root - it->second.blade.root), 1e-4f);
      EXPECT_EQ(g.fade, it->second.fade);
      EXPECT_NEAR(g.amount, it->second.amount, 0.5f / 63.0f + 1e-4f);
    }
    expectNear(matched, cpuList.size(), "matched instances");
    EXPECT_LT(worstHeight, 0.01) << "root heights within 1 cm of the terrain query";
    RecordProperty("worst_root_height_m", std::to_string(worstHeight));
  }
}

TEST_F(GrassGpu, VertexShaderExpansionMatchesExpandBlade) {
  const auto field = smallField();
  GrassRenderer renderer(shaders(), field);
  CullSettings settings;
  std::vector<VisibleBlade> visible;
  const render::Camera cam = camera(*field, {4.0f, 1.7f, 3.0f}, {60.0f, 1.0f, 55.0f});
  cullField(*field, cam.viewProjection(1.5f), cam.position, settings, &visible);
  // A spread of blades at every level.
  std::vector<VisibleBlade> sample;
  std::array<int, 3> perLod{0, 0, 0};
  for (const VisibleBlade& v : visible) {
    if (perLod[static_cast<std::size_t>(v.lod)]++ % 17 == 0 && sample.size() < 240) {
      sample.push_back(v);
    }
  }
  ASSERT_GT(sample.size(), 60u);
  // Rasterisation is off while capturing, but a complete framebuffer must still be bound.
  render::RenderTarget target(16, 16);
  target.begin(glm::vec4(0.0f));
  wind::WindSettings wind;
  wind.speed = 7.0f;
  wind.direction = {0.8f, 0.6f};
  for (const double time : {0.0, 3.25}) {
    const auto gpuBlades = renderer.captureExpansion(sample, wind, time);
    ASSERT_EQ(gpuBlades.size(), sample.size());
    const gpu::WindUniforms u = wind::toUniforms(wind, static_cast<float>(time));
    double worst = 0.0;
    for (std::size_t i = 0; i < sample.size(); ++i) {
      const VisibleBlade& v = sample[i];
      const gpu::GrassBlade& b = field->patch()[v.blade.patchIndex];
      const std::vector<BladeVertex> cpu =
          expandBlade(field->types()[b.info.x], v.lod, b, v.blade.root,
                      wind::windVelocity(u, glm::vec2(v.blade.root.x, v.blade.root.z)));
      ASSERT_EQ(gpuBlades[i].size(), cpu.size());
      for (std::size_t j = 0; j < cpu.size(); ++j) {
        const BladeVertex& g = gpuBlades[i][j];
        worst = std::max<double>(worst, glm::length(g.position - cpu[j].position));
        ASSERT_LT(glm::length(g.position - cpu[j].position), 1e-4f) << "blade " << i << " vertex " << j;
        ASSERT_LT(glm::length(g.normal - cpu[j].normal), 1e-3f) << "blade " << i << " vertex " << j;
        ASSERT_NEAR(g.along, cpu[j].along, 1e-5f);
        ASSERT_EQ(g.side, cpu[j].side);
      }
    }
    std::printf("expansion: worst CPU/GPU vertex difference %.3g m (t = %.2f s)\n", worst, time);
  }
}

TEST_F(GrassGpu, PipelineStatisticsCountTheCpuBlades) {
  if (!epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) {
    GTEST_SKIP() << "no GL_ARB_pipeline_statistics_query";
  }
  const auto field = smallField();
  // The whole field from high above with nothing culled but by the frustum (none): every blade of the CPU
  // count is drawn, once, at the finest level.
  CullSettings open;
  open.maxDistance = 1000.0f;
  open.lodDistances = {900.0f, 950.0f};
  open.lodFade = 0.0f;
  open.farFade = 0.0f;
  open.orientationCos = 0.0f;
  GrassRenderer renderer(shaders(), field, open);
  render::RenderTarget target(160, 120);
  target.begin(glm::vec4(0.5f, 0.6f, 0.8f, 1.0f));
  const render::Camera cam = camera(*field, {48.0f, 150.0f, 40.01f}, {48.0f, 0.0f, 40.0f}, 60.0f);
  renderer.cull(cam, target.aspect());
  GrassDrawOptions options;
  options.countPrimitives = true;
  renderer.draw(cam, 160, 120, 0.0, nullptr, options);
  const std::size_t cpu = field->countBlades();
  EXPECT_GT(cpu, 10000u);
  EXPECT_EQ(renderer.lastVerticesSubmitted(), static_cast<std::int64_t>(cpu * 32));
  EXPECT_EQ(renderer.lastPrimitivesSubmitted(), static_cast<std::int64_t>(cpu * 30));
  RecordProperty("blades", std::to_string(cpu));
}

TEST_F(GrassGpu, SameFrameSameImage) {
  const auto field = smallField();
  GrassRenderer renderer(shaders(), field);
  const render::Camera cam = camera(*field, {4.0f, 1.5f, 3.0f}, {25.0f, -2.0f, 22.0f});
  auto frame = [&] {
    render::RenderTarget target(192, 108);
    target.begin(glm::vec4(0.5f, 0.6f, 0.8f, 1.0f));
    renderer.cull(cam, target.aspect());
    GrassDrawOptions options;
    options.wind.speed = 5.0f;
    renderer.draw(cam, 192, 108, 2.5, nullptr, options);
    return target.readColor();
  };
  const Image a = frame();
  const Image b = frame();
  ASSERT_EQ(a.byteSize(), b.byteSize());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.byteSize()), 0);
  // Something was drawn: grass-coloured pixels over the sky (no terrain here, so the gaps show sky).
  int green = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      green += a.get(x, y, 1) > a.get(x, y, 2) + 0.05f ? 1 : 0;
    }
  }
  EXPECT_GT(green, a.width() * a.height() / 40);
}

TEST_F(GrassGpu, BadSettingsAreErrors) {
  const auto field = smallField();
  CullSettings bad;
  bad.maxDistance = std::nanf("");
  EXPECT_THROW(GrassRenderer(shaders(), field, bad), Error);
  EXPECT_THROW(GrassField(field->terrain(), {}, FieldSettings{}), Error);
  FieldSettings zero;
  zero.patch.blades = 0;
  EXPECT_THROW(GrassField(field->terrain(), proceduralBladeTypes(), zero), Error);
}

} // namespace
} // namespace sylva::grass
