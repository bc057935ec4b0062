// Cascaded sun shadows on the GPU (render::ShadowMaps + shaders/common/shadows.glsl) with the terrain as
// caster and receiver: the shadowed pixels agree with a CPU ray cast towards the sun over the height field, a
// flat control shows no dark region (no acne), shadows off are byte-identical to no shadow map at all, and a
// camera moved by small steps leaves sunVisibility() at fixed world points unchanged (no swimming), and the
// depth-only caster program writes the same depth as the shading one, also where the data has holes.
#include <sylva/gl/Buffer.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Program.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/render/gpu/ShadowMaps.hpp>
#include <sylva/render/Shadows.hpp>
#include <sylva/shader/Compiler.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/Noise.hpp>
#include <sylva/terrain/Quadtree.hpp>
#include <sylva/terrain/gpu/TerrainRenderer.hpp>

#include "GlTest.hpp"
#include "TempDir.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

namespace sylva::render {
namespace {

using ShadowGpu = test::GlTest;

constexpr int kW = 256;
constexpr int kH = 176;
const glm::vec3 kSun = glm::normalize(glm::vec3(-1.0f, 0.55f, 0.25f)); // low, from the west

/** 321 m square at 2 m: a north–south ridge 36 m high and a round hill, on flat ground (or flat only). */
terrain::HeightField testField(bool relief) {
  terrain::HeightField field(161, 161, 2.0f, 2.0f);
  for (int j = 0; j < 161; ++j) {
    for (int i = 0; i < 161; ++i) {
      const float x = 2.0f * static_cast<float>(i);
      const float z = 2.0f * static_cast<float>(j);
      const float ridge = 36.0f * std::exp(-std::pow((x - 100.0f) / 9.0f, 2.0f)) *
                          std::clamp((z - 30.0f) / 20.0f, 0.0f, 1.0f) *
                          std::clamp((290.0f - z) / 20.0f, 0.0f, 1.0f);
      const float hill = 22.0f * std::exp(-(std::pow(x - 220.0f, 2.0f) + std::pow(z - 90.0f, 2.0f)) / 300.0f);
      field.at(i, j) = relief ? ridge + hill : 0.0f;
    }
  }
  return field;
}

Camera viewCamera(const glm::vec3& offset = glm::vec3(0.0f)) {
  Camera camera;
  camera.position = glm::vec3(170.0f, 95.0f, 370.0f) + offset;
  camera.target = glm::vec3(170.0f, 0.0f, 150.0f) + offset;
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 1.0f;
  camera.farPlane = 1000.0f;
  return camera;
}

ShadowSettings testSettings() {
  ShadowSettings settings;
  settings.cascades = 3;
  settings.size = 1024;
  settings.distance = 600.0f;
  settings.lambda = 0.7f;
  return settings;
}

/** The terrain with its quadtree, one LOD selection from the viewer (kept for every pass). */
struct Terrain {
  terrain::HeightField field;
  terrain::Quadtree quadtree;
  terrain::TerrainRenderer renderer;
  terrain::QuadtreeSelection selection;
  Aabb bounds;

  Terrain(const shader::Library& library, bool relief, bool holes = false)
      : field(withHoles(testField(relief), holes)), quadtree(config(), field),
        renderer(library, field, terrain::defaultSplatLayers(0.0f, 40.0f)) {
    selection = quadtree.select(viewCamera().position, nullptr);
    bounds = Aabb{{0.0f, -1.0f, 0.0f}, {320.0f, 40.0f, 320.0f}};
  }
  /** With `holes`, a 40 m square of nodata on the ridge's west flank (in every cascade's view). */
  static terrain::HeightField withHoles(terrain::HeightField field, bool holes) {
    for (int j = 60; holes && j < 80; ++j) {
      for (int i = 30; i < 50; ++i) {
        field.at(i, j) = std::numeric_limits<float>::quiet_NaN();
      }
    }
    return field;
  }
  static terrain::QuadtreeConfig config() {
    terrain::QuadtreeConfig c;
    c.rootSize = 80.0f;
    c.maxDepth = 3;
    c.patchTessLevel = 16;
    return c;
  }

  /** Renders every cascade's depth with the terrain as caster. */
  void renderShadows(ShadowMaps& maps, const ShadowCascades& fit,
                     terrain::TerrainView view = terrain::TerrainView::Shaded) {
    for (int i = 0; i < static_cast<int>(fit.cascades.size()); ++i) {
      const ShadowCascade& cascade = fit.cascades[static_cast<std::size_t>(i)];
      // Cull against the cascade's orthographic frustum; LOD stays the viewer's (same mesh as the receivers).
      const Frustum frustum = cascade.camera.frustum(1.0f);
      const terrain::QuadtreeSelection casters = quadtree.select(viewCamera().position, &frustum);
      maps.begin(i);
      terrain::TerrainDrawOptions options;
      options.environment.fogDensity = 0.0f;
      options.view = view;
      renderer.draw(casters, cascade.camera, maps.size(), maps.size(), 0.0, nullptr, options);
      maps.end();
    }
  }

  Image shaded(const Camera& camera, const ShadowFrame& shadows) {
    RenderTarget target(kW, kH);
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    terrain::TerrainDrawOptions options;
    options.environment.fogDensity = 0.0f;
    options.environment.sunDirection = kSun;
    options.environment.shadows = shadows;
    renderer.draw(selection, camera, kW, kH, 0.0, nullptr, options);
    return target.readColor();
  }

  /** World position per pixel (alpha 0 = background), rows in file order like readColor(). */
  Image positions(const Camera& camera) {
    gl::Texture position = gl::Texture::create2D(GL_RGBA32F, kW, kH);
    gl::Texture depth = gl::Texture::create2D(GL_DEPTH_COMPONENT32F, kW, kH);
    gl::Framebuffer fb;
    fb.attachColor(0, position);
    fb.attachDepth(depth);
    fb.checkComplete();
    fb.bindForDraw(kW, kH);
    fb.clearColor(0, glm::vec4(0.0f));
    fb.clearDepth();
    glEnable(GL_DEPTH_TEST);
    terrain::TerrainDrawOptions options;
    options.view = terrain::TerrainView::WorldPosition;
    renderer.draw(selection, camera, kW, kH, 0.0, nullptr, options);
    Image image = position.download(4, PixelType::F32);
    image.flipVertically();
    return image;
  }
};

float luminance(const Image& image, int x, int y) {
  return 0.2126f * image.get(x, y, 0) + 0.7152f * image.get(x, y, 1) + 0.0722f * image.get(x, y, 2);
}

TEST_F(ShadowGpu, TerrainShadowsMatchCpuRayCast) {
  Terrain scene(shaders(), true);
  const Camera camera = viewCamera();
  const float aspect = static_cast<float>(kW) / static_cast<float>(kH);
  const ShadowSettings settings = testSettings();
  const ShadowCascades fit = fitCascades(camera, aspect, kSun, settings, scene.bounds);
  ShadowMaps maps(settings.size, settings.cascades);
  scene.renderShadows(maps, fit);
  maps.bind();
  const Image lit = scene.shaded(camera, ShadowFrame{});
  const Image shadowed = scene.shaded(camera, toFrame(fit, settings));
  ShadowMaps::unbind();
  const Image unbound = scene.shaded(camera, ShadowFrame{});
  const Image world = scene.positions(camera);
  if (std::getenv("SYLVA_DUMP") != nullptr) {
    std::filesystem::create_directories("/tmp/exp");
    saveImage("/tmp/exp/shadow-off.png", lit);
    saveImage("/tmp/exp/shadow-on.png", shadowed);
  }
  // Shadows off: the bound shadow map changes nothing.
  ASSERT_EQ(lit.byteSize(), unbound.byteSize());
  EXPECT_EQ(std::memcmp(lit.data(), unbound.data(), lit.byteSize()), 0);

  int covered = 0;
  int agree = 0;
  int cpuShadowed = 0;
  int gpuShadowed = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      if (world.get(x, y, 3) == 0.0f) {
        continue;
      }
      const glm::vec3 p(world.get(x, y, 0), world.get(x, y, 1), world.get(x, y, 2));
      const glm::vec3 n = terrain::normalAt(scene.field, p.x, p.z);
      if (glm::dot(n, kSun) < 0.15f) {
        continue; // facing away from the sun or grazing: dark with or without shadows
      }
      ++covered;
      const bool cpu = terrain::raycast(scene.field, p + 0.05f * n + 0.2f * kSun, kSun, 600.0f).has_value();
      const float off = luminance(lit, x, y);
      const bool gpu = luminance(shadowed, x, y) < 0.85f * off;
      cpuShadowed += cpu ? 1 : 0;
      gpuShadowed += gpu ? 1 : 0;
      agree += cpu == gpu ? 1 : 0;
    }
  }
  const double agreement = static_cast<double>(agree) / std::max(covered, 1);
  RecordProperty("covered_pixels", covered);
  RecordProperty("cpu_shadowed", cpuShadowed);
  RecordProperty("gpu_shadowed", gpuShadowed);
  RecordProperty("agreement", std::to_string(agreement));
  EXPECT_GT(covered, kW * kH / 3);
  EXPECT_GT(cpuShadowed, covered / 10) << "the scene must contain real shadows";
  EXPECT_GE(agreement, 0.95) << covered << " covered, CPU " << cpuShadowed << " shadowed, GPU "
                             << gpuShadowed;
}

TEST_F(ShadowGpu, DepthOnlyCastersWriteTheSameDepth) {
  // TerrainView::Depth drops the fragment shader's work and, without holes, its discard: every cascade's
  // depth must equal the shading program's, except a few texels on the terrain's outer edge, where the
  // interpolated position rounds a hair outside the extent and the shading program discards them. With holes
  // it falls back to the discarding program: equal bit for bit, and the holes stay open (the control: more
  // texels keep the cleared depth than without holes, so a program that filled them would fail).
  int clearedWithout = 0;
  for (const bool holes : {false, true}) {
    Terrain scene(shaders(), true, holes);
    const ShadowSettings settings = testSettings();
    const ShadowCascades fit = fitCascades(viewCamera(), float(kW) / float(kH), kSun, settings, scene.bounds);
    ShadowMaps shaded(settings.size, settings.cascades);
    ShadowMaps depth(settings.size, settings.cascades);
    scene.renderShadows(shaded, fit, terrain::TerrainView::Shaded);
    scene.renderShadows(depth, fit, terrain::TerrainView::Depth);
    int cleared = 0;
    for (int i = 0; i < settings.cascades; ++i) {
      const Image a = shaded.downloadDepth(i);
      const Image b = depth.downloadDepth(i);
      int differ = 0;
      int edge = 0;
      for (int y = 0; y < a.height(); ++y) {
        for (int x = 0; x < a.width(); ++x) {
          cleared += a.get(x, y, 0) == 1.0f ? 1 : 0;
          if (a.get(x, y, 0) != b.get(x, y, 0)) {
            ++differ;
            edge += a.get(x, y, 0) == 1.0f ? 1 : 0;
          }
        }
      }
      if (holes) {
        EXPECT_EQ(differ, 0) << "cascade " << i << " with holes";
      } else {
        EXPECT_EQ(edge, differ) << "cascade " << i << ": texels the shading program drew differ";
        EXPECT_LE(differ, 8) << "cascade " << i;
      }
    }
    if (holes) {
      EXPECT_GT(cleared, clearedWithout + 100);
    } else {
      clearedWithout = cleared;
    }
  }
}

TEST_F(ShadowGpu, FlatGroundHasNoDarkRegion) {
  Terrain scene(shaders(), false);
  const Camera camera = viewCamera();
  const float aspect = static_cast<float>(kW) / static_cast<float>(kH);
  const ShadowSettings settings = testSettings();
  const ShadowCascades fit = fitCascades(camera, aspect, kSun, settings, scene.bounds);
  ShadowMaps maps(settings.size, settings.cascades);
  scene.renderShadows(maps, fit);
  maps.bind();
  const Image lit = scene.shaded(camera, ShadowFrame{});
  const Image shadowed = scene.shaded(camera, toFrame(fit, settings));
  ShadowMaps::unbind();
  int covered = 0;
  int dark = 0;
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const float off = luminance(lit, x, y);
      if (off <= 0.0f) {
        continue;
      }
      ++covered;
      dark += luminance(shadowed, x, y) < 0.97f * off ? 1 : 0;
    }
  }
  EXPECT_GT(covered, kW * kH / 3);
  EXPECT_EQ(dark, 0) << "shadow acne on flat ground";
}

/** Evaluates sunVisibility(point, normal) on the GPU for a list of world points (compute shader). */
class VisibilityProbe {
public:
  explicit VisibilityProbe(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals)
      : mCount(static_cast<int>(points.size())), mPoints(pack(points)), mNormals(pack(normals)),
        mOut(points.size() * sizeof(float)) {
    // A throw-away library: the probe next to links to the real shader folders it includes.
    const std::filesystem::path source = shader::Library::sourceDirectory();
    std::filesystem::create_directory_symlink(source / "common", mDir / "common");
    std::filesystem::create_directory_symlink(source / "shared", mDir / "shared");
    std::ofstream(mDir / "probe.comp") << R"(#version 450 core
#include "common/shadows.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) readonly buffer Normals { vec4 normals[]; };
layout(std430, binding = 2) writeonly buffer Visibility { float visibility[]; };
uniform int count;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i < count) {
    visibility[i] = sunVisibility(points[i].xyz, normals[i].xyz);
  }
}
)";
    mProgram = shader::compileProgram(shader::Library(mDir.path()), {"shadow probe", {"probe.comp"}, {}});
  }

  /** Visibility of every point with the frame block as `camera` and `shadows` set it. */
  std::vector<float> run(const Camera& camera, const ShadowFrame& shadows) {
    Environment environment;
    environment.sunDirection = kSun;
    environment.shadows = shadows;
    mFrame.update(camera, kW, kH, 0.0, environment);
    mFrame.bind();
    mPoints.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    mNormals.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    mOut.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    mProgram.use();
    mProgram.setUniform("count", mCount);
    glDispatchCompute(static_cast<GLuint>((mCount + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> out(static_cast<std::size_t>(mCount));
    mOut.getSubData(0, out.size() * sizeof(float), out.data());
    return out;
  }

private:
  static gl::Buffer pack(const std::vector<glm::vec3>& values) {
    std::vector<glm::vec4> packed;
    for (const glm::vec3& v : values) {
      packed.emplace_back(v, 0.0f);
    }
    return gl::Buffer(std::span<const glm::vec4>(packed));
  }
  int mCount;
  test::TempDir mDir;
  gl::Buffer mPoints;
  gl::Buffer mNormals;
  gl::Buffer mOut;
  gl::Program mProgram{gl::NoCreate};
  FrameUniformBuffer mFrame;
};

TEST_F(ShadowGpu, SmallCameraStepsDoNotMoveShadowTexels) {
  Terrain scene(shaders(), true);
  const float aspect = static_cast<float>(kW) / static_cast<float>(kH);
  const ShadowSettings settings = testSettings();
  // Fixed ground points east of the ridge and around the hill, where shadow edges are.
  std::vector<glm::vec3> points;
  std::vector<glm::vec3> normals;
  for (float z = 40.0f; z <= 300.0f; z += 3.7f) {
    for (float x = 90.0f; x <= 260.0f; x += 1.3f) {
      points.emplace_back(x, terrain::heightAt(scene.field, x, z), z);
      normals.push_back(terrain::normalAt(scene.field, x, z));
    }
  }
  VisibilityProbe probe(points, normals);
  ShadowMaps maps(settings.size, settings.cascades);
  const auto visibility = [&](const Camera& camera, ShadowCascades fit) {
    scene.renderShadows(maps, fit);
    maps.bind();
    std::vector<float> v = probe.run(camera, toFrame(fit, settings));
    ShadowMaps::unbind();
    return v;
  };
  const Camera base = viewCamera();
  const ShadowCascades baseFit = fitCascades(base, aspect, kSun, settings, scene.bounds);
  const std::vector<float> before = visibility(base, baseFit);
  int partial = 0;
  for (float v : before) {
    partial += v > 0.02f && v < 0.98f ? 1 : 0;
  }
  RecordProperty("probe_points", static_cast<int>(points.size()));
  RecordProperty("edge_points", partial);
  EXPECT_GT(partial, 100) << "probe points must sit on shadow edges";

  // Comparable points: same cascade before and after, away from the last cascade's fade.
  const ShadowFrame baseFrame = toFrame(baseFit, settings);
  const auto comparable = [&](const Camera& camera, const ShadowFrame& frame, std::size_t k) {
    const int a = cascadeFor(baseFrame, base.view(), points[k]);
    const int b = cascadeFor(frame, camera.view(), points[k]);
    const float depth = -(camera.view() * glm::vec4(points[k], 1.0f)).z;
    return a == b && a >= 0 && depth < 0.85f * frame.splits[settings.cascades - 1];
  };
  int compared = 0;
  float worst = 0.0f;
  int moved = 0;
  for (int step = 1; step <= 4; ++step) {
    const Camera camera = viewCamera(glm::vec3(0.13f, 0.04f, -0.11f) * static_cast<float>(step));
    const ShadowCascades fit = fitCascades(camera, aspect, kSun, settings, scene.bounds);
    const ShadowFrame frame = toFrame(fit, settings);
    for (std::size_t c = 0; c < fit.cascades.size(); ++c) {
      moved += fit.cascades[c].shadow != baseFit.cascades[c].shadow ? 1 : 0;
    }
    const std::vector<float> after = visibility(camera, fit);
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (comparable(camera, frame, k)) {
        ++compared;
        worst = std::max(worst, std::abs(after[k] - before[k]));
      }
    }
  }
  EXPECT_GT(moved, 0) << "the cascades followed the camera";
  EXPECT_GT(compared, static_cast<int>(points.size()));
  RecordProperty("compared", compared);
  RecordProperty("worst_difference", std::to_string(worst));
  EXPECT_LE(worst, 1.0f / 64.0f) << "shadows swim: a fixed point's visibility changed";

  // Control: the same maps shifted by a fraction of a texel (what an unsnapped cascade does) change it.
  ShadowCascades shifted = baseFit;
  for (ShadowCascade& cascade : shifted.cascades) {
    const glm::vec3 right = glm::normalize(glm::cross(cascade.camera.forward(), cascade.camera.up));
    cascade.camera.position += right * (0.37f * cascade.texelSize);
    cascade.camera.target += right * (0.37f * cascade.texelSize);
    cascade.shadow = glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) *
                     glm::scale(glm::mat4(1.0f), glm::vec3(0.5f)) * cascade.camera.viewProjection(1.0f);
  }
  const std::vector<float> swum = visibility(base, shifted);
  float swumWorst = 0.0f;
  for (std::size_t k = 0; k < points.size(); ++k) {
    swumWorst = std::max(swumWorst, std::abs(swum[k] - before[k]));
  }
  RecordProperty("unsnapped_worst_difference", std::to_string(swumWorst));
  EXPECT_GT(swumWorst, 0.05f) << "the probe must see sub-texel shifts";
}

// The documentation's picture (docs/scenes.md "Sun shadows"): a ridged procedural landscape under a low sun,
// without (top) and with (bottom) cascaded shadows. Runs only with SYLVA_SHADOW_PICTURE=<output.png>.
TEST_F(ShadowGpu, DocumentationPicture) {
  const char* output = std::getenv("SYLVA_SHADOW_PICTURE");
  if (output == nullptr) {
    GTEST_SKIP() << "set SYLVA_SHADOW_PICTURE=<file.png> to render the documentation picture";
  }
  terrain::ProceduralSpec spec;
  spec.seed = 7;
  spec.type = terrain::ProceduralSpec::Type::Ridged;
  spec.frequency = 1.0f / 300.0f;
  spec.heightScale = 90.0f;
  const terrain::HeightField field = terrain::generate(spec, 0.0, 0.0, 513, 513, 2.0f);
  terrain::QuadtreeConfig config;
  config.rootSize = 128.0f;
  config.maxDepth = 4;
  terrain::Quadtree quadtree(config, field);
  terrain::TerrainRenderer renderer(shaders(), field, terrain::defaultSplatLayers(0.0f, 90.0f));
  const int w = 640;
  const int h = 300;
  const float aspect = static_cast<float>(w) / static_cast<float>(h);
  Camera camera;
  camera.position = {500.0f, terrain::heightAt(field, 500.0f, 900.0f) + 45.0f, 900.0f};
  camera.target = {520.0f, 20.0f, 650.0f};
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 0.5f;
  camera.farPlane = 2000.0f;
  const glm::vec3 sun = glm::normalize(glm::vec3(-0.8f, 0.3f, -0.5f));
  const Frustum frustum = camera.frustum(aspect);
  const terrain::QuadtreeSelection selection = quadtree.select(camera.position, &frustum);
  ShadowSettings settings;
  settings.cascades = 4;
  settings.size = 2048;
  settings.distance = 900.0f;
  const ShadowCascades fit =
      fitCascades(camera, aspect, sun, settings, Aabb{{0.0f, -1.0f, 0.0f}, {1024.0f, 100.0f, 1024.0f}});
  ShadowMaps maps(settings.size, settings.cascades);
  // Wall-clock costs (glFinish around each pass, best of 3), printed for the documentation; nothing is
  // asserted.
  const auto timed = [](const auto& pass) {
    double best = 1e30;
    for (int k = 0; k < 3; ++k) {
      glFinish();
      const auto start = std::chrono::steady_clock::now();
      pass();
      glFinish();
      best = std::min(
          best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    return best;
  };
  const double shadowMs = timed([&] {
    for (int i = 0; i < settings.cascades; ++i) {
      const ShadowCascade& cascade = fit.cascades[static_cast<std::size_t>(i)];
      const Frustum shadowFrustum = cascade.camera.frustum(1.0f);
      const terrain::QuadtreeSelection casters = quadtree.select(camera.position, &shadowFrustum);
      maps.begin(i);
      renderer.draw(casters, cascade.camera, maps.size(), maps.size(), 0.0);
      maps.end();
    }
  });
  maps.bind();
  Image picture(w, 2 * h, 4, PixelType::U8);
  double mainMs[2] = {0.0, 0.0};
  for (int half = 0; half < 2; ++half) {
    RenderTarget target(w, h);
    terrain::TerrainDrawOptions options;
    options.environment.sunDirection = sun;
    options.environment.fogDensity = 0.0006f;
    options.environment.shadows = half == 1 ? toFrame(fit, settings) : ShadowFrame{};
    mainMs[half] = timed([&] {
      target.begin(glm::vec4(0.55f, 0.68f, 0.85f, 1.0f));
      renderer.draw(selection, camera, w, h, 0.0, nullptr, options);
    });
    const Image image = target.readColor();
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        for (int c = 0; c < 4; ++c) {
          picture.set(x, y + half * h, c, image.get(x, y, c));
        }
      }
    }
  }
  std::printf("shadow maps (%d x %d^2): %.2f ms; terrain %dx%d without shadows %.2f ms, with %.2f ms\n",
              settings.cascades, settings.size, shadowMs, w, h, mainMs[0], mainMs[1]);
  ShadowMaps::unbind();
  saveImage(output, picture);
}

} // namespace
} // namespace sylva::render
