#pragma once

#include <sylva/core/Geometry.hpp>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace sylva::render {

/**
 * Camera in world space (metres, y up, right-handed; looks along -z of its view space): perspective by
 * default, orthographic when orthoHeight > 0 (the sun's view of a shadow cascade). Value type.
 */
struct Camera {
  glm::vec3 position{0.0f, 10.0f, 30.0f}; ///< eye, world metres
  glm::vec3 target{0.0f};                 ///< the point looked at, world metres
  glm::vec3 up{0.0f, 1.0f, 0.0f};         ///< world direction that is up on screen
  float fovY = glm::radians(60.0f);       ///< vertical field of view, radians
  float nearPlane = 0.1f;                 ///< metres
  float farPlane = 5000.0f;               ///< metres
  /**
   * 0 = perspective (fovY). > 0 = orthographic: the view spans ±orthoHeight metres vertically and
   * ±orthoHeight·aspect horizontally around the view axis, between nearPlane and farPlane (fovY unused).
   */
  float orthoHeight = 0.0f;

  /** World to view space (glm::lookAt). */
  glm::mat4 view() const;
  /** Projection for `aspect` = width / height (glm::perspective, or glm::ortho when orthoHeight > 0). */
  glm::mat4 projection(float aspect) const;
  /** projection(aspect) · view(): world to clip space. */
  glm::mat4 viewProjection(float aspect) const { return projection(aspect) * view(); }
  /** The view frustum at `aspect`, world space. */
  Frustum frustum(float aspect) const { return Frustum(viewProjection(aspect)); }
  /** Unit direction from position to target. */
  glm::vec3 forward() const { return glm::normalize(target - position); }
};

/**
 * Compass direction a framing camera looks from, in Sylva's world axes: +x east, +z south (row order of
 * height fields: row 0 is north), +y up. Top looks straight down with north up in the image.
 */
enum class ViewFrom { SouthWest, South, SouthEast, East, NorthEast, North, NorthWest, West, Top };

/** "south-west", "south", ..., "top"; throws sylva::Error naming `option` and the choices otherwise. */
ViewFrom parseViewFrom(const std::string& name, const std::string& option = "--view-from");
/** The names parseViewFrom accepts, in enum order. */
const std::vector<std::string>& viewFromNames();

/**
 * A camera looking at `target` from `from` (30° above the horizon; Top: straight down), at the smallest
 * distance at which every corner of `box` is inside the view for `aspect` (width / height) and `fovY`
 * (radians), times `margin`. Clip planes are fitted with fitClipPlanes. Pure CPU.
 */
Camera frameBox(const Aabb& box, ViewFrom from, float fovY, float aspect, const glm::vec3& target,
                float margin = 1.06f);

/**
 * Near and far planes for `camera` that keep `box` (world space, metres) in view: far just beyond the box's
 * farthest corner, near a fraction of the distance to the box's nearest point (never below far / 10⁵, which
 * keeps a 24-bit depth buffer usable).
 */
void fitClipPlanes(Camera& camera, const Aabb& box);

/**
 * Density (per metre) of exponential fog 1 − exp(−density · d) that reaches `amount` (0..1) at the farthest
 * corner of `box` seen from `position`: fog that scales with the scene instead of a fixed distance.
 */
float fogDensityFor(const glm::vec3& position, const Aabb& box, float amount);

/** Orbit control: yaw/pitch/distance around a target (viewer default). Angles in radians, distance metres. */
struct OrbitController {
  glm::vec3 target{0.0f};  ///< the point orbited, world metres
  float yaw = 0.6f;        ///< radians about +y
  float pitch = 0.45f;     ///< radians above the horizon
  float distance = 120.0f; ///< metres from the target
  /** Zoom limits, metres (the viewer sets them from the scene: the whole terrain fits at maxDistance). */
  float minDistance = 0.5f;
  float maxDistance = 1.0e5f; ///< farthest zoom, metres

  /** Orbit parameters that reproduce `camera` (its target, distance and direction). */
  static OrbitController from(const Camera& camera);

  /** Drag by `dx`, `dy` pixels (rotate), scroll `wheel` notches (zoom), pan by `panDx`, `panDy` pixels. */
  void rotate(float dxPixels, float dyPixels);
  /** Scroll `wheelNotches` notches: each one scales the distance by a fixed step, within the limits. */
  void zoom(float wheelNotches);
  /** Moves the target sideways and up by `dxPixels`, `dyPixels` (scaled with the distance). */
  void pan(float dxPixels, float dyPixels);
  /** Sets `camera`'s position and target from the orbit. */
  void apply(Camera& camera) const;
};

/** First-person fly control. Speed in metres per second; angles radians. */
struct FlyController {
  glm::vec3 position{0.0f, 20.0f, 60.0f}; ///< eye, world metres
  float yaw = 3.14159265f;                ///< heading, radians about +y
  float pitch = -0.2f;                    ///< radians above the horizon
  float speed = 30.0f;                    ///< metres per second at full stick

  /** Moves by `move` (x right, y up, z forward; each in [-1, 1]) over `dt` seconds; looks by pixel deltas. */
  void update(const glm::vec3& move, float dxPixels, float dyPixels, float dt);
  /** Sets `camera`'s position and target (one metre ahead) from the flyer. */
  void apply(Camera& camera) const;
};

} // namespace sylva::render
