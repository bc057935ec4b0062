#include <sylva/grass/Expand.hpp>

#include <sylva/core/Error.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <math.h>
#include <cmath>

namespace sylva::grass {
namespace {

/** Rotates v about the unit axis by angle (Rodrigues). */
glm::vec3 rotate(const glm::vec3& v, const glm::vec3& axis, float angle) {
  float s = 0.0f;
  float c = 1.0f;
  ::sincosf(angle, &s, &c);
  return v * c + glm::cross(axis, v) * s + axis * (glm::dot(axis, v) * (1.0f - c));
}

} // namespace

float bendAngle(float windSpeed, float stiffness) {
  return std::min(1.3f, 0.12f * std::abs(windSpeed) / std::max(stiffness, 0.05f));
}

namespace {

/** The bent knot line: centres (world) and each knot's bend angle, as expandBlade and the shaders walk it. */
/** A blade's turn about the vertical (its rotation), blade space → world directions. */
struct Turn {
  float c = 1.0f;
  float s = 0.0f;
  explicit Turn(float angle) : c(std::cos(angle)), s(std::sin(angle)) {}
  glm::vec3 operator()(const glm::vec3& v) const { return {c * v.x + s * v.z, v.y, -s * v.x + c * v.z}; }
};

struct CentreLine {
  std::array<glm::vec3, SYLVA_GRASS_LOD0_KNOTS> centre{};
  std::array<float, SYLVA_GRASS_LOD0_KNOTS> angle{};
  glm::vec3 axis{1.0f, 0.0f, 0.0f};
  float total = 1.0f;
  Turn turn{0.0f};
};

CentreLine walkBlade(const BladeType& type, int lod, const gpu::GrassBlade& blade, const glm::vec3& root,
                     const glm::vec2& windVelocity) {
  if (lod < 0 || lod >= static_cast<int>(kLodKnots.size())) {
    fail("grass: level of detail {} outside 0..2", lod);
  }
  const BladeShapeLod& shape = type.lods[static_cast<std::size_t>(lod)];
  const std::size_t n = shape.knots.size();
  const float scale = blade.placement.w;
  CentreLine line;
  line.turn = Turn(blade.placement.z);
  const Turn& turn = line.turn;
  const float speed = glm::length(windVelocity);
  const float theta = bendAngle(speed, type.stiffness);
  // Downwind bend: about the horizontal axis across the wind (up × wind), so tips lean downwind.
  const glm::vec3 downwind =
      speed > 1e-6f ? glm::vec3(windVelocity.x, 0.0f, windVelocity.y) / speed : glm::vec3(0.0f);
  line.axis = speed > 1e-6f ? glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), downwind))
                            : glm::vec3(1.0f, 0.0f, 0.0f);
  float total = 0.0f;
  for (std::size_t k = 1; k < n; ++k) {
    total += glm::length(shape.knots[k] - shape.knots[k - 1]);
  }
  line.total = std::max(total, 1e-9f);
  line.centre[0] = root;
  float along = 0.0f;
  for (std::size_t k = 1; k < n; ++k) {
    const glm::vec3 segment = turn(shape.knots[k] - shape.knots[k - 1]) * scale;
    along += glm::length(shape.knots[k] - shape.knots[k - 1]);
    const float u = along / line.total;
    line.angle[k] = theta * u * u;
    line.centre[k] = line.centre[k - 1] + rotate(segment, line.axis, line.angle[k]);
  }
  return line;
}

} // namespace

std::vector<glm::vec3> bladeCentreLine(const BladeType& type, int lod, const gpu::GrassBlade& blade,
                                       const glm::vec3& root, const glm::vec2& windVelocity) {
  const CentreLine line = walkBlade(type, lod, blade, root, windVelocity);
  const std::size_t n = type.lods[static_cast<std::size_t>(lod)].knots.size();
  return {line.centre.begin(), line.centre.begin() + static_cast<std::ptrdiff_t>(n)};
}

void bladeCentreLine(const BladeType& type, const gpu::GrassBlade& blade, const glm::vec3& root,
                     const glm::vec2& windVelocity, std::span<glm::vec3, SYLVA_GRASS_LOD0_KNOTS> out) {
  const CentreLine line = walkBlade(type, 0, blade, root, windVelocity);
  std::copy(line.centre.begin(), line.centre.end(), out.begin());
}

std::vector<BladeVertex> expandBlade(const BladeType& type, int lod, const gpu::GrassBlade& blade,
                                     const glm::vec3& root, const glm::vec2& windVelocity) {
  const CentreLine line = walkBlade(type, lod, blade, root, windVelocity);
  const BladeShapeLod& shape = type.lods[static_cast<std::size_t>(lod)];
  const std::size_t n = shape.knots.size();
  const float scale = blade.placement.w;
  const Turn& turn = line.turn;
  const auto& centre = line.centre;
  std::vector<BladeVertex> out;
  out.reserve(2 * n);
  float along = 0.0f;
  for (std::size_t k = 0; k < n; ++k) {
    if (k > 0) {
      along += glm::length(shape.knots[k] - shape.knots[k - 1]);
    }
    // The face normal (+Z in blade space) and the blade's tangent, bent like the knot line.
    const glm::vec3 face = rotate(turn(glm::vec3(0.0f, 0.0f, 1.0f)), line.axis, line.angle[k]);
    const glm::vec3 tangent = glm::normalize(centre[std::min(k + 1, n - 1)] - centre[k > 0 ? k - 1 : 0]);
    glm::vec3 side = glm::cross(tangent, face);
    side = glm::length(side) > 1e-9f ? glm::normalize(side) : turn(glm::vec3(1.0f, 0.0f, 0.0f));
    const glm::vec3 normal = glm::normalize(glm::cross(side, tangent));
    const float half = 0.5f * shape.widths[k] * scale;
    const float v = along / line.total;
    out.push_back({centre[k] - side * half, normal, v, -1.0f});
    out.push_back({centre[k] + side * half, normal, v, 1.0f});
  }
  return out;
}

} // namespace sylva::grass
