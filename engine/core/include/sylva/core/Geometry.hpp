#pragma once

#include <array>

#include <glm/glm.hpp>

namespace sylva {

/** Axis-aligned box in whichever space its user states (world space for terrain nodes), metres. */
struct Aabb {
  glm::vec3 min{0.0f}; ///< smallest corner
  glm::vec3 max{0.0f}; ///< largest corner

  /** Centre of the box. */
  glm::vec3 center() const { return 0.5f * (min + max); }
  /** Half the box's size along each axis. */
  glm::vec3 extent() const { return 0.5f * (max - min); }
};

/** Result of a frustum test. */
enum class Containment { Outside, Intersects, Inside };

/**
 * View frustum as six inward-facing planes (left, right, bottom, top, near, far) extracted from a
 * view-projection matrix with OpenGL clip conventions (-w ≤ x, y, z ≤ w). A point p is inside plane (n, d)
 * when dot(n, p) + d ≥ 0. Planes are normalised, so plane distances are in world units (metres).
 */
class Frustum {
public:
  Frustum() = default;
  /** Gribb–Hartmann extraction from clip = viewProj · world. */
  explicit Frustum(const glm::mat4& viewProj);

  /** The planes (n.xyz, d), inward-facing and normalised, in the order above. */
  const std::array<glm::vec4, 6>& planes() const { return mPlanes; }

  /** Conservative box test: Outside only if the box lies entirely behind one plane. */
  Containment test(const Aabb& box) const;
  /** test(box) is not Outside: some of the box may be visible. */
  bool intersects(const Aabb& box) const { return test(box) != Containment::Outside; }
  /** Sphere test with centre and radius in world units. */
  bool intersectsSphere(const glm::vec3& center, float radius) const;
  /** Whether `point` (world units) lies inside or on all six planes. */
  bool contains(const glm::vec3& point) const;

private:
  std::array<glm::vec4, 6> mPlanes{};
};

} // namespace sylva
