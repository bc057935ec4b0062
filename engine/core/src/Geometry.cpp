#include <sylva/core/Geometry.hpp>

namespace sylva {

Frustum::Frustum(const glm::mat4& m) {
  // glm is column-major: m[c][r]. Row r of the matrix is (m[0][r], m[1][r], m[2][r], m[3][r]).
  auto row = [&](int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
  const glm::vec4 r0 = row(0);
  const glm::vec4 r1 = row(1);
  const glm::vec4 r2 = row(2);
  const glm::vec4 r3 = row(3);
  mPlanes = {r3 + r0, r3 - r0, r3 + r1, r3 - r1, r3 + r2, r3 - r2};
  for (glm::vec4& p : mPlanes) {
    p /= glm::length(glm::vec3(p));
  }
}

Containment Frustum::test(const Aabb& box) const {
  const glm::vec3 c = box.center();
  const glm::vec3 e = box.extent();
  Containment result = Containment::Inside;
  for (const glm::vec4& p : mPlanes) {
    const glm::vec3 n(p);
    const float distance = glm::dot(n, c) + p.w;
    const float radius = glm::dot(glm::abs(n), e);
    if (distance < -radius) {
      return Containment::Outside;
    }
    if (distance < radius) {
      result = Containment::Intersects;
    }
  }
  return result;
}

bool Frustum::intersectsSphere(const glm::vec3& center, float radius) const {
  for (const glm::vec4& p : mPlanes) {
    if (glm::dot(glm::vec3(p), center) + p.w < -radius) {
      return false;
    }
  }
  return true;
}

bool Frustum::contains(const glm::vec3& point) const {
  for (const glm::vec4& p : mPlanes) {
    if (glm::dot(glm::vec3(p), point) + p.w < 0.0f) {
      return false;
    }
  }
  return true;
}

} // namespace sylva
