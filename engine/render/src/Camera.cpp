#include <sylva/render/Camera.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

glm::mat4 Camera::view() const {
  return glm::lookAt(position, target, up);
}

glm::mat4 Camera::projection(float aspect) const {
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
  distance = std::clamp(distance * std::pow(0.9f, notches), 0.5f, 1e5f);
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
