#include <sylva/trees/Piece.hpp>
#include "internal/Finite.hpp"

#include <sylva/core/Error.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <map>
#include <numbers>

namespace sylva::trees {
namespace {

using internal::finite;

// Corner constants: computed once in double and rounded, so every caller (and the shader's table, written
// from the same values) sees identical floats.
struct CornerTable {
  std::array<glm::vec3, kRimCorners> corner{};
  std::array<glm::vec3, kRimCorners> normal{};
  CornerTable() {
    const double cb = std::cos(static_cast<double>(kRimConeAngle));
    const double sb = std::sin(static_cast<double>(kRimConeAngle));
    for (int k = 0; k < kRimCorners; ++k) {
      const double a = std::numbers::pi / 3.0 * k;
      // Exact zeros and halves where the hexagon has them.
      const double c = std::abs(std::cos(a)) < 1e-12 ? 0.0 : std::cos(a);
      const double s = std::abs(std::sin(a)) < 1e-12 ? 0.0 : std::sin(a);
      corner[static_cast<std::size_t>(k)] = glm::vec3(static_cast<float>(c), 0.0f, static_cast<float>(s));
      normal[static_cast<std::size_t>(k)] =
          glm::vec3(static_cast<float>(cb * c), static_cast<float>(sb), static_cast<float>(cb * s));
    }
  }
};

const CornerTable& table() {
  static const CornerTable t;
  return t;
}

/** Uniform scale of a similarity, or -1 when `m` is not one (within `tolerance`, relative). */
float similarityScale(const glm::mat4& m, float tolerance) {
  if (std::abs(m[0][3]) > tolerance || std::abs(m[1][3]) > tolerance || std::abs(m[2][3]) > tolerance ||
      std::abs(m[3][3] - 1.0f) > tolerance) {
    return -1.0f;
  }
  const glm::vec3 x(m[0]);
  const glm::vec3 y(m[1]);
  const glm::vec3 z(m[2]);
  const float s = glm::length(x);
  if (!(s > 1e-6f)) {
    return -1.0f;
  }
  const float rel = tolerance * 10.0f;
  if (std::abs(glm::length(y) - s) > rel * s || std::abs(glm::length(z) - s) > rel * s ||
      std::abs(glm::dot(x, y)) > rel * s * s || std::abs(glm::dot(y, z)) > rel * s * s ||
      std::abs(glm::dot(x, z)) > rel * s * s || glm::dot(glm::cross(x, y), z) <= 0.0f) {
    return -1.0f;
  }
  return s;
}

} // namespace

glm::vec3 rimCorner(int k) {
  return table().corner[static_cast<std::size_t>(((k % 6) + 6) % 6)];
}

glm::vec3 rimNormal(int k) {
  return table().normal[static_cast<std::size_t>(((k % 6) + 6) % 6)];
}

glm::mat4 rimRotation(int steps) {
  // Rotation about +y taking corner k (angle 60°k from x towards z) to corner k + steps.
  const int s = ((steps % 6) + 6) % 6;
  if (s == 0) {
    return glm::mat4(1.0f);
  }
  const glm::vec3 x = rimCorner(s);
  const glm::vec3 z = glm::vec3(-x.z, 0.0f, x.x); // x rotated by +90° in the same sense
  glm::mat4 m(1.0f);
  m[0] = glm::vec4(x, 0.0f);
  m[2] = glm::vec4(z, 0.0f);
  return m;
}

void validatePiece(const Piece& piece, const std::string& where, float tolerance) {
  const std::string name = piece.name.empty() ? std::string("piece") : piece.name;
  if (piece.vertices.empty() || piece.quads.empty()) {
    fail("{}: piece '{}' has no quads", where, name);
  }
  if (piece.rims.empty()) {
    fail("{}: piece '{}': missing root rim", where, name);
  }
  if (piece.joints.size() != piece.rims.size()) {
    fail("{}: piece '{}': {} joints for {} rims (one root joint and one terminal joint per leaf rim)", where,
         name, piece.joints.size(), piece.rims.size());
  }
  if (piece.rims.size() > 16) {
    fail("{}: piece '{}': {} leaf rims (at most 15)", where, name, piece.rims.size() - 1);
  }
  if (!piece.tileClass.empty() && piece.tileClass.size() != piece.quads.size()) {
    fail("{}: piece '{}': {} tile classes for {} quads", where, name, piece.tileClass.size(),
         piece.quads.size());
  }
  const auto n = static_cast<std::uint32_t>(piece.vertices.size());
  for (std::size_t q = 0; q < piece.quads.size(); ++q) {
    for (std::uint32_t i : piece.quads[q]) {
      if (i >= n) {
        fail("{}: piece '{}': quad {} refers to vertex {} of {}", where, name, q, i, n);
      }
    }
  }
  for (std::size_t i = 0; i < piece.vertices.size(); ++i) {
    const PieceVertex& v = piece.vertices[i];
    if (!finite(v.position) || !finite(v.normal) ||
        !std::isfinite(v.weights.x + v.weights.y + v.weights.z + v.weights.w)) {
      fail("{}: piece '{}': vertex {} is not finite", where, name, i);
    }
    float sum = 0.0f;
    for (int w = 0; w < 4; ++w) {
      if (v.weights[w] < 0.0f ||
          (v.weights[w] > 0.0f && v.joints[static_cast<std::size_t>(w)] >= piece.joints.size())) {
        fail("{}: piece '{}': vertex {} has a bad joint weight", where, name, i);
      }
      sum += v.weights[w];
    }
    if (std::abs(sum - 1.0f) > 1e-3f) {
      fail("{}: piece '{}': vertex {} weights sum to {} (expected 1)", where, name, i, sum);
    }
  }
  for (std::size_t r = 0; r < piece.rims.size(); ++r) {
    const Rim& rim = piece.rims[r];
    const std::string rimName = r == 0 ? std::string("root rim") : fmt::format("leaf rim {}", r);
    if (!finite(rim.frame)) {
      fail("{}: piece '{}': {}: frame is not finite", where, name, rimName);
    }
    if (r == 0) {
      for (int c = 0; c < 4; ++c) {
        for (int k = 0; k < 4; ++k) {
          if (std::abs(rim.frame[c][k] - (c == k ? 1.0f : 0.0f)) > tolerance) {
            fail("{}: piece '{}': root rim is not the standard rim (unit hexagon at the origin, axis +y)",
                 where, name);
          }
        }
      }
    }
    const float scale = similarityScale(rim.frame, tolerance);
    if (scale <= 0.0f) {
      fail("{}: piece '{}': {}: building transform is not a similarity", where, name, rimName);
    }
    if (rim.joint != static_cast<int>(r) || piece.joints[r].rim != static_cast<int>(r)) {
      fail("{}: piece '{}': {}: must carry joint {}", where, name, rimName, r);
    }
    const glm::mat3 rotation = glm::mat3(rim.frame) / scale;
    for (int k = 0; k < kRimCorners; ++k) {
      const std::uint32_t vi = rim.vertices[static_cast<std::size_t>(k)];
      if (vi >= n) {
        fail("{}: piece '{}': {}: corner {} refers to vertex {} of {}", where, name, rimName, k, vi, n);
      }
      const PieceVertex& v = piece.vertices[vi];
      const glm::vec3 expected = glm::vec3(rim.frame * glm::vec4(rimCorner(k), 1.0f));
      if (glm::length(v.position - expected) > tolerance * std::max(1.0f, scale)) {
        fail("{}: piece '{}': {} is not a regular hexagon (corner {} is {:.4g} off)", where, name, rimName, k,
             glm::length(v.position - expected));
      }
      const glm::vec3 normal = glm::normalize(rotation * rimNormal(k));
      if (glm::length(v.normal - normal) > 1e-3f) {
        fail("{}: piece '{}': {}: wrong normal at corner {} (the rim's quad ring must be the fixed cone)",
             where, name, rimName, k);
      }
      if (v.rim != static_cast<int>(r) || v.corner != k || v.joints[0] != r || v.weights.x != 1.0f) {
        fail("{}: piece '{}': {}: corner {} is not bound with weight 1 to joint {}", where, name, rimName, k,
             r);
      }
    }
  }
  // Closed apart from the rims: every edge is shared by two quads, or by one quad and lies on a rim.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& q : piece.quads) {
    for (int e = 0; e < 4; ++e) {
      const std::uint32_t a = q[static_cast<std::size_t>(e)];
      const std::uint32_t b = q[static_cast<std::size_t>((e + 1) % 4)];
      if (a == b) {
        fail("{}: piece '{}': degenerate quad edge at vertex {}", where, name, a);
      }
      edges[{a, b}] += 1;
    }
  }
  for (const auto& [edge, count] : edges) {
    if (count > 1) {
      fail("{}: piece '{}': edge {}–{} is used twice in the same direction (inconsistent quad orientation)",
           where, name, edge.first, edge.second);
    }
    if (edges.count({edge.second, edge.first}) == 0) {
      const PieceVertex& a = piece.vertices[edge.first];
      const PieceVertex& b = piece.vertices[edge.second];
      if (a.rim < 0 || a.rim != b.rim) {
        fail("{}: piece '{}': open edge {}–{} that is not on a rim (the piece must be closed apart from its "
             "rims)",
             where, name, edge.first, edge.second);
      }
    }
  }
}

void snapRims(Piece& piece) {
  for (std::size_t r = 0; r < piece.rims.size(); ++r) {
    const Rim& rim = piece.rims[r];
    const glm::mat3 linear(rim.frame);
    for (int k = 0; k < kRimCorners; ++k) {
      PieceVertex& v = piece.vertices[rim.vertices[static_cast<std::size_t>(k)]];
      v.position = glm::vec3(rim.frame * glm::vec4(rimCorner(k), 1.0f));
      v.normal = glm::normalize(linear * rimNormal(k));
      v.rim = static_cast<int>(r);
      v.corner = k;
      v.joints = {static_cast<std::uint8_t>(rim.joint), 0, 0, 0};
      v.weights = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
    }
  }
}

void computeNormals(Piece& piece) {
  std::vector<glm::vec3> sum(piece.vertices.size(), glm::vec3(0.0f));
  for (const auto& q : piece.quads) {
    const glm::vec3 p0 = piece.vertices[q[0]].position;
    const glm::vec3 p1 = piece.vertices[q[1]].position;
    const glm::vec3 p2 = piece.vertices[q[2]].position;
    const glm::vec3 p3 = piece.vertices[q[3]].position;
    // Twice the vector area of the quad (its diagonals' cross product).
    const glm::vec3 area = glm::cross(p2 - p0, p3 - p1);
    for (std::uint32_t i : q) {
      sum[i] += area;
    }
  }
  for (std::size_t i = 0; i < piece.vertices.size(); ++i) {
    if (piece.vertices[i].rim < 0 && glm::length(sum[i]) > 0.0f) {
      piece.vertices[i].normal = glm::normalize(sum[i]);
    }
  }
}

Bounds pieceBounds(const Piece& piece) {
  Bounds b{glm::vec3(1e30f), glm::vec3(-1e30f)};
  for (const PieceVertex& v : piece.vertices) {
    b.min = glm::min(b.min, v.position);
    b.max = glm::max(b.max, v.position);
  }
  return b;
}

} // namespace sylva::trees
