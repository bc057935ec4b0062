#pragma once

#include <sylva/core/Geometry.hpp>

#include <glm/glm.hpp>

namespace sylva::render {

/**
 * Perspective camera in world space (metres, y up, right-handed; looks along -z of its view space).
 * Value type.
 */
struct Camera {
  glm::vec3 position{0.0f, 10.0f, 30.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovY = glm::radians(60.0f); ///< vertical field of view, radians
  float nearPlane = 0.1f;           ///< metres
  float farPlane = 5000.0f;         ///< metres

  glm::mat4 view() const;
  /** Projection for `aspect` = width / height. */
  glm::mat4 projection(float aspect) const;
  glm::mat4 viewProjection(float aspect) const { return projection(aspect) * view(); }
  Frustum frustum(float aspect) const { return Frustum(viewProjection(aspect)); }
  /** Unit direction from position to target. */
  glm::vec3 forward() const { return glm::normalize(target - position); }
};

/** Orbit control: yaw/pitch/distance around a target (viewer default). Angles in radians, distance metres. */
struct OrbitController {
  glm::vec3 target{0.0f};
  float yaw = 0.6f;
  float pitch = 0.45f;
  float distance = 120.0f;

  /** Drag by `dx`, `dy` pixels (rotate), scroll `wheel` notches (zoom), pan by `panDx`, `panDy` pixels. */
  void rotate(float dxPixels, float dyPixels);
  void zoom(float wheelNotches);
  void pan(float dxPixels, float dyPixels);
  void apply(Camera& camera) const;
};

/** First-person fly control. Speed in metres per second; angles radians. */
struct FlyController {
  glm::vec3 position{0.0f, 20.0f, 60.0f};
  float yaw = 3.14159265f;
  float pitch = -0.2f;
  float speed = 30.0f;

  /** Moves by `move` (x right, y up, z forward; each in [-1, 1]) over `dt` seconds; looks by pixel deltas. */
  void update(const glm::vec3& move, float dxPixels, float dyPixels, float dt);
  void apply(Camera& camera) const;
};

} // namespace sylva::render
