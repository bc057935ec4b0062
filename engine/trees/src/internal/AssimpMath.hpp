#pragma once
// Assimp ↔ glm conversions shared by the trees' Assimp loaders (pieces in Import.cpp, leaf clouds in
// Foliage.cpp).

#include <assimp/matrix4x4.h>
#include <glm/mat4x4.hpp>

namespace sylva::trees::internal {

/** Assimp's row-major 4x4 matrix as a column-major glm matrix (the same transform). */
inline glm::mat4 toGlm(const aiMatrix4x4& m) {
  glm::mat4 out(1.0f);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      out[c][r] = m[static_cast<unsigned>(r)][static_cast<unsigned>(c)];
    }
  }
  return out;
}

} // namespace sylva::trees::internal
