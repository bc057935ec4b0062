// GPU quadtree selection against the CPU reference: the same leaves with bit-identical patch records
// (position, size, height range, edge levels and flags) over random cameras, both LOD rules, culling on and
// off, every crack method and several base levels, on a real DEM and a rough procedural field.
#include <sylva/core/Random.hpp>
#include <sylva/gl/State.hpp>
#include <sylva/terrain/HeightSources.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/gpu/GpuQuadtreeSelection.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/terrain/gpu/TerrainPopping.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"

#include <fmt/format.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <tuple>

namespace sylva::terrain {
namespace {

using TerrainGpuSelection = test::GlTest;

std::vector<gpu::TerrainNode> sorted(std::vector<gpu::TerrainNode> nodes) {
  std::sort(nodes.begin(), nodes.end(), [](const gpu::TerrainNode& a, const gpu::TerrainNode& b) {
    return std::tie(a.grid.y, a.grid.z, a.grid.x) < std::tie(b.grid.y, b.grid.z, b.grid.x);
  });
  return nodes;
}

struct FieldCase {
  std::string name;
  HeightField field;
  QuadtreeConfig layout;
};

std::vector<FieldCase> fields() {
  std::vector<FieldCase> out;
  if (std::filesystem::exists(test::externalData("jacksboro_fault_dem.npz"))) {
    HeightField dem = loadHeightField(test::externalData("jacksboro_fault_dem.npz"));
    QuadtreeConfig c = QuadtreeConfig::forRootCount(16, dem.extentX(), dem.extentZ());
    c.maxDepth = 5;
    out.push_back({"jacksboro", std::move(dem), c});
  }
  ProceduralSpec spec;
  spec.type = ProceduralSpec::Type::Ridged;
  spec.seed = 5;
  spec.octaves = 8;
  spec.frequency = 1.0f / 600.0f;
  spec.heightScale = 400.0f;
  QuadtreeConfig c;
  c.rootSize = 256.0f;
  c.maxDepth = 6;
  out.push_back({"ridged", generate(spec, 0.0, 0.0, 513, 385, 2.0f), c});
  return out;
}

TEST_F(TerrainGpuSelection, SelectsExactlyTheCpuLeavesAndEdgeLevels) {
  long long compared = 0;
  long long doubled = 0;
  std::vector<double> gpuMs;
  std::vector<double> cpuMs;
  std::vector<double> timerMs;
  for (FieldCase& f : fields()) {
    Rng rng(0x6E1EC7ULL);
    for (const bool errorLod : {false, true}) {
      QuadtreeConfig config = f.layout;
      config.lodErrorPixels = errorLod ? 1.0f : 0.0f;
      config.patchTessLevel = 16;
      Quadtree quadtree(config, f.field);
      GpuQuadtreeSelection gpuSelection(shaders(), quadtree);
      for (int cam = 0; cam < 40; ++cam) {
        const float span = std::max(f.field.extentX(), f.field.extentZ());
        const glm::vec3 position(rng.uniform(-0.2f, 1.2f) * f.field.extentX(),
                                 rng.uniform(-50.0f, 0.3f * span),
                                 rng.uniform(-0.2f, 1.2f) * f.field.extentZ());
        const float yaw = rng.uniform(0.0f, 6.2831853f);
        const float pitch = rng.uniform(-1.3f, 0.3f);
        const glm::vec3 dir(std::cos(pitch) * std::cos(yaw), std::sin(pitch),
                            std::cos(pitch) * std::sin(yaw));
        const Frustum frustum(
            glm::perspective(glm::radians(rng.uniform(30.0f, 90.0f)), 16.0f / 9.0f, 0.5f, 3.0f * span) *
            glm::lookAt(position, position + dir, glm::vec3(0, 1, 0)));
        QuadtreeConfig policy = quadtree.config();
        policy.frustumCull = cam % 3 != 0;
        policy.method = cam % 5 == 0   ? CrackMethod::None
                        : cam % 2 == 0 ? CrackMethod::PaperSearch
                                       : CrackMethod::RestrictedLevelMap;
        policy.restrictSelection = cam % 7 != 0;
        if (!policy.restrictSelection) {
          policy.lodDistanceFactor = rng.uniform(0.5f, 4.0f);
        } else {
          policy.lodDistanceFactor = rng.uniform(kMinRestrictedLodFactor, 6.0f);
        }
        policy.lodErrorPixels = errorLod ? rng.uniform(0.3f, 4.0f) : 0.0f;
        policy.pixelsPerRadian = rng.uniform(300.0f, 1500.0f);
        policy.lodEnabled = cam % 11 != 0;
        quadtree.setConfig(policy);
        const auto start = std::chrono::steady_clock::now();
        const QuadtreeSelection cpu = quadtree.select(position, &frustum);
        cpuMs.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        gl::finish();
        const auto gpuStart = std::chrono::steady_clock::now();
        gpuSelection.select(position, &frustum);
        gl::finish();
        gpuMs.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - gpuStart).count());
        timerMs.push_back(gpuSelection.lastGpuMs());
        ASSERT_EQ(gpuSelection.overflow(), 0u);
        const std::vector<gpu::TerrainNode> want =
            sorted(packTerrainNodes(cpu, f.field.extentX(), f.field.extentZ(), false));
        const std::vector<gpu::TerrainNode> got = sorted(gpuSelection.readNodes());
        ASSERT_EQ(got.size(), want.size()) << f.name << " camera " << cam << (errorLod ? " (error LOD)" : "");
        for (std::size_t i = 0; i < want.size(); ++i) {
          ASSERT_EQ(std::memcmp(&got[i], &want[i], sizeof(gpu::TerrainNode)), 0)
              << f.name << " camera " << cam << " leaf " << i << ": grid " << got[i].grid.x << ","
              << got[i].grid.y << "," << got[i].grid.z << " vs " << want[i].grid.x << "," << want[i].grid.y
              << "," << want[i].grid.z << "; outer " << got[i].tessOuter.x << " " << got[i].tessOuter.y << " "
              << got[i].tessOuter.z << " " << got[i].tessOuter.w << " vs " << want[i].tessOuter.x << " "
              << want[i].tessOuter.y << " " << want[i].tessOuter.z << " " << want[i].tessOuter.w;
        }
        compared += static_cast<long long>(want.size());
        doubled += cpu.stats.doubledEdges;
      }
    }
  }
  std::sort(gpuMs.begin(), gpuMs.end());
  std::sort(cpuMs.begin(), cpuMs.end());
  RecordProperty("leaves_compared", std::to_string(compared));
  std::sort(timerMs.begin(), timerMs.end());
  RecordProperty("gpu_select_wall_ms_median", fmt::format("{:.3f}", gpuMs[gpuMs.size() / 2]));
  RecordProperty("gpu_timer_ms_median", fmt::format("{:.3f}", timerMs[timerMs.size() / 2]));
  RecordProperty("cpu_select_ms_median", fmt::format("{:.3f}", cpuMs[cpuMs.size() / 2]));
  std::printf(
      "GPU selection: %lld leaves compared, %lld doubled edges; median wall %.3f ms (dispatch to finish; "
      "GL timer %.3f ms), CPU %.3f ms\n",
      compared, doubled, gpuMs[gpuMs.size() / 2], timerMs[timerMs.size() / 2], cpuMs[cpuMs.size() / 2]);
  EXPECT_GT(compared, 5000);
  EXPECT_GT(doubled, 500);
}

// Drawn from the GPU's buffers with one indirect draw, the frame is byte-identical to the CPU selection's.
TEST_F(TerrainGpuSelection, IndirectDrawMatchesTheCpuSelectionsFrame) {
  FieldCase f = fields().back();
  QuadtreeConfig config = f.layout;
  config.patchTessLevel = 8;
  config.lodErrorPixels = 1.0f;
  Quadtree quadtree(config, f.field);
  GpuQuadtreeSelection gpuSelection(shaders(), quadtree);
  TerrainRenderer renderer(shaders(), f.field, defaultSplatLayers(0.0f, 400.0f));
  render::RenderTarget target(320, 180);
  int differing = 0;
  for (int pose = 0; pose < 4; ++pose) {
    render::Camera camera;
    camera.position = {100.0f + 150.0f * static_cast<float>(pose), 420.0f, 60.0f};
    camera.target = {500.0f, 100.0f, 500.0f};
    camera.nearPlane = 1.0f;
    camera.farPlane = 3000.0f;
    const Frustum frustum = camera.frustum(target.aspect());
    TerrainDrawOptions options;
    options.view = pose % 2 == 0 ? TerrainView::Shaded : TerrainView::LodColours;
    target.begin(glm::vec4(0.5f, 0.6f, 0.8f, 1.0f));
    renderer.draw(quadtree.select(camera.position, &frustum), camera, 320, 180, 0.0, nullptr, options);
    const Image cpu = target.readColor();
    gpuSelection.select(camera.position, &frustum);
    target.begin(glm::vec4(0.5f, 0.6f, 0.8f, 1.0f));
    renderer.draw(gpuSelection, camera, 320, 180, 0.0, nullptr, options);
    const Image gpu = target.readColor();
    ASSERT_EQ(cpu.byteSize(), gpu.byteSize());
    differing += std::memcmp(cpu.data(), gpu.data(), cpu.byteSize()) != 0 ? 1 : 0;
    EXPECT_GT(changedPixelFraction(cpu, Image(320, 180, 4, PixelType::U8)), 0.3)
        << "pose " << pose << " drew little";
  }
  EXPECT_EQ(differing, 0);
}

} // namespace
} // namespace sylva::terrain
