#include <sylva/ui/CameraRig.hpp>

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace sylva::ui {

CameraRig::CameraRig(std::vector<std::string> names, const std::string& first, const render::Camera& start,
                     World world, float startAspect)
    : mNames(std::move(names)), mWorld(std::move(world)), mStart(start), mCamera(start) {
  const auto it = std::find(mNames.begin(), mNames.end(), first);
  mIndex = it != mNames.end() && mWorld.namedCamera ? static_cast<int>(it - mNames.begin()) : orbitIndex();
  if (named()) {
    mCamera = mWorld.namedCamera(mNames[static_cast<std::size_t>(mIndex)], startAspect);
  }
  mStart.fovY = mCamera.fovY;
  mOrbit = render::OrbitController::from(mCamera);
  syncFly();
}

void CameraRig::setOrbitLimits(float minDistance, float maxDistance) {
  mOrbit.minDistance = minDistance;
  mOrbit.maxDistance = maxDistance;
}

void CameraRig::syncFly() {
  mFly.position = mCamera.position;
  const glm::vec3 d = glm::normalize(mCamera.target - mCamera.position);
  mFly.yaw = std::atan2(d.x, d.z);
  mFly.pitch = std::asin(std::clamp(d.y, -1.0f, 1.0f));
}

void CameraRig::goFly() {
  if (!flying() && flyAllowed()) {
    mLastNamed = named() ? mIndex : -1;
    syncFly();
    mIndex = flyIndex();
  }
}

void CameraRig::back() {
  mWalk = false;
  mIndex = mLastNamed >= 0 ? mLastNamed : orbitIndex();
  if (orbiting()) {
    const render::OrbitController from = render::OrbitController::from(mCamera);
    mOrbit.target = mCamera.target;
    mOrbit.yaw = from.yaw;
    mOrbit.pitch = from.pitch;
    mOrbit.distance = std::clamp(from.distance, mOrbit.minDistance, mOrbit.maxDistance);
  }
}

void CameraRig::toggleFly() {
  if (flying()) {
    back();
  } else {
    goFly();
  }
}

void CameraRig::toggleWalk() {
  if (flyAllowed()) {
    goFly();
    mWalk = !mWalk;
  }
}

const render::Camera& CameraRig::update(const platform::InputState& in, const glm::vec3& move, bool mouseFree,
                                        float dt, float aspect) {
  const bool dragged = in.cursorDelta.x != 0.0 || in.cursorDelta.y != 0.0;
  const auto dx = static_cast<float>(in.cursorDelta.x);
  const auto dy = static_cast<float>(in.cursorDelta.y);
  if (move != glm::vec3(0.0f) || (named() && mouseFree && in.mouseLeft && dragged)) {
    goFly(); // flying (or looking around from a named camera) leaves it
  }
  if (named()) {
    mCamera = mWorld.namedCamera(mNames[static_cast<std::size_t>(mIndex)], aspect);
    syncFly(); // flying starts where the named camera is
    return mCamera;
  }
  if (orbiting()) {
    if (mouseFree && in.mouseLeft) {
      mOrbit.rotate(dx, dy);
    }
    if (mouseFree && (in.mouseRight || in.mouseMiddle)) {
      mOrbit.pan(dx, dy);
    }
    if (mouseFree) {
      mOrbit.zoom(static_cast<float>(in.scrollDelta));
    }
    mOrbit.apply(mCamera);
    syncFly(); // flying starts where the orbit camera is
  } else {
    const bool look = mouseFree && in.mouseLeft;
    mFly.speed = mWalk ? walkSpeed : flySpeed;
    mFly.update(move, look ? dx : 0.0f, look ? dy : 0.0f, dt);
    if (mWalk) {
      const float ground = mWorld.groundHeight(mFly.position.x, mFly.position.z);
      if (!std::isnan(ground)) {
        mFly.position.y = ground + kWalkEyeHeight;
      }
    }
    mCamera = render::Camera{};
    mFly.apply(mCamera);
  }
  mCamera.fovY = mStart.fovY;
  mCamera.nearPlane = mStart.nearPlane;
  mCamera.farPlane = mStart.farPlane;
  return mCamera;
}

void CameraRig::selector() {
  std::vector<const char*> labels;
  for (const std::string& name : mNames) {
    labels.push_back(name.c_str());
  }
  labels.push_back("orbit (drag, right-drag, wheel)");
  labels.push_back(flyAllowed() ? "fly (F; G: walk)" : "fly (no ground here)");
  int index = mIndex;
  if (ImGui::Combo("camera", &index, labels.data(), static_cast<int>(labels.size()))) {
    if (index == flyIndex()) {
      goFly();
    } else {
      mWalk = false;
      mLastNamed = index < orbitIndex() ? index : -1;
      mIndex = flyIndex();
      back();
    }
  }
  if (flyAllowed() && ImGui::Checkbox("walk (G)", &mWalk) && mWalk) {
    goFly();
  }
}

} // namespace sylva::ui
