#include <sylva/terrain/gpu/TerrainScene.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace sylva::terrain {

namespace {

/** `field` with every height multiplied by `factor` (validated > 0 and finite). */
HeightField exaggerated(HeightField field, float factor) {
  if (!std::isfinite(factor) || factor <= 0.0f) {
    fail("terrain: exaggeration {} must be finite and > 0", factor);
  }
  if (factor != 1.0f) {
    for (float& h : field.samples()) {
      h *= factor;
    }
  }
  return field;
}

} // namespace

std::unique_ptr<TerrainScene> TerrainScene::fromSetup(const shader::Library& library,
                                                      const TerrainSetup& setup,
                                                      const TerrainFieldName& name) {
  // Limits known before any work: the GPU's largest texture.
  GLint maxTexture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
  LoadedTerrain loaded = loadTerrainSetup(setup, name, maxTexture,
                                          fmt::format("the GPU's largest texture side is {}", maxTexture));
  TerrainSceneOptions options;
  options.geomorph = setup.geomorph;
  options.exaggeration = setup.exaggeration;
  options.layers = std::move(loaded.layers);
  options.seaLevel = loaded.seaLevel;
  const QuadtreeConfig config = loaded.config;
  HeightField heights = std::move(loaded.heights);
  std::optional<Progress> progress;
  if (heights.samples().size() > kProgressSamples) {
    progress.emplace("building terrain (min/max tree, GPU normal and splat maps)", 1);
  }
  auto scene = std::make_unique<TerrainScene>(library, std::move(heights), config, std::move(options));
  if (progress) {
    progress->advance();
  }
  return scene;
}

TerrainScene::TerrainScene(const shader::Library& library, HeightField field, const QuadtreeConfig& config,
                           std::vector<SplatLayer> layers)
    : TerrainScene(library, std::move(field), config, TerrainSceneOptions{std::move(layers), 1.0f, {}}) {}

TerrainScene::TerrainScene(const shader::Library& library, HeightField field, const QuadtreeConfig& config,
                           TerrainSceneOptions options)
    : mOptions(std::move(options)), mField(exaggerated(std::move(field), mOptions.exaggeration)),
      mInfo(heightFieldInfo(mField)), mQuadtree(config, mField) {
  if (mOptions.seaLevel && !std::isfinite(*mOptions.seaLevel)) {
    fail("terrain: sea level {} must be finite", *mOptions.seaLevel);
  }
  std::vector<SplatLayer> layers = mOptions.layers;
  if (layers.empty()) {
    const float e = mOptions.exaggeration;
    layers = defaultSplatLayers(mInfo.minHeight / e, mInfo.maxHeight / e, mOptions.seaLevel);
  }
  mRenderer = std::make_unique<TerrainRenderer>(library, mField, std::move(layers), SobelOptions{},
                                                mOptions.exaggeration);
}

const QuadtreeSelection& TerrainScene::update(const render::Camera& camera, float aspect,
                                              int viewportHeightPx) {
  const Frustum frustum = mFrozen ? *mFrozen : camera.frustum(aspect);
  if (viewportHeightPx > 0 && mQuadtree.config().lodErrorPixels > 0.0f && camera.orthoHeight <= 0.0f) {
    const float scale = QuadtreeConfig::pixelsPerRadianFor(static_cast<float>(viewportHeightPx), camera.fovY);
    if (scale != mQuadtree.config().pixelsPerRadian) {
      QuadtreeConfig config = mQuadtree.config();
      config.pixelsPerRadian = scale;
      mQuadtree.setConfig(config);
    }
  }
  const auto start = std::chrono::steady_clock::now();
  mQuadtree.select(camera.position, &frustum, mSelection);
  mLastUpdateMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return mSelection;
}

void TerrainScene::draw(const render::Camera& camera, int width, int height, double time,
                        render::GpuTimers* timers, const TerrainDrawOptions& options) {
  mRenderer->draw(mSelection, camera, width, height, time, timers, options);
}

void TerrainScene::setQuadtreeConfig(const QuadtreeConfig& config) {
  if (mQuadtree.canSetConfig(config)) {
    mQuadtree.setConfig(config);
  } else {
    mQuadtree = Quadtree(config, mField);
  }
}

Aabb TerrainScene::bounds() const {
  float lo = mInfo.minHeight;
  float hi = mInfo.maxHeight;
  if (mOptions.seaLevel) {
    const float water = *mOptions.seaLevel * mOptions.exaggeration;
    lo = std::min(lo, water);
    hi = std::max(hi, water);
  }
  return Aabb{glm::vec3(0.0f, lo, 0.0f), glm::vec3(mField.extentX(), hi, mField.extentZ())};
}

render::Camera TerrainScene::frameCamera(render::ViewFrom from, float fovY, float aspect) const {
  const Aabb box = bounds();
  return render::frameBox(box, from, fovY, aspect, box.center());
}

render::Environment TerrainScene::environment(const render::Camera& camera, float fog) const {
  render::Environment environment;
  environment.fogDensity = render::fogDensityFor(camera.position, bounds(), fog);
  return environment;
}

TerrainDrawOptions TerrainScene::drawOptions(const render::Camera& camera, float fog) const {
  TerrainDrawOptions options;
  options.environment = environment(camera, fog);
  options.geomorph = mOptions.geomorph;
  if (mOptions.seaLevel) {
    options.waterLevel = *mOptions.seaLevel * mOptions.exaggeration;
  }
  // Layer textures repeat about every 12 samples, so they stay visible on kilometre-spaced DEMs as well.
  options.textureTiling = std::max(24.0f, 12.0f * std::min(mField.spacingX(), mField.spacingZ()));
  return options;
}

} // namespace sylva::terrain
