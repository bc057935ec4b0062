#pragma once
// Whether every component of a vector or matrix is a finite number (input validation of the trees module).

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cmath>

namespace sylva::trees::internal {

inline bool finite(const glm::vec2& v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}

inline bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) {
        return false;
      }
    }
  }
  return true;
}

} // namespace sylva::trees::internal
