#include <sylva/render/Camera.hpp>

#include <sylva/core/Error.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <array>

#include <algorithm>
#include <cmath>

namespace sylva::render {

glm::mat4 Camera::view() const {
  return glm::lookAt(position, target, up);
}

glm::mat4 Camera::projection(float aspect) const {
  if (orthoHeight > 0.0f) {
    const float w = orthoHeight * aspect;
    return glm::ortho(-w, w, -orthoHeight, orthoHeight, nearPlane, farPlane);
  }
  return glm::perspective(fovY, aspect, nearPlane, farPlane);
}

namespace {
constexpr float kRadiansPerPixel = 0.005f;
constexpr float kMaxPitch = 1.55f;

glm::vec3 directionOf(float yaw, float pitch) {
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), std::cos(pitch) * std::cos(yaw)};
}
} // namespace

void OrbitController::rotate(float dx, float dy) {
  yaw -= dx * kRadiansPerPixel;
  pitch = std::clamp(pitch + dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void OrbitController::zoom(float notches) {
  distance = std::clamp(distance * std::pow(0.9f, notches), minDistance, std::max(minDistance, maxDistance));
}

OrbitController OrbitController::from(const Camera& camera) {
  OrbitController orbit;
  orbit.target = camera.target;
  const glm::vec3 offset = camera.position - camera.target;
  orbit.distance = std::max(glm::length(offset), 1e-3f);
  const glm::vec3 dir = offset / orbit.distance;
  orbit.yaw = std::atan2(dir.x, dir.z);
  orbit.pitch = std::clamp(std::asin(std::clamp(dir.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
  return orbit;
}

const std::vector<std::string>& viewFromNames() {
  static const std::vector<std::string> names = {
      "south-west", "south", "south-east", "east", "north-east", "north", "north-west", "west", "top"};
  return names;
}

ViewFrom parseViewFrom(const std::string& name, const std::string& option) {
  const std::vector<std::string>& names = viewFromNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    std::string list;
    for (const std::string& n : names) {
      list += (list.empty() ? "" : ", ") + n;
    }
    fail("{}: unknown view '{}' (expected one of {})", option, name, list);
  }
  return static_cast<ViewFrom>(it - names.begin());
}

namespace {

/** Unit vector from the target towards the camera. */
glm::vec3 viewOffset(ViewFrom from) {
  if (from == ViewFrom::Top) {
    return {0.0f, 1.0f, 0.0f};
  }
  // Compass bearing of the camera seen from the target: south = +z, east = +x.
  static constexpr float kBearing[] = {225.0f, 180.0f, 135.0f, 90.0f, 45.0f, 0.0f, 315.0f, 270.0f};
  const float bearing = glm::radians(kBearing[static_cast<int>(from)]);
  const float elevation = glm::radians(30.0f);
  return {std::cos(elevation) * std::sin(bearing), std::sin(elevation),
          -std::cos(elevation) * std::cos(bearing)};
}

std::array<glm::vec3, 8> corners(const Aabb& box) {
  std::array<glm::vec3, 8> out{};
  for (int k = 0; k < 8; ++k) {
    out[static_cast<std::size_t>(k)] = {(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                        (k & 4) ? box.max.z : box.min.z};
  }
  return out;
}

} // namespace

Camera frameBox(const Aabb& box, ViewFrom from, float fovY, float aspect, const glm::vec3& target,
                float margin) {
  Camera camera;
  camera.fovY = fovY;
  const glm::vec3 back = viewOffset(from);
  camera.up = from == ViewFrom::Top ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 forward = -back;
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  const float tanY = std::tan(0.5f * fovY);
  const float tanX = tanY * aspect;
  const std::array<glm::vec3, 8> points = corners(box);
  // Camera at t - forward·d: a corner c at depth d + dot(c - t, forward) is inside the view when its lateral
  // offsets fit in depth·tan. The smallest such d over all corners frames the box around t; the view is then
  // re-aimed at the middle of what it sees (perspective makes near corners reach further) and fitted again.
  glm::vec3 aim = target;
  float distance = 0.0f;
  for (int pass = 0; pass < 4; ++pass) {
    distance = 0.0f;
    for (const glm::vec3& c : points) {
      const glm::vec3 r = c - aim;
      const float z = glm::dot(r, forward);
      distance =
          std::max({distance, std::abs(glm::dot(r, right)) / tanX - z, std::abs(glm::dot(r, up)) / tanY - z});
    }
    distance = std::max(distance, 1e-3f);
    if (pass == 3) {
      break;
    }
    // Screen-space (tangent) extent of the corners seen from the fitted camera; shift the aim to centre it.
    float loX = 1e30f, hiX = -1e30f, loY = 1e30f, hiY = -1e30f;
    for (const glm::vec3& c : points) {
      const glm::vec3 r = c - aim;
      const float depth = std::max(distance + glm::dot(r, forward), 1e-3f);
      loX = std::min(loX, glm::dot(r, right) / depth);
      hiX = std::max(hiX, glm::dot(r, right) / depth);
      loY = std::min(loY, glm::dot(r, up) / depth);
      hiY = std::max(hiY, glm::dot(r, up) / depth);
    }
    aim += (0.5f * (loX + hiX) * right + 0.5f * (loY + hiY) * up) * distance;
  }
  camera.target = aim;
  camera.position = aim + back * (distance * margin);
  fitClipPlanes(camera, box);
  return camera;
}

void fitClipPlanes(Camera& camera, const Aabb& box) {
  float farthest = 0.0f;
  for (const glm::vec3& c : corners(box)) {
    farthest = std::max(farthest, glm::length(c - camera.position));
  }
  const glm::vec3 nearestPoint = glm::clamp(camera.position, box.min, box.max);
  const float nearest = glm::length(nearestPoint - camera.position);
  camera.farPlane = std::max(1.05f * farthest, 1.0f);
  camera.nearPlane = std::clamp(0.5f * nearest, camera.farPlane * 1e-5f, 0.1f * camera.farPlane);
}

float fogDensityFor(const glm::vec3& position, const Aabb& box, float amount) {
  float farthest = 0.0f;
  for (const glm::vec3& c : corners(box)) {
    farthest = std::max(farthest, glm::length(c - position));
  }
  if (amount <= 0.0f || farthest <= 0.0f) {
    return 0.0f;
  }
  return -std::log(1.0f - std::min(amount, 0.999f)) / farthest;
}

void OrbitController::pan(float dx, float dy) {
  const glm::vec3 forward = -directionOf(yaw, pitch);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  const glm::vec3 up = glm::cross(right, forward);
  const float scale = distance * 0.0015f;
  target += (-dx * right + dy * up) * scale;
}

void OrbitController::apply(Camera& camera) const {
  camera.target = target;
  camera.position = target + distance * directionOf(yaw, pitch);
  camera.up = {0, 1, 0};
}

void FlyController::update(const glm::vec3& move, float dx, float dy, float dt) {
  yaw -= dx * kRadiansPerPixel;
  pitch = std::clamp(pitch - dy * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
  const glm::vec3 forward = directionOf(yaw, pitch);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
  position += (move.x * right + move.y * glm::vec3(0, 1, 0) + move.z * forward) * speed * dt;
}

void FlyController::apply(Camera& camera) const {
  camera.position = position;
  camera.target = position + directionOf(yaw, pitch);
  camera.up = {0, 1, 0};
}

} // namespace sylva::render
