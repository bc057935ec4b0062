#pragma once

#include <sylva/scene/SceneFile.hpp>

#include <functional>
#include <vector>

#include <glm/vec3.hpp>

/**
 * Camera paths (docs/scenes.md): keys (time, position, target, fov) interpolated in time with centripetal
 * Catmull-Rom splines (alpha 0.5; Yuksel, Schaefer & Keyser 2011: no cusps or self-intersections within a
 * segment, no overshoot on uneven key spacing). Position and target are separate curves; fov uses the same
 * spline on the scalar. Render-free, deterministic: the time comes from a fixed clock (frame / fps).
 */
namespace sylva::scene {

/** A camera key with both points in world metres (above-ground heights already resolved). */
struct WorldCameraKey {
  double time = 0.0;        ///< seconds
  glm::vec3 position{0.0f}; ///< world metres
  glm::vec3 target{0.0f};   ///< world metres
  float fov = 50.0f;        ///< vertical field of view, degrees
};

/** The camera at one instant. */
struct CameraSample {
  glm::vec3 position{0.0f}; ///< world metres
  glm::vec3 target{0.0f};   ///< world metres
  float fov = 50.0f;        ///< vertical field of view, degrees
};

/**
 * Terrain height (world metres, y) at world (x, z); used to resolve "above_ground" points.
 */
using GroundHeight = std::function<float(float x, float z)>;

/** `p` in world metres: p.p unchanged, or with y added to the ground height at (x, z) when aboveGround. */
glm::vec3 resolvePoint(const Vec3Ground& p, const GroundHeight& ground);

/** A camera's keys in world metres (see resolvePoint). */
std::vector<WorldCameraKey> resolveKeys(const CameraDesc& camera, const GroundHeight& ground);

/**
 * The camera at `time` seconds. Keys must be non-empty with strictly increasing times (throws sylva::Error
 * otherwise). One key: that key at any time. Without `loop`, time is clamped to [first, last] key time. With
 * `loop`, time wraps modulo the duration (last − first key time) and the path is closed: the last key joins
 * the first (their values should match for a seamless loop; the segment from last back to first takes no
 * time, so a path that ends away from where it starts jumps once per period). Exact at every key.
 */
CameraSample evaluate(const std::vector<WorldCameraKey>& keys, double time, bool loop);

/** One centripetal Catmull-Rom segment between p1 and p2 at u ∈ [0, 1] (alpha 0.5); exposed for tests. */
glm::vec3 centripetalCatmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                                const glm::vec3& p3, float u);

/**
 * Seconds at which the scene's timeline ends: the end of its output frame range ((lastFrame + 1) / fps) or
 * the last key of its longest camera path, whichever is later (the viewer's time slider runs to it).
 */
double timelineEnd(const SceneDesc& desc);

} // namespace sylva::scene
