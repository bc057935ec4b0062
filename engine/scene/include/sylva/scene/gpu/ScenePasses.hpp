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
#include <optional>
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
  /** Target height, pixels. */
  int height = 0;
  double time = 0.0;                      ///< scene seconds
  const render::Environment& environment; ///< sun, sky, haze, shadow cascades of this frame
  render::GpuTimers* timers = nullptr;    ///< may be null
  /** The view camera: `camera` itself, except in shadow draws (LOD is chosen for what the viewer sees). */
  const render::Camera* viewer = nullptr;
  /** Shadow draws: the world → clip matrix of the cascade (frustum culling of the casters). */
  bool shadow = false;
};

/** A pass's draw callback. */
using PassDraw = std::function<void(const PassInput&)>;

/**
 * The lighting and atmosphere of a scene file (pure CPU): sun direction and intensity, sky turbidity and
 * exposure, haze density, Atmosphere::Sky; fogColor is the sky's horizon colour seen away from the sun (what
 * the standalone fog would use). Shadows are left empty (filled per frame).
 */
render::Environment sceneEnvironment(const SceneDesc& scene);

/**
 * The time (seconds) far shadow cascade `cascade` (≥ 1) of `cascades` draws its casters at for a frame at
 * `time` on a clock of `fps` frames per second (ScenePasses::setShadowReuse): `time` rounded down to steps of
 * (cascades − 1) frames, shifted by cascade − 1 frames. Cascade 0, one cascade or fps ≤ 0: `time`.
 */
double farCascadeTime(double time, int cascade, int cascades, double fps);

/**
 * Runs a scene's frame: shadow cascades (terrain and trees cast), terrain, trees, grass, bodies, water, sky
 * and the sun's flare, each pass timed under its name. Owns the shared resources (the shadow-map array, the
 * sky). Needs a current GL context.
 */
class ScenePasses {
public:
  /** The passes of `scene`'s frame (environment, sky, shadows) with shaders from `library`. */
  ScenePasses(const shader::Library& library, const SceneDesc& scene);
  ~ScenePasses();
  ScenePasses(const ScenePasses&) = delete;
  ScenePasses& operator=(const ScenePasses&) = delete;

  /** Registers `pass`'s draw; `shadow` (optional) draws the same subsystem's depth from a sun camera. */
  void set(Pass pass, PassDraw draw, PassDraw shadow = {});
  /** Turns a pass on or off (viewer toggles); Shadows off: everything fully sunlit. */
  void setEnabled(Pass pass, bool on) { mEnabled[static_cast<int>(pass)] = on; }
  /** Whether `pass` is on. */
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

  /**
   * Real-time shadows (the default; false: every cascade every frame, the full path). Cascade 0 is drawn
   * every frame. Far cascade k ≥ 1 is drawn when its step of (cascades − 1) frames of the scene's clock
   * begins (farCascadeTime: one far cascade each frame), or when its camera, the viewer or the casters'
   * bounds changed; otherwise its map is kept. What the kept maps miss is how casters moved since: wind sway,
   * about a texel there, lags up to cascades − 2 frames. A frame then depends on the frames drawn before, so
   * offline renders (`sylva render`, whose frames are a pure function of the scene and the frame) take the
   * full path.
   */
  void setShadowReuse(bool on);
  /**
   * The quality step's say on shadows (on by default; Quality.hpp): off, no cascade is drawn and everything
   * is fully sunlit, as with the pass toggled off, without touching the toggle.
   */
  void setShadowsAllowed(bool on);
  /** Whether shadows may be drawn at all (the quality step). */
  bool shadowsAllowed() const { return mShadowsAllowed; }
  /** Forgets the cached far cascades (casters changed in a way the cache key does not see). */
  void invalidateShadows() { mShadowCache.clear(); }
  /** Cascades drawn by the last frame (0 when shadows are off). */
  int lastCascadesDrawn() const { return mLastCascadesDrawn; }
  /** The cascades' depth maps (null: the scene has no shadows). */
  const render::ShadowMaps* shadowMaps() const { return mShadowMaps.get(); }

  /** Fog (extinction per metre, ≥ 0) of the next frames, instead of the scene's. */
  void setFogDensity(float density) { mBase.fogDensity = density; }
  /** The environment of the last frame (with its shadow cascades). */
  const render::Environment& environment() const { return mEnvironment; }
  /** GPU bytes of the shared resources (shadow maps). */
  std::size_t gpuBytes() const;
  /** Recompiles the shared shaders from `library`; keeps the old ones and throws on error. */
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
  bool mShadowsAllowed = true;
  std::unique_ptr<render::ShadowMaps> mShadowMaps;
  std::unique_ptr<render::SkyRenderer> mSky;
  render::FrameUniformBuffer mFrame; ///< the frame's one block: every pass binds it (Environment::frame)
  /** What a far cascade's map was last drawn with (setShadowReuse). */
  struct CascadeKey {
    glm::mat4 viewProj{1.0f};
    double casterTime = 0.0;
    glm::vec3 viewerPosition{0.0f};
    glm::vec3 viewerTarget{0.0f};
    glm::vec3 viewerUp{0.0f};
    glm::vec4 viewerLens{0.0f}; ///< fovY, near, far, orthoHeight
    glm::vec3 castersMin{0.0f};
    glm::vec3 castersMax{0.0f};
    bool operator==(const CascadeKey&) const = default;
  };
  bool mShadowReuse = true;
  std::vector<std::optional<CascadeKey>> mShadowCache;
  int mLastCascadesDrawn = 0;
};

} // namespace sylva::scene
