// The sky pass, the shared haze and the lens flare on the GPU against the CPU references of render/Sky.hpp:
// every sky pixel equals skyWithSun through the same rays; applyAtmosphere (as every lit pass calls it)
// equals render::aerial in mode 1 and the old fog in mode 0; the flare's visibility is 1 with nothing in
// front of the sun, 0 behind an occluder (and then adds nothing), and the CPU count of the same depth texels
// when half covered, where the ghosts are half as bright.
#include <sylva/gl/Buffer.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/render/Sky.hpp>
#include <sylva/render/gpu/SkyRenderer.hpp>
#include <sylva/shader/Compiler.hpp>

#include "GlTest.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace sylva::render {
namespace {

using SkyRendererTest = test::GlTest;

const glm::vec3 kSkySun = glm::normalize(glm::vec3(0.75f, 0.5f, -0.3f));

Environment skyEnvironment() {
  Environment env;
  env.sunDirection = kSkySun;
  env.atmosphere = Atmosphere::Sky;
  env.turbidity = 3.0f;
  env.exposure = 1.0f;
  env.fogDensity = 0.002f;
  return env;
}

/** A camera at `eye` looking `yawOffset` radians (about y) beside the sun's azimuth at `pitch` radians. */
Camera cameraNearSun(float fovDegrees, float yawOffset, float pitch) {
  Camera camera;
  camera.position = glm::vec3(3.0f, 12.0f, -7.0f);
  const float yaw = std::atan2(kSkySun.z, kSkySun.x) + yawOffset;
  camera.target = camera.position + glm::vec3(std::cos(yaw) * std::cos(pitch), std::sin(pitch),
                                              std::sin(yaw) * std::cos(pitch));
  camera.fovY = glm::radians(fovDegrees);
  camera.nearPlane = 0.5f;
  camera.farPlane = 3000.0f;
  return camera;
}

float toSrgb(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

struct Comparison {
  int worst = 0;
  int over = 0; ///< pixels with a channel more than `tolerance` levels off
};

/** GPU sky image against skyWithSun through each pixel centre's ray. */
Comparison compareSky(const Image& image, const FrameUniformBuffer& frame, const SkyParams& params,
                      int tolerance) {
  Comparison result;
  const int w = image.width();
  const int h = image.height();
  for (int row = 0; row < h; ++row) {
    for (int x = 0; x < w; ++x) {
      const glm::vec2 ndc((static_cast<float>(x) + 0.5f) / static_cast<float>(w) * 2.0f - 1.0f,
                          1.0f - (static_cast<float>(row) + 0.5f) / static_cast<float>(h) * 2.0f);
      const glm::vec3 dir = skyViewDirection(frame.data().viewProj, frame.data().view, ndc);
      const glm::vec3 c = skyWithSun(dir, kSkySun, params);
      int pixelWorst = 0;
      for (int ch = 0; ch < 3; ++ch) {
        const int cpu = static_cast<int>(std::lround(toSrgb(c[ch]) * 255.0f));
        const int gpu = static_cast<int>(std::lround(image.get(x, row, ch) * 255.0f));
        pixelWorst = std::max(pixelWorst, std::abs(cpu - gpu));
      }
      result.worst = std::max(result.worst, pixelWorst);
      result.over += pixelWorst > tolerance ? 1 : 0;
    }
  }
  return result;
}

TEST_F(SkyRendererTest, SkyPassEqualsTheCpuSkyPerPixel) {
  SkyRenderer sky(shaders());
  FrameUniformBuffer frame;
  const Environment env = skyEnvironment();
  const SkyParams params = skyParamsFrom(env);
  // A wide view from below the horizon to high up, and a narrow one on the sun (its disc ~7 px in radius).
  for (const auto& [fov, pitch] : {std::pair{70.0f, 0.35f}, std::pair{6.0f, std::asin(kSkySun.y)}}) {
    RenderTarget target(96, 64);
    const Camera camera = cameraNearSun(fov, 0.0f, pitch);
    frame.update(camera, target.width(), target.height(), 0.0, env);
    frame.bind();
    target.begin(glm::vec4(1.0f, 0.0f, 1.0f, 1.0f));
    sky.drawSky();
    const Image image = target.readColor();
    // GPU acos/exp/pow are not correctly rounded: one 8-bit level (measured on llvmpipe: 1, disc included);
    // 2 on at most 4 pixels leaves room for the sun disc's soft rim (a smoothstep over 0.002 rad) elsewhere.
    const Comparison c = compareSky(image, frame, params, 1);
    if (std::getenv("SYLVA_TEST_VERBOSE") != nullptr) {
      std::printf("sky fov %.0f: worst %d levels, %d pixels over 1\n", fov, c.worst, c.over);
    }
    EXPECT_LE(c.over, 4) << "fov " << fov << ", worst " << c.worst;
    EXPECT_LE(c.worst, 2) << "fov " << fov;
    if (fov < 10.0f) {
      // The sun's disc is at the centre and white.
      EXPECT_EQ(image.get(48, 32, 0), 1.0f);
      EXPECT_EQ(image.get(48, 32, 2), 1.0f);
    }
    // No depth writes: the depth stays cleared.
    const Image depth = target.readDepth();
    EXPECT_EQ(depth.get(10, 10, 0), 1.0f);
    EXPECT_EQ(depth.get(90, 60, 0), 1.0f);
  }
}

TEST_F(SkyRendererTest, SkyOnlyFillsPixelsNothingCovered) {
  SkyRenderer sky(shaders());
  FrameUniformBuffer frame;
  RenderTarget target(64, 48);
  frame.update(cameraNearSun(60.0f, 0.2f, 0.2f), 64, 48, 0.0, skyEnvironment());
  frame.bind();
  target.begin(glm::vec4(1.0f, 0.0f, 1.0f, 1.0f));
  // "Opaque geometry" on the left half: depth 0.5 through a scissored clear.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 32, 48);
  target.framebuffer().clearDepth(0.5f);
  glDisable(GL_SCISSOR_TEST);
  sky.drawSky();
  const Image image = target.readColor();
  EXPECT_EQ(image.get(5, 20, 0), 1.0f); // magenta clear colour kept
  EXPECT_EQ(image.get(5, 20, 1), 0.0f);
  EXPECT_GT(image.get(50, 20, 1), 0.2f); // sky drawn
}

TEST_F(SkyRendererTest, AtmosphereMatchesTheCpuAerialAndTheOldFog) {
  const gl::Program probe =
      shader::compileProgram(shaders(), {"probe", {"render/atmosphere_probe.comp"}, {}});
  FrameUniformBuffer frame;
  Camera camera = cameraNearSun(60.0f, 0.0f, 0.0f);
  // Surfaces of known colours at known places: near and far, below the horizon, above it, towards the sun and
  // away from it.
  std::vector<glm::vec4> points;
  std::vector<glm::vec3> lit;
  std::vector<glm::vec3> world;
  for (int i = 0; i < 96; ++i) {
    const float azimuth = 0.37f * static_cast<float>(i);
    const float elevation = -0.6f + 0.8f * static_cast<float>(i % 7) / 6.0f;
    const float distance = 5.0f * std::pow(1.09f, static_cast<float>(i));
    const glm::vec3 dir(std::cos(azimuth) * std::cos(elevation), std::sin(elevation),
                        std::sin(azimuth) * std::cos(elevation));
    lit.push_back(
        glm::vec3(0.05f + 0.01f * static_cast<float>(i % 5), 0.3f, 0.6f - 0.005f * static_cast<float>(i)));
    world.push_back(camera.position + dir * distance);
    points.push_back(glm::vec4(lit.back(), 0.0f));
    points.push_back(glm::vec4(world.back(), 0.0f));
  }
  const gl::Buffer input{std::span<const glm::vec4>(points)};
  const gl::Buffer output(lit.size() * sizeof(glm::vec4));
  for (Atmosphere mode : {Atmosphere::Sky, Atmosphere::Fog}) {
    Environment env = skyEnvironment();
    env.atmosphere = mode;
    frame.update(camera, 64, 64, 0.0, env);
    frame.bind();
    probe.use();
    probe.setUniform("uCount", static_cast<unsigned>(lit.size()));
    input.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    output.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    glDispatchCompute(static_cast<GLuint>((lit.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    const std::vector<glm::vec4> gpu = output.read<glm::vec4>();
    float worst = 0.0f;
    for (std::size_t i = 0; i < lit.size(); ++i) {
      const glm::vec3 toSurface = world[i] - camera.position;
      const float distance = glm::length(toSurface);
      glm::vec3 cpu;
      if (mode == Atmosphere::Sky) {
        cpu = aerial(lit[i], toSurface / distance, distance, kSkySun, skyParamsFrom(env));
      } else {
        const float fog = std::clamp(1.0f - std::exp(-env.fogDensity * distance), 0.0f, 1.0f);
        cpu = glm::mix(lit[i], env.fogColor, fog);
      }
      worst = std::max(worst, glm::length(glm::vec3(gpu[i]) - cpu));
    }
    // Float sky maths on the GPU (acos, exp, tan not correctly rounded): far below one 8-bit level.
    EXPECT_LT(worst, 1e-3f) << "mode " << static_cast<int>(mode);
  }
}

TEST_F(SkyRendererTest, TurbidityAndSunElevationGrid) {
  // Panels of the sky pass for turbidity 2, 3, 6, 10 (columns) and the sun 5°, 20°, 45° up (rows), each
  // looking 60° away from the sun's azimuth. Clearer skies are bluer at the top of every panel;
  // SYLVA_TEST_IMAGES=dir also saves the grid (docs/images/sky-turbidity.png).
  const int pw = 160;
  const int ph = 90;
  const float turbidities[] = {2.0f, 3.0f, 6.0f, 10.0f};
  const float elevations[] = {5.0f, 20.0f, 45.0f};
  SkyRenderer sky(shaders());
  FrameUniformBuffer frame;
  Image grid(4 * pw, 3 * ph, 4, PixelType::U8);
  for (int row = 0; row < 3; ++row) {
    float previousBlueOverRed = 1e9f;
    for (int col = 0; col < 4; ++col) {
      Environment env = skyEnvironment();
      const float e = glm::radians(elevations[row]);
      env.sunDirection = glm::vec3(std::cos(e), std::sin(e), 0.0f);
      env.turbidity = turbidities[col];
      env.exposure = skyAutoExposure(env.sunDirection, env.turbidity);
      Camera camera;
      camera.position = glm::vec3(0.0f, 2.0f, 0.0f);
      camera.target = camera.position + glm::vec3(std::cos(1.05f), 0.45f, std::sin(1.05f));
      camera.fovY = glm::radians(75.0f);
      RenderTarget target(pw, ph);
      frame.update(camera, pw, ph, 0.0, env);
      frame.bind();
      target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      sky.drawSky();
      const Image panel = target.readColor();
      const float blueOverRed = panel.get(pw / 2, 2, 2) / panel.get(pw / 2, 2, 0);
      EXPECT_LT(blueOverRed, previousBlueOverRed) << "T " << turbidities[col] << ", sun " << elevations[row];
      previousBlueOverRed = blueOverRed;
      for (int y = 0; y < ph; ++y) {
        for (int x = 0; x < pw; ++x) {
          for (int ch = 0; ch < 4; ++ch) {
            grid.set(col * pw + x, row * ph + y, ch, panel.get(x, y, ch));
          }
        }
      }
    }
  }
  if (const char* dir = std::getenv("SYLVA_TEST_IMAGES")) {
    saveImage(std::filesystem::path(dir) / "sky-turbidity.png", grid);
  }
}

struct FlareRun {
  Image image;
  float visibility = 0.0f;
  glm::vec4 sunPixel{0.0f};
  Image depth;
};

/** Sky, optional occluder over window pixels x < `coverRight` (depth 0.3), then the flare (strength s). */
FlareRun renderFlare(const shader::Library& library, int coverRight, float strength) {
  const int w = 128;
  const int h = 96;
  SkyRenderer sky(library);
  FrameUniformBuffer frame;
  RenderTarget target(w, h);
  // Exposure 0.4: at 1 the sky around the sun is saturated white and additive ghosts could not show.
  Environment env = skyEnvironment();
  env.exposure = 0.4f;
  frame.update(cameraNearSun(50.0f, -0.12f, std::asin(kSkySun.y) - 0.08f), w, h, 0.0, env);
  frame.bind();
  target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  if (coverRight > 0) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, coverRight, h);
    target.framebuffer().clearDepth(0.3f);
    target.framebuffer().clearColor(0, glm::vec4(0.2f, 0.2f, 0.2f, 1.0f));
    glDisable(GL_SCISSOR_TEST);
  }
  sky.drawSky();
  FlareSettings settings;
  settings.strength = strength;
  settings.minSampleRadiusPixels = 3.0f;
  sky.drawFlare(target.depth(), settings);
  FlareRun run;
  run.image = target.readColor();
  run.visibility = sky.lastFlareVisibility();
  run.sunPixel = sky.lastSunPixel();
  run.depth = target.readDepth();
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  return run;
}

float channelSum(const Image& a, int x, int row) {
  return a.get(x, row, 0) + a.get(x, row, 1) + a.get(x, row, 2);
}

TEST_F(SkyRendererTest, FlareFullClearZeroOccludedHalfWhenHalfCovered) {
  const FlareRun plain = renderFlare(shaders(), 0, 0.0f);
  const FlareRun full = renderFlare(shaders(), 0, 1.0f);
  // The sun where the CPU projects it.
  const glm::vec4 cpuSun = sunScreenPosition(
      [&] {
        FrameUniformBuffer f;
        f.update(cameraNearSun(50.0f, -0.12f, std::asin(kSkySun.y) - 0.08f), 128, 96, 0.0, skyEnvironment());
        return f.data().viewProj;
      }(),
      kSkySun, 128, 96, 3.0f);
  EXPECT_NEAR(full.sunPixel.x, cpuSun.x, 1e-2f);
  EXPECT_NEAR(full.sunPixel.y, cpuSun.y, 1e-2f);
  EXPECT_EQ(full.sunPixel.z, 1.0f);
  EXPECT_NEAR(full.sunPixel.w, cpuSun.w, 1e-4f);
  ASSERT_GT(cpuSun.x, 70.0f) << "the sun must be right of the centre for the occluder cases";
  ASSERT_LT(cpuSun.x, 110.0f);

  EXPECT_EQ(full.visibility, 1.0f);
  EXPECT_EQ(plain.visibility, 1.0f);
  // Ghosts add light where the CPU geometry puts them (sprite centres; the last ghost mirrors the sun).
  const glm::vec2 sunNdc = glm::vec2(cpuSun) / glm::vec2(128.0f, 96.0f) * 2.0f - 1.0f;
  int brighter = 0;
  for (const FlareGhost& g : flareGhosts(sunNdc)) {
    const int x = static_cast<int>((g.centre.x * 0.5f + 0.5f) * 128.0f);
    const int row = 95 - static_cast<int>((g.centre.y * 0.5f + 0.5f) * 96.0f);
    if (x >= 0 && x < 128 && row >= 0 && row < 96) {
      brighter += channelSum(full.image, x, row) > channelSum(plain.image, x, row) + 0.02f ? 1 : 0;
    }
  }
  EXPECT_GE(brighter, 6);
  EXPECT_NE(full.image, plain.image);

  // An occluder over the whole sun disc: visibility 0 and not one pixel changed by the flare.
  const FlareRun hiddenPlain = renderFlare(shaders(), 128, 0.0f);
  const FlareRun hidden = renderFlare(shaders(), 128, 1.0f);
  EXPECT_EQ(hidden.visibility, 0.0f);
  EXPECT_EQ(hidden.image, hiddenPlain.image);

  // Half covered: the GPU counts exactly the texels the CPU counts on the same depth, and the halo (linear in
  // visibility) is that fraction as bright.
  const int half = static_cast<int>(std::lround(cpuSun.x));
  const FlareRun halfPlain = renderFlare(shaders(), half, 0.0f);
  const FlareRun halved = renderFlare(shaders(), half, 1.0f);
  const Image& depth = halved.depth;
  const float cpuVisibility =
      flareVisibility(cpuSun, 128, 96, [&](int x, int y) { return depth.get(x, 95 - y, 0); });
  EXPECT_EQ(halved.visibility, cpuVisibility);
  if (std::getenv("SYLVA_TEST_VERBOSE") != nullptr) {
    std::printf("flare: sun at pixel (%.2f, %.2f), visibility half covered %.4f\n", cpuSun.x, cpuSun.y,
                halved.visibility);
  }
  EXPECT_GT(halved.visibility, 0.3f);
  EXPECT_LT(halved.visibility, 0.7f);
  // On the occluder beside the sun, inside the halo: the added light is that fraction of what a flare at full
  // visibility adds over the same occluder (one that stops short of the sample disc), within 8-bit rounding.
  const FlareRun besidePlain = renderFlare(shaders(), half - 4, 0.0f);
  const FlareRun beside = renderFlare(shaders(), half - 4, 1.0f);
  EXPECT_EQ(beside.visibility, 1.0f);
  const int x = half - 5;
  const int row = 95 - static_cast<int>(cpuSun.y);
  for (int ch = 0; ch < 3; ++ch) {
    const float added = halved.image.get(x, row, ch) - halfPlain.image.get(x, row, ch);
    const float addedFull = beside.image.get(x, row, ch) - besidePlain.image.get(x, row, ch);
    EXPECT_GT(addedFull, 0.05f) << ch;
    EXPECT_NEAR(added, halved.visibility * addedFull, 2.5f / 255.0f) << ch;
  }
}

} // namespace
} // namespace sylva::render
