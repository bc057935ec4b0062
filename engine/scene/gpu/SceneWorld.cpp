#include <sylva/scene/gpu/SceneWorld.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/physics/World.hpp>
#include <sylva/render/Shadows.hpp>
#include <sylva/scene/gpu/GrassSimulation.hpp>
#include <sylva/scene/gpu/Ground.hpp>
#include <sylva/scene/SceneForest.hpp>
#include <sylva/scene/SceneGrass.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>
#include <sylva/scene/SceneTerrain.hpp>
#include <sylva/scene/gpu/ShoreWater.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/TerrainMaps.hpp>
#include <sylva/trees/Forest.hpp>
#include <sylva/trees/Species.hpp>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <cmath>

namespace sylva::scene {

wind::WindSettings windSettings(const WindDesc& desc) {
  wind::WindSettings w;
  const float a = glm::radians(desc.direction);
  w.direction = {std::sin(a), -std::cos(a)}; // clockwise from north (−z), the way it blows
  w.speed = desc.speed;
  w.gustStrength = desc.gusts;
  w.seed = desc.seed;
  return w;
}

SceneWorld::SceneWorld(const shader::Library& library, SceneDesc desc)
    : mLibrary(library), mDesc(std::move(desc)) {
  mWind = windSettings(mDesc.wind);

  mTerrain = terrain::TerrainScene::fromSetup(library, terrainSetup(mDesc.terrain),
                                              sceneFieldName(mDesc, "/terrain"));
  log::info("scene {}: terrain {}×{} samples, {:.0f}×{:.0f} m", mDesc.name, mTerrain->field().width(),
            mTerrain->field().height(), mTerrain->field().extentX(), mTerrain->field().extentZ());

  mSimulatedGrass = simulatedGrassLayer(mDesc);
  for (std::size_t i = 0; i < mDesc.grass.size(); ++i) {
    mGrass.push_back(makeGrass(i, mDesc.grass[i]));
  }

  for (std::size_t i = 0; i < mDesc.forests.size(); ++i) {
    trees::ForestSettings placement;
    mForests.push_back(makeForest(i, mDesc.forests[i], placement));
    mPlacements.push_back(placement);
  }

  const float e = mTerrain->exaggeration();
  for (const WaterDesc& w : mDesc.water) {
    ShoreSettings settings;
    settings.level = w.level * e;
    settings.band = w.band;
    settings.tile = w.tile;
    if (!w.folding.empty()) {
      settings.folding = w.folding;
    }
    mWater.push_back(std::make_unique<ShoreWater>(library, mTerrain->field(), e, settings));
  }

  const GroundHeight ground = [this](float x, float z) {
    const float h = groundHeight(x, z);
    return std::isnan(h) ? 0.0f : h;
  };
  for (const auto& [name, camera] : mDesc.cameras) {
    mCameras[name] = resolveKeys(camera, ground);
  }

  mPasses = std::make_unique<ScenePasses>(library, mDesc);
  registerPasses();
  buildSimulation();
}

SceneWorld::~SceneWorld() = default;

grass::CullSettings SceneWorld::scaledGrassCull(std::size_t i, const GrassLayer& layer) const {
  const GrassFieldName name = sceneFieldName(mDesc, "/grass/" + std::to_string(i));
  return grass::scaled(grassCullSettings(layer, name), mQuality.grassDistance);
}

std::unique_ptr<grass::GrassRenderer> SceneWorld::makeGrass(std::size_t i, const GrassLayer& layer) const {
  const GrassFieldName name = sceneFieldName(mDesc, "/grass/" + std::to_string(i));
  const grass::CullSettings cull = scaledGrassCull(i, layer);
  auto field = buildGrassField(layer, grassGround(*mTerrain), name);
  return std::make_unique<grass::GrassRenderer>(mLibrary, field, cull);
}

std::unique_ptr<trees::ForestScene> SceneWorld::makeForest(std::size_t i, const ForestDesc& f,
                                                           trees::ForestSettings& placement) const {
  const FieldName name = sceneFieldName(mDesc, "/forests/" + std::to_string(i));
  placement = forestSettings(f, mTerrain->exaggeration(), mTerrain->seaLevel(), name,
                             glm::vec2(mTerrain->field().extentX(), mTerrain->field().extentZ()),
                             terrain::snowLine(grassGround(*mTerrain).layers));
  const trees::ForestLook look = forestLook(f, name);
  auto forest = std::make_shared<trees::Forest>(trees::placeForest(mTerrain->field(), placement));
  auto scene = std::make_unique<trees::ForestScene>(mLibrary, forest, f.wind);
  scene->applyLook(look, placement, farGround(*mTerrain));
  if (forest->trees.size() < static_cast<std::size_t>(std::max(f.count, 0))) {
    // Spacing, slope, height band and region leave room for fewer trees than asked: say so, not only at info.
    log::warn("{}: /forests/{}/count: {} trees asked, {} fit (spacing {} m, slope, heights and region)",
              mDesc.path, i, f.count, forest->trees.size(), f.spacing);
  }
  log::info("scene {}: forest {}: {} trees", mDesc.name, i, forest->trees.size());
  return scene;
}

void SceneWorld::registerPasses() {
  mPasses->set(
      Pass::Terrain,
      [this](const PassInput& in) {
        const float aspect = static_cast<float>(in.width) / static_cast<float>(in.height);
        {
          const render::GpuTimerScope timed(in.timers, "lod (cpu)");
          mTerrain->setFrozenFrustum(mDrawOptions.frozenFrustum);
          mTerrain->update(in.camera, aspect, in.height);
        }
        terrain::TerrainDrawOptions options = mTerrain->drawOptions(in.camera);
        options.environment = in.environment;
        options.waterLevel.reset(); // the scene's water pass draws the lakes
        options.geomorph = mDesc.terrain.setup ? mDesc.terrain.setup->geomorph : mDesc.terrain.geomorph;
        options.view = mDrawOptions.terrainView;
        options.wireframe = mDrawOptions.wireframe;
        options.skirts = mDrawOptions.terrainSkirts;
        options.countVertices = mDrawOptions.countVertices;
        if (!mGrass.empty() && options.view == terrain::TerrainView::Shaded) {
          options.groundTint = mGrass.front()->groundTint();
        }
        mTerrain->draw(in.camera, in.width, in.height, in.time, in.timers, options);
      },
      [this](const PassInput& in) {
        // Patches chosen for the viewer (as fine as those the shadows fall on), culled by the cascade.
        mTerrain->setFrozenFrustum(in.camera.frustum(1.0f));
        mTerrain->update(*in.viewer, 1.0f);
        mTerrain->setFrozenFrustum(std::nullopt);
        terrain::TerrainDrawOptions options = mTerrain->drawOptions(in.camera);
        options.environment = in.environment;
        options.waterLevel.reset();
        options.geomorph = mDesc.terrain.setup ? mDesc.terrain.setup->geomorph : mDesc.terrain.geomorph;
        options.view = terrain::TerrainView::Depth; // depth is all a cascade keeps
        mTerrain->draw(in.camera, in.width, in.height, in.time, nullptr, options);
      });
  if (!mForests.empty()) {
    auto drawTrees = [this](const PassInput& in) {
      trees::TreeDrawOptions options;
      options.environment = in.environment;
      // Shadow draws: the distance rule measured from the sun camera (outside the casters) gives the coarsest
      // pieces, which is what a shadow map of this resolution can show; depth is all a cascade keeps, and
      // pieces under the shadow filter's footprint are skipped.
      options.view = mDrawOptions.treeView;
      trees::TreeLod lod = mDrawOptions.treeLod;
      if (in.shadow) {
        options.view = trees::TreeView::Depth;
        lod.minPixels = render::kCasterMinTexels;
        lod.minWidthPixels = std::max(lod.minWidthPixels, 1.0f);
      }
      for (auto& forest : mForests) {
        forest->draw(in.camera, in.width, in.height, in.time, lod, options, in.timers);
      }
    };
    mPasses->set(Pass::Trees, drawTrees, drawTrees);
  }
  if (!mGrass.empty()) {
    mPasses->set(Pass::Grass, [this](const PassInput& in) {
      const float aspect = static_cast<float>(in.width) / static_cast<float>(in.height);
      grass::GrassDrawOptions options;
      options.view = mDrawOptions.grassView;
      options.countPrimitives = mDrawOptions.countPrimitives;
      options.environment = in.environment;
      options.wind = mWind;
      for (auto& g : mGrass) {
        g->cull(in.camera, aspect, in.timers);
        g->draw(in.camera, in.width, in.height, in.time, in.timers, options);
      }
    });
  }
  if (mSimulatedGrass >= 0) {
    mPasses->set(Pass::Bodies, [this](const PassInput& in) {
      const render::GpuTimerScope timed(in.timers, passName(Pass::Bodies));
      mSimulation->drawBodies(in.camera, in.width, in.height, in.time, in.environment);
    });
  }
  if (!mWater.empty()) {
    mPasses->set(Pass::Water, [this](const PassInput& in) {
      const render::GpuTimerScope timed(in.timers, passName(Pass::Water));
      for (auto& w : mWater) {
        w->update(in.time);
        w->draw(in.camera, in.width, in.height, in.time, in.environment);
      }
    });
  }
}

void SceneWorld::setGrassLayer(std::size_t i, GrassLayer layer) {
  if (i > mGrass.size()) {
    fail("{}: /grass/{}: the scene has {} grass layers", mDesc.path, i, mGrass.size());
  }
  const bool simulated = static_cast<int>(i) == mSimulatedGrass;
  if (layer.simulate && mSimulatedGrass >= 0 && !simulated) {
    fail("{}: /grass/{}/simulate: only one grass layer can be simulated (layer {} already is)", mDesc.path, i,
         mSimulatedGrass);
  }
  std::unique_ptr<grass::GrassRenderer> renderer = makeGrass(i, layer); // throws: the world is unchanged
  if (simulated) {
    mSimulation.reset(); // registered with the renderer it moves: goes first
    layer.simulate = true;
  }
  if (i == mGrass.size()) {
    mGrass.push_back(std::move(renderer));
    mDesc.grass.push_back(std::move(layer));
  } else {
    mGrass[i] = std::move(renderer);
    mDesc.grass[i] = std::move(layer);
  }
  if (mDesc.grass[i].simulate && !simulated) {
    mSimulatedGrass = static_cast<int>(i);
  }
  registerPasses();
  if (mDesc.grass[i].simulate) {
    buildSimulation();
  }
}

void SceneWorld::simulateGrass(std::size_t i) {
  if (i >= mGrass.size()) {
    fail("{}: /grass/{}: the scene has {} grass layers", mDesc.path, i, mGrass.size());
  }
  if (mSimulatedGrass >= 0) {
    fail("{}: /grass/{}/simulate: only one grass layer can be simulated (layer {} already is)", mDesc.path, i,
         mSimulatedGrass);
  }
  mDesc.grass[i].simulate = true;
  mSimulatedGrass = static_cast<int>(i);
  registerPasses();
  buildSimulation();
}

void SceneWorld::clearBodies() {
  mDesc.bodies.clear();
  mDesc.drops.clear();
  buildSimulation();
}

void SceneWorld::setForest(std::size_t i, ForestDesc forest) {
  if (i > mForests.size()) {
    fail("{}: /forests/{}: the scene has {} forests", mDesc.path, i, mForests.size());
  }
  trees::ForestSettings placement;
  std::unique_ptr<trees::ForestScene> scene = makeForest(i, forest, placement); // throws: unchanged
  if (i == mForests.size()) {
    mForests.push_back(std::move(scene));
    mPlacements.push_back(placement);
    mDesc.forests.push_back(std::move(forest));
  } else {
    mForests[i] = std::move(scene);
    mPlacements[i] = placement;
    mDesc.forests[i] = std::move(forest);
  }
  registerPasses();
}

Aabb SceneWorld::bounds() {
  Aabb box = terrain().bounds();
  for (std::size_t i = 0; i < forestCount(); ++i) {
    box.min = glm::min(box.min, forest(i).bounds().min);
    box.max = glm::max(box.max, forest(i).bounds().max);
  }
  return box;
}

float SceneWorld::groundHeight(float x, float z) const {
  return terrain::heightAt(mTerrain->field(), x,
                           z); // the scene's field holds the drawn (exaggerated) heights
}

void SceneWorld::buildSimulation() {
  mSimulation.reset();
  if (mSimulatedGrass >= 0) {
    grass::GrassRenderer& g = *mGrass[static_cast<std::size_t>(mSimulatedGrass)];
    mSimulation =
        std::make_unique<GrassSimulation>(mLibrary, mTerrain->field(), g, g.fieldPointer(), mDesc.grassSim);
    for (std::size_t i = 0; i < mDesc.bodies.size(); ++i) {
      const BodyDesc& b = mDesc.bodies[i];
      physics::BodySpec spec;
      spec.shape = b.shape == BodyDesc::Shape::Ball ? physics::Shape::Sphere : physics::Shape::Box;
      spec.size = b.shape == BodyDesc::Shape::Ball ? glm::vec3(b.radius) : b.halfExtents;
      spec.position = b.position.p;
      if (b.position.aboveGround) {
        spec.position.y += groundHeight(spec.position.x, spec.position.z);
      }
      spec.velocity = b.velocity;
      spec.mass = b.mass;
      mSimulation->addBody(spec, fmt::format("{}: /bodies/{}", mDesc.path, i));
    }
    for (const BodyDrop& d : mDesc.drops) {
      mSimulation->spawnBalls(d.centre, d.radius, d.count, d.seed, d.height);
    }
  }
  for (auto& forest : mForests) {
    forest->resetWind();
  }
  mFrame = -1;
  mTime = 0.0;
}

void SceneWorld::stepTo(double time) {
  if (mSimulation) {
    mSimulation->advance(time, mWind);
  }
  for (auto& forest : mForests) {
    forest->advance(time, mWind, 1 << 20);
  }
  mTime = time;
}

void SceneWorld::advanceToFrame(int frame) {
  if (frame < mFrame) {
    buildSimulation();
  }
  if (mSimulation) {
    mSimulation->setFocus(std::nullopt); // frame-exact: every tile, whatever was drawn before
  }
  for (int f = std::max(mFrame + 1, 0); f <= frame; ++f) {
    stepTo(frameTime(f));
  }
  mFrame = std::max(mFrame, frame);
}

void SceneWorld::advanceTo(double time) {
  if (time < mTime) {
    buildSimulation();
  }
  stepTo(time);
  mFrame = -1;
}

render::Camera SceneWorld::camera(const std::string& name, double time, float aspect) const {
  const auto it = mCameras.find(name);
  if (it == mCameras.end()) {
    std::string names;
    for (const auto& [n, keys] : mCameras) {
      names += (names.empty() ? "" : ", ") + n;
    }
    fail("{}: no camera '{}' (the file has: {})", mDesc.path, name, names);
  }
  const auto c = mDesc.cameras.find(name);
  const CameraSample s = evaluate(it->second, time, c->second.loop);
  render::Camera camera;
  camera.position = s.position;
  camera.target = s.target;
  camera.fovY = glm::radians(s.fov);
  (void)aspect;
  render::fitClipPlanes(camera, mTerrain->bounds());
  return camera;
}

void SceneWorld::setDrawOptions(const SceneDrawOptions& options) {
  // The trees' rule decides which pieces cast (shadow draws keep it): cached far cascades go with it.
  if (std::memcmp(&options.treeLod, &mDrawOptions.treeLod, sizeof(options.treeLod)) != 0) {
    mPasses->invalidateShadows();
  }
  mDrawOptions = options;
  mPasses->setShadowReuse(!options.fullQuality);
}

grass::CullSettings SceneWorld::grassCull(std::size_t i) const {
  return grassCullSettings(mDesc.grass.at(i), sceneFieldName(mDesc, "/grass/" + std::to_string(i)));
}

void SceneWorld::setGrassCull(std::size_t i, const grass::CullSettings& cull) {
  grass::validate(cull);
  GrassLayer& layer = mDesc.grass.at(i);
  layer.cull = cull;
  mGrass.at(i)->setCullSettings(scaledGrassCull(i, layer));
}

void SceneWorld::setQuality(const QualityStep& step) {
  if (!(step.grassDistance > 0.0f) || !(step.renderScale > 0.0f)) {
    fail("quality: grass distance {} and render scale {} must be > 0", step.grassDistance, step.renderScale);
  }
  const bool grassChanged = step.grassDistance != mQuality.grassDistance;
  mQuality = step;
  if (grassChanged) {
    for (std::size_t i = 0; i < mGrass.size(); ++i) {
      mGrass[i]->setCullSettings(scaledGrassCull(i, mDesc.grass[i]));
    }
  }
  mPasses->setShadowsAllowed(step.shadows);
  // The water's folding frame at the resolution the smaller frame samples anyway (ShoreWater::setSwashLevel).
  const int swashLevel = static_cast<int>(std::floor(std::log2(1.0f / step.renderScale) + 1e-4f));
  for (auto& w : mWater) {
    w->setSwashLevel(swashLevel);
  }
}

void SceneWorld::draw(const render::Camera& camera, int width, int height, double time,
                      const gl::Texture* depth, render::GpuTimers* timers) {
  Aabb casters = mTerrain->bounds();
  for (auto& forest : mForests) {
    casters.min = glm::min(casters.min, forest->bounds().min);
    casters.max = glm::max(casters.max, forest->bounds().max);
  }
  if (mDesc.fog.farSide) {
    mPasses->setFogDensity(render::fogDensityFor(camera.position, mTerrain->bounds(), *mDesc.fog.farSide));
  }
  mPasses->render(camera, width, height, time, casters, depth, timers);
  if (mDrawOptions.treeView == trees::TreeView::Tiles) {
    // The tile-id view keeps the piece instance's high bits in alpha (TreeRenderer.hpp) for code that reads
    // the renderer's ids; the world's frame is a picture, opaque like every other view (a saved PNG showed
    // the trees at alpha 1/255).
    GLboolean mask[4];
    glGetBooleanv(GL_COLOR_WRITEMASK, mask);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
    const GLfloat opaque[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, opaque);
    glColorMask(mask[0], mask[1], mask[2], mask[3]);
  }
  // Real time (advanceTo): the next steps leave the simulated grass tiles this camera cannot draw held.
  if (mSimulation) {
    const float drawn = scaledGrassCull(static_cast<std::size_t>(mSimulatedGrass),
                                        mDesc.grass[static_cast<std::size_t>(mSimulatedGrass)])
                            .maxDistance;
    mSimulation->setFocus(mDrawOptions.fullQuality ? std::nullopt
                                                   : std::optional<grass::SimFocus>(
                                                         {{camera.position.x, camera.position.z}, drawn}));
  }
}

void SceneWorld::addDrop(const BodyDrop& drop) {
  if (mSimulatedGrass < 0) {
    fail("{}: /drops: balls need a grass layer with \"simulate\": true (the physics world moves the grass)",
         mDesc.path);
  }
  mDesc.drops.push_back(drop);
  buildSimulation();
}

bool SceneWorld::spawnBall(const glm::vec3& position, const glm::vec3& velocity) {
  if (!mSimulation) {
    return false;
  }
  mSimulation->spawnBall(position, velocity);
  return true;
}

std::size_t SceneWorld::bodies() const {
  return mSimulation ? mSimulation->bodies() : 0;
}

std::size_t SceneWorld::treeCount() const {
  std::size_t n = 0;
  for (const auto& forest : mForests) {
    n += forest->forest().trees.size();
  }
  return n;
}

std::size_t SceneWorld::gpuBytes() const {
  std::size_t bytes = mPasses->gpuBytes();
  for (const auto& forest : mForests) {
    bytes += forest->gpuBytes();
  }
  return bytes;
}

void SceneWorld::reloadShaders(const shader::Library& library) {
  mPasses->reloadShaders(library);
  mTerrain->renderer().reloadShaders(library);
  for (auto& g : mGrass) {
    g->reloadShaders(library);
  }
  for (auto& w : mWater) {
    w->reloadShaders(library);
  }
  for (auto& forest : mForests) {
    forest->reloadShaders(library);
  }
  if (mSimulation) {
    mSimulation->reloadShaders(library);
  }
}

} // namespace sylva::scene
