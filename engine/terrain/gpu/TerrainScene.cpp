#include <sylva/terrain/TerrainScene.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <chrono>

namespace sylva::terrain {

ProceduralSpec TerrainSource::defaultProcedural() {
  return defaultLandscapeSpec();
}

HeightField loadTerrainSource(const TerrainSource& source) {
  if (!source.dem.empty()) {
    return loadHeightField(source.dem, source.load);
  }
  return generate(source.procedural, 0.0, 0.0, source.proceduralSize, source.proceduralSize,
                  source.proceduralSpacing);
}

TerrainScene::TerrainScene(const shader::Library& library, HeightField field, const QuadtreeConfig& config,
                           std::vector<SplatLayer> layers)
    : mField(std::move(field)), mInfo(heightFieldInfo(mField)), mQuadtree(config, mField) {
  if (layers.empty()) {
    layers = defaultSplatLayers(mInfo.minHeight, mInfo.maxHeight);
  }
  mRenderer = std::make_unique<TerrainRenderer>(library, mField, std::move(layers));
}

const QuadtreeSelection& TerrainScene::update(const render::Camera& camera, float aspect) {
  const Frustum frustum = mFrozen ? *mFrozen : camera.frustum(aspect);
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
  const QuadtreeConfig& current = mQuadtree.config();
  const bool sameLayout = (config.rootsX == 0 || config.rootsX == current.rootsX) &&
                          (config.rootsZ == 0 || config.rootsZ == current.rootsZ) &&
                          config.rootSize == current.rootSize && config.maxDepth == current.maxDepth;
  if (sameLayout) {
    mQuadtree.setConfig(config);
  } else {
    mQuadtree = Quadtree(config, mField);
  }
}

render::Camera TerrainScene::defaultCamera() const {
  const float ex = mField.extentX();
  const float ez = mField.extentZ();
  const float span = std::max(ex, ez);
  const float relief = std::max(mInfo.maxHeight - mInfo.minHeight, 1.0f);
  render::Camera camera;
  camera.position = {0.02f * ex, mInfo.maxHeight + 0.4f * relief + 0.1f * span, 1.0f * ez};
  camera.target = {0.5f * ex, mInfo.minHeight, 0.42f * ez};
  camera.nearPlane = std::max(0.1f, 0.0005f * span);
  camera.farPlane = 4.0f * span + 4.0f * relief;
  camera.fovY = glm::radians(55.0f);
  return camera;
}

} // namespace sylva::terrain

namespace sylva::terrain {

render::Environment TerrainScene::environment() const {
  render::Environment environment;
  environment.fogDensity = 0.9f / std::max(mField.extentX(), mField.extentZ());
  return environment;
}

} // namespace sylva::terrain
