#include <sylva/trees/gpu/ForestScene.hpp>

#include <sylva/trees/Forest.hpp>

#include <algorithm>
#include <filesystem>
#include <cmath>

namespace sylva::trees {

ForestScene::ForestScene(const shader::Library& library, std::shared_ptr<const Forest> forest, bool wind)
    : mShaders(library), mForest(std::move(forest)),
      mRenderer(std::make_unique<TreeRenderer>(library, mForest)), mBounds(forestBounds(*mForest)) {
  setWind(wind);
}

void ForestScene::setBark(const std::optional<BarkSources>& sources) {
  if (!sources) {
    mBarkSets.clear();
    mRenderer->setBark({});
    return;
  }
  // Into locals first: on an error the scene keeps its bark (the viewer's Bark combo relies on it).
  std::vector<int> speciesSet;
  std::vector<BarkSet> sets = barkSetsFor(*mForest, *sources, speciesSet);
  mRenderer->setBark(sets, speciesSet);
  mBarkSets = std::move(sets);
  mSpeciesSet = std::move(speciesSet);
}

void ForestScene::setFoliage(bool enabled, const Image* leafImage, const LeafCloud* cloud) {
  mLeafImageCopy.reset();
  mLeafCloud.reset();
  if (!enabled) {
    mFoliage.reset();
    return;
  }
  if (leafImage != nullptr) {
    mLeafImageCopy = *leafImage;
  }
  if (cloud != nullptr) {
    mLeafCloud = *cloud;
  }
  auto foliage = std::make_unique<FoliageRenderer>(mShaders, mForest);
  if (leafImage != nullptr) {
    foliage->setLeafTexture(*leafImage);
  }
  if (cloud != nullptr) {
    foliage->setLeafCloud(*cloud);
  }
  mFoliage = std::move(foliage);
}

void ForestScene::applyLook(const ForestLook& look, const ForestSettings& placement,
                            const FarGround& ground) {
  setBark(barkSources(look));
  applyFoliage(look);
  applyFarField(look, placement, ground);
}

void ForestScene::applyFoliage(const ForestLook& look) {
  if (!look.foliage) {
    setFoliage(false);
    return;
  }
  std::optional<Image> image;
  if (look.leaves == "auto" && std::filesystem::exists(kAutoLeafImage)) {
    image = loadLeafImage(kAutoLeafImage);
  } else if (look.leaves != "auto" && look.leaves != "procedural") {
    image = loadLeafImage(look.leaves);
  }
  std::optional<LeafCloud> cloud;
  if (!look.leafModel.empty()) {
    cloud = loadLeafCloud(look.leafModel);
  }
  setFoliage(true, image ? &*image : nullptr, cloud ? &*cloud : nullptr);
}

void ForestScene::applyFarField(const ForestLook& look, const ForestSettings& placement,
                                const FarGround& ground) {
  if (look.farDistance <= 0.0f) {
    setFarField(glm::vec2(0.0f));
    return;
  }
  const std::vector<FarTree> extra =
      farFieldTrees(look, placement, *mForest, mRenderer->treeCentres(), ground);
  setFarField(glm::vec2(look.farDistance, look.farDistance + look.farBand), extra);
}

void ForestScene::setFarField(glm::vec2 range, std::span<const FarTree> extra) {
  if (range.y <= range.x) {
    mImpostors.reset();
    mFarRange = glm::vec2(0.0f);
    return;
  }
  auto impostors = std::make_unique<ImpostorRenderer>(mShaders);
  // Each species' representative tree is baked as this scene draws it: bark tiles and foliage.
  const ImpostorBakeOptions options =
      sceneBakeOptions(mShaders, mBarkSets, mSpeciesSet, mFoliage != nullptr,
                       mLeafImageCopy ? &*mLeafImageCopy : nullptr, mLeafCloud ? &*mLeafCloud : nullptr);
  impostors->bake(*mForest, options);
  std::vector<FarTree> all = farTrees(*mForest);
  all.insert(all.end(), extra.begin(), extra.end());
  impostors->setTrees(all);
  mImpostors = std::move(impostors);
  mFarRange = range;
}

void ForestScene::setWind(bool on) {
  if (on && !mWind) {
    mWind = std::make_unique<JointWindGpu>(mShaders, forestWindRest(*mForest), JointWindSolve::Auto);
  }
  mWindOn = on;
  mRenderer->useFrames(on ? &mWind->frames() : nullptr);
}

void ForestScene::resetWind() {
  mClock.reset();
  if (mWind) {
    mWind = std::make_unique<JointWindGpu>(mShaders, forestWindRest(*mForest), JointWindSolve::Auto);
    mRenderer->useFrames(mWindOn ? &mWind->frames() : nullptr);
  }
}

void ForestScene::advance(double time, const wind::WindSettings& wind, int maxSteps,
                          render::GpuTimers* timers) {
  mSteps = 0;
  if (mImpostors) {
    // Far trees lean in the wind the near ones bend in (none: upright, as the rest pose).
    mImpostors->setWind(mWindOn ? wind::toUniforms(wind, static_cast<float>(time)) : gpu::WindUniforms{});
  }
  if (!mWindOn) {
    return;
  }
  int steps = 0;
  if (!mClock) {
    // From rest, a fixed stretch of wind before the first frame: the same time gives the same state.
    mClock = time - kForestWindWarmup;
    steps = fixedSteps(*mClock, time, kForestWindStep,
                       static_cast<int>(std::ceil(kForestWindWarmup / kForestWindStep)) + 1);
  } else {
    steps = fixedSteps(*mClock, time, kForestWindStep, std::max(maxSteps, 1));
  }
  if (steps == 0) {
    return;
  }
  const render::GpuTimerScope timed(timers, "trees wind");
  // Step i runs at the wind time clock − (n − 1 − i)·dt (fixedSteps' contract).
  for (int i = 0; i < steps; ++i) {
    const double at = *mClock - static_cast<double>(steps - 1 - i) * kForestWindStep;
    mWind->step(wind::toUniforms(wind, static_cast<float>(at)), static_cast<float>(kForestWindStep));
  }
  mWind->updateFrames();
  mSteps = steps;
}

void ForestScene::draw(const render::Camera& camera, int width, int height, double time, const TreeLod& lod,
                       const TreeDrawOptions& options, render::GpuTimers* timers) {
  TreeLod l = lod;
  l.farRange = mImpostors ? mFarRange : glm::vec2(0.0f);
  mRenderer->cull(camera, width, height, l, timers, options.environment);
  mRenderer->draw(camera, width, height, time, l, timers, options);
  const bool full = options.view == TreeView::Shaded || options.view == TreeView::Depth;
  if (mFoliage && full) {
    mFoliage->bake(camera, options.environment, timers);
    mFoliage->draw(camera, width, height, time, *mRenderer, l, timers, options.environment);
  }
  if (mImpostors && full) {
    mImpostors->draw(camera, width, height, time, mFarRange, timers, options.environment);
  }
}

void ForestScene::reloadShaders(const shader::Library& library) {
  mRenderer->reloadShaders(library);
  if (mFoliage) {
    mFoliage->reloadShaders(library);
  }
  if (mImpostors) {
    mImpostors->reloadShaders(library);
  }
  if (mWind) {
    mWind->reloadShaders(library);
  }
  mShaders = library;
}

std::size_t ForestScene::gpuBytes() const {
  std::size_t bytes = mRenderer->gpuBytes() + (mFoliage ? mFoliage->gpuBytes() : 0) +
                      (mImpostors ? mImpostors->gpuBytes() : 0);
  if (mWind) {
    bytes += mWind->jointCount() * (sizeof(gpu::TreeJointRest) + sizeof(glm::vec4) + sizeof(gpu::JointFrame));
  }
  return bytes;
}

} // namespace sylva::trees
