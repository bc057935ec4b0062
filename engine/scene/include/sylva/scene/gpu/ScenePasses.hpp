#pragma once
// The frame of a scene: which passes run, in which order, with which shared environment (docs/scenes.md
// "Frame"). Subsystems stay unaware of each other; each registers a draw (and, for casters, a shadow draw)
// with the pass it belongs to, and every pass reads the same frame environment (camera, sun, sky, haze,
// shadow cascades).

#include <sylva/core/Geometry.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/gpu/FrameUniforms.hpp>
#include <sylva/render/gpu/GpuTimers.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/shader/Library.hpp>

#include <array>
#include <functional>
#include <memory>
#include <string>

namespace sylva::render {
class ShadowMaps;
class SkyRenderer;
} // namespace sylva::render

namespace sylva::scene {

/** The passes of a scene frame, in the order they run. */
enum class Pass { Shadows, Terrain, Trees, Grass, Bodies, Water, Sky, Flare, Count };

/** "shadows", "terrain", ... (timer labels, viewer toggles, bench rows). */
const char* passName(Pass pass);

/** What a pass draws with. */
struct PassInput {
  const render::Camera& camera; ///< the view camera (or, in a shadow draw, the cascade's sun camera)
  int width = 0;                ///< target size, pixels
  int height = 0;
  double time = 0.0;                      ///< scene seconds
  const render::Environment& environment; ///< sun, sky, haze, shadow cascades of this frame
  render::GpuTimers* timers = nullptr;    ///< may be null
  /** The view camera: `camera` itself, except in shadow draws (LOD is chosen for what the viewer sees). */
  const render::Camera* viewer = nullptr;
  /** Shadow draws: the world → clip matrix of the cascade (frustum culling of the casters). */
  bool shadow = false;
};

using PassDraw = std::function<void(const PassInput&)>;

/**
 * The lighting and atmosphere of a scene file (pure CPU): sun direction and intensity, sky turbidity and
 * exposure, haze density, Atmosphere::Sky; fogColor is the sky's horizon colour seen away from the sun (what
 * the standalone fog would use). Shadows are left empty (filled per frame).
 */
render::Environment sceneEnvironment(const SceneDesc& scene);

/**
 * Runs a scene's frame: shadow cascades (terrain and trees cast), terrain, trees, grass, bodies, water, sky
 * and the sun's flare, each pass timed under its name. Owns the shared resources (the shadow-map array, the
 * sky). Needs a current GL context.
 */
class ScenePasses {
public:
  ScenePasses(const shader::Library& library, const SceneDesc& scene);
  ~ScenePasses();
  ScenePasses(const ScenePasses&) = delete;
  ScenePasses& operator=(const ScenePasses&) = delete;

  /** Registers `pass`'s draw; `shadow` (optional) draws the same subsystem's depth from a sun camera. */
  void set(Pass pass, PassDraw draw, PassDraw shadow = {});
  /** Turns a pass on or off (viewer toggles); Shadows off: everything fully sunlit. */
  void setEnabled(Pass pass, bool on) { mEnabled[static_cast<int>(pass)] = on; }
  bool enabled(Pass pass) const { return mEnabled[static_cast<int>(pass)]; }
  /** Whether anything is registered for `pass` (the sky, flare and shadows always are). */
  bool present(Pass pass) const;

  /**
   * Draws the frame into the bound framebuffer (`width` × `height`, depth cleared by the caller) for `camera`
   * at `time`. `casters` bounds everything that casts shadows (world metres). `depth` is the bound target's
   * depth attachment, for the flare's occlusion test (null: no flare).
   */
  void render(const render::Camera& camera, int width, int height, double time, const Aabb& casters,
              const gl::Texture* depth, render::GpuTimers* timers = nullptr);

  /** Fog (extinction per metre, ≥ 0) of the next frames, instead of the scene's. */
  void setFogDensity(float density) { mBase.fogDensity = density; }
  /** The environment of the last frame (with its shadow cascades). */
  const render::Environment& environment() const { return mEnvironment; }
  /** GPU bytes of the shared resources (shadow maps). */
  std::size_t gpuBytes() const;
  void reloadShaders(const shader::Library& library);

private:
  struct Entry {
    PassDraw draw;
    PassDraw shadow;
  };
  void renderShadows(const render::Camera& camera, float aspect, double time, const Aabb& casters,
                     render::GpuTimers* timers);

  SceneDesc mScene;
  render::Environment mBase;
  render::Environment mEnvironment;
  std::array<Entry, static_cast<int>(Pass::Count)> mEntries{};
  std::array<bool, static_cast<int>(Pass::Count)> mEnabled{};
  std::unique_ptr<render::ShadowMaps> mShadowMaps;
  std::unique_ptr<render::SkyRenderer> mSky;
  render::FrameUniformBuffer mFrame; ///< the frame's one block: every pass binds it (Environment::frame)
};

} // namespace sylva::scene
