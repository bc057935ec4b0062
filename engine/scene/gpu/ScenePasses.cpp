#include <sylva/scene/gpu/ScenePasses.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/render/gpu/ShadowMaps.hpp>
#include <sylva/render/Shadows.hpp>
#include <sylva/render/Sky.hpp>
#include <sylva/render/gpu/SkyRenderer.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>

namespace sylva::scene {

const char* passName(Pass pass) {
  switch (pass) {
  case Pass::Shadows:
    return "shadows";
  case Pass::Terrain:
    return "terrain";
  case Pass::Trees:
    return "trees";
  case Pass::Grass:
    return "grass";
  case Pass::Bodies:
    return "bodies";
  case Pass::Water:
    return "water";
  case Pass::Sky:
    return "sky";
  case Pass::Flare:
    return "flare";
  case Pass::Count:
    break;
  }
  return "?";
}

render::Environment sceneEnvironment(const SceneDesc& scene) {
  render::Environment e;
  e.sunDirection = scene.sun.direction();
  e.sunIntensity = scene.sun.intensity;
  e.fogDensity = scene.fog.density;
  e.atmosphere = render::Atmosphere::Sky;
  e.turbidity = scene.sky.turbidity;
  e.exposure = scene.sky.exposure;
  // The standalone fog colour: the sky at the horizon, looking away from the sun (what a flat fog would
  // pick).
  const glm::vec3 away = glm::normalize(glm::vec3(-e.sunDirection.x, 0.0f, -e.sunDirection.z) + 1e-6f);
  e.fogColor = render::skyRadiance(away, e.sunDirection, render::skyParamsFrom(e));
  return e;
}

double farCascadeTime(double time, int cascade, int cascades, double fps) {
  if (cascade <= 0 || cascades <= 1 || !(fps > 0.0)) {
    return time;
  }
  // Steps of (cascades − 1) frames, cascade k's shifted by k − 1 frames: one far cascade's step begins each
  // frame. In frames, so a frame's own time maps to the same step whatever the rounding of f / fps (the
  // 1e-6 frame keeps f exact).
  const double frame = time * fps;
  const double shift = static_cast<double>(cascade - 1);
  const double step = static_cast<double>(cascades - 1);
  const double stepped = (std::floor((frame - shift) / step + 1e-6) * step + shift) / fps;
  return time >= 0.0 ? std::max(stepped, 0.0) : stepped; // a clock that starts at 0 does not go before it
}

ScenePasses::ScenePasses(const shader::Library& library, const SceneDesc& scene)
    : mScene(scene), mBase(sceneEnvironment(scene)), mEnvironment(mBase) {
  mEnabled.fill(true);
  if (scene.shadows.cascades > 0) {
    mShadowMaps = std::make_unique<render::ShadowMaps>(scene.shadows.size, scene.shadows.cascades);
  }
  mSky = std::make_unique<render::SkyRenderer>(library);
  mEnabled[static_cast<int>(Pass::Flare)] = scene.sky.flare;
}

ScenePasses::~ScenePasses() = default;

void ScenePasses::set(Pass pass, PassDraw draw, PassDraw shadow) {
  if (pass == Pass::Shadows || pass == Pass::Sky || pass == Pass::Flare || pass == Pass::Count) {
    fail("scene: the {} pass belongs to the scene module", passName(pass));
  }
  mEntries[static_cast<int>(pass)] = {std::move(draw), std::move(shadow)};
  invalidateShadows(); // what casts may have changed
}

void ScenePasses::setShadowReuse(bool on) {
  if (on != mShadowReuse) {
    mShadowReuse = on;
    invalidateShadows();
  }
}

bool ScenePasses::present(Pass pass) const {
  if (pass == Pass::Shadows) {
    return mShadowMaps != nullptr;
  }
  if (pass == Pass::Sky || pass == Pass::Flare) {
    return true;
  }
  return static_cast<bool>(mEntries[static_cast<int>(pass)].draw);
}

void ScenePasses::renderShadows(const render::Camera& camera, float aspect, double time, const Aabb& casters,
                                render::GpuTimers* timers) {
  render::ShadowSettings settings;
  settings.cascades = mScene.shadows.cascades;
  settings.size = mScene.shadows.size;
  settings.distance = mScene.shadows.distance;
  settings.lambda = mScene.shadows.lambda;
  const render::ShadowCascades cascades =
      render::fitCascades(camera, aspect, mBase.sunDirection, settings, casters);
  const render::GpuTimerScope timed(timers, passName(Pass::Shadows));
  render::Environment casterEnvironment = mBase; // casters draw unshadowed (their colour is not kept)
  casterEnvironment.frame = &mFrame;
  const int count = static_cast<int>(cascades.cascades.size());
  if (static_cast<int>(mShadowCache.size()) != count) {
    mShadowCache.assign(static_cast<std::size_t>(count), std::nullopt);
  }
  mLastCascadesDrawn = 0;
  for (int i = 0; i < count; ++i) {
    const render::ShadowCascade& c = cascades.cascades[static_cast<std::size_t>(i)];
    double casterTime = time;
    if (mShadowReuse && i > 0) {
      casterTime = farCascadeTime(time, i, count, mScene.output.fps);
      const CascadeKey key{
          c.viewProj,      casterTime,
          camera.position, camera.target,
          camera.up,       glm::vec4(camera.fovY, camera.nearPlane, camera.farPlane, camera.orthoHeight),
          casters.min,     casters.max};
      std::optional<CascadeKey>& cached = mShadowCache[static_cast<std::size_t>(i)];
      if (cached == key) {
        continue; // its step has not begun and nothing its map was fitted to changed: kept
      }
      cached = key;
    } else {
      mShadowCache[static_cast<std::size_t>(i)].reset();
    }
    ++mLastCascadesDrawn;
    mShadowMaps->begin(i);
    mFrame.update(c.camera, mShadowMaps->size(), mShadowMaps->size(), casterTime, casterEnvironment);
    const PassInput input{
        c.camera, mShadowMaps->size(), mShadowMaps->size(), casterTime, casterEnvironment, nullptr, &camera,
        true};
    for (const Entry& e : mEntries) {
      if (e.shadow) {
        e.shadow(input);
      }
    }
    mShadowMaps->end();
  }
  mEnvironment.shadows = render::toFrame(cascades, settings);
  mShadowMaps->bind();
}

void ScenePasses::setShadowsAllowed(bool on) {
  if (on && !mShadowsAllowed) {
    invalidateShadows(); // the kept far cascades are from before the pause
  }
  mShadowsAllowed = on;
}

void ScenePasses::render(const render::Camera& camera, int width, int height, double time,
                         const Aabb& casters, const gl::Texture* depth, render::GpuTimers* timers) {
  const float aspect = static_cast<float>(width) / static_cast<float>(std::max(height, 1));
  mEnvironment = mBase;
  // A camera whose near plane lies beyond the shadow distance (a whole large terrain in view) sees nothing
  // the cascades cover: everything is drawn fully sunlit.
  if (mShadowMaps && enabled(Pass::Shadows) && mShadowsAllowed && casters.max.x > casters.min.x &&
      camera.nearPlane < mScene.shadows.distance) {
    renderShadows(camera, aspect, time, casters, timers);
  } else {
    render::ShadowMaps::unbind();
    mLastCascadesDrawn = 0;
  }
  // One frame block for every pass of the view (the cascades above filled it for their own cameras).
  mEnvironment.frame = &mFrame;
  mFrame.update(camera, width, height, time, mEnvironment);
  mFrame.bind();
  const PassInput input{camera, width, height, time, mEnvironment, timers, &camera, false};
  for (Pass pass : {Pass::Terrain, Pass::Trees, Pass::Grass, Pass::Bodies, Pass::Water}) {
    const Entry& e = mEntries[static_cast<int>(pass)];
    if (e.draw && enabled(pass)) {
      e.draw(input);
    }
  }
  if (enabled(Pass::Sky)) {
    const render::GpuTimerScope timed(timers, passName(Pass::Sky));
    mFrame.bind();
    mSky->drawSky();
  }
  if (enabled(Pass::Flare) && depth != nullptr) {
    const render::GpuTimerScope timed(timers, passName(Pass::Flare));
    mFrame.bind();
    mSky->drawFlare(*depth);
  }
  render::ShadowMaps::unbind();
}

std::size_t ScenePasses::gpuBytes() const {
  if (!mShadowMaps) {
    return 0;
  }
  return static_cast<std::size_t>(mShadowMaps->size()) * mShadowMaps->size() * mShadowMaps->cascades() * 4;
}

void ScenePasses::reloadShaders(const shader::Library& library) {
  mSky = std::make_unique<render::SkyRenderer>(library);
}

} // namespace sylva::scene
