#pragma once
// The ui module's viewer camera (docs/engine.md): a scene's named cameras, an orbit, and a fly camera that
// can walk on the ground, driven by the window's mouse and keys. GL-free; the world it looks at answers
// through two callbacks, so the rig needs no scene module.

#include <sylva/platform/GlfwWindow.hpp>
#include <sylva/render/Camera.hpp>

#include <functional>
#include <string>
#include <vector>

namespace sylva::ui {

/**
 * Which camera a viewer looks through, and its mouse and keys: a named camera (the scene file's, evaluated by
 * the world at its time), the orbit (left drag rotates, right/middle drag pans, the wheel zooms), or fly
 * (W/A/S/D/E/Q, left drag looks; walking keeps the eye kWalkEyeHeight above the ground). Moving with the
 * keys, or looking around from a named camera, leaves it for fly; F goes back to where fly was entered from.
 */
class CameraRig {
public:
  /** Eye height above the ground while walking, metres. */
  static constexpr float kWalkEyeHeight = 1.8f;

  /** What the rig asks of the world it looks at. */
  struct World {
    /** The named camera `name` at the world's current time for `aspect` (null: no named cameras). */
    std::function<render::Camera(const std::string& name, float aspect)> namedCamera;
    /** Ground height under world x, z in metres (NaN off the ground; null: no ground, no flying). */
    std::function<float(float x, float z)> groundHeight;
  };

  /**
   * `names`: the world's cameras; `first`: the one to start with (not among them: the orbit around
   * `start`); `start`: the first camera otherwise, whose vertical field of view every free camera keeps.
   */
  CameraRig(std::vector<std::string> names, const std::string& first, const render::Camera& start,
            World world, float startAspect);

  /** Orbit distance limits, metres (zoom stops there). */
  void setOrbitLimits(float minDistance, float maxDistance);
  /** The orbit camera's distance from its target, metres. */
  float orbitDistance() const { return mOrbit.distance; }

  /** Whether fly (and walk) is offered: the world has a ground to fly over. */
  bool flyAllowed() const { return static_cast<bool>(mWorld.groundHeight); }
  /** True while one of the world's named cameras is selected. */
  bool named() const { return mIndex < orbitIndex(); }
  /** True while the fly camera is selected. */
  bool flying() const { return mIndex == flyIndex(); }
  /** True while flying keeps to walking height over the ground. */
  bool walking() const { return mWalk; }

  /** F: into fly from the current camera, or back to where fly was entered from. */
  void toggleFly();
  /** G: walking on or off (entering fly). */
  void toggleWalk();

  /**
   * This frame's camera from the mouse (`in`; `mouseFree`: no ImGui window under it), the fly keys' `move`
   * (ui::flyKeys: x right, y up, z forward) and `dt` seconds of flight. Free cameras keep the start's clip
   * planes; the caller fits them to its world.
   */
  const render::Camera& update(const platform::InputState& in, const glm::vec3& move, bool mouseFree,
                               float dt, float aspect);
  /** The camera of the last update(). */
  const render::Camera& camera() const { return mCamera; }

  /** The ImGui camera selector (named cameras, orbit, fly) and the walk checkbox. */
  void selector();

  float flySpeed = 30.0f; ///< metres per second
  float walkSpeed = 4.0f; ///< metres per second

private:
  int orbitIndex() const { return static_cast<int>(mNames.size()); }
  int flyIndex() const { return orbitIndex() + 1; }
  bool orbiting() const { return mIndex == orbitIndex(); }
  void goFly();
  void back();
  void syncFly();

  std::vector<std::string> mNames;
  World mWorld;
  render::Camera mStart;
  render::Camera mCamera;
  render::OrbitController mOrbit;
  render::FlyController mFly;
  int mIndex = 0;
  int mLastNamed = -1; ///< where F goes back to from fly (-1: orbit)
  bool mWalk = false;
};

} // namespace sylva::ui
