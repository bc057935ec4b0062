#pragma once
// Blade types of the grass field: knot lines with widths at the field's three levels of detail (16, 8 and 4
// knots), a colour and a stiffness. Made procedurally, or from blade-model files of the capture module.

#include <sylva/blades/BladeModel.hpp>

#include <glm/vec3.hpp>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::grass {

/** Knot counts of the levels of detail, finest first. */
inline constexpr std::array<int, 3> kLodKnots{16, 8, 4};

/** One level: knots root → tip in blade space (metres, root at the origin, +Y up, +Z the face) and widths. */
struct BladeShapeLod {
  std::vector<glm::vec3> knots;
  std::vector<float> widths;
};

/** A blade type. */
struct BladeType {
  std::string name;
  /** kLodKnots.size() levels with kLodKnots[i] knots each. */
  std::array<BladeShapeLod, 3> lods;
  /** Base colour, linear RGB [0, 1]. */
  glm::vec3 colour{0.2f, 0.45f, 0.1f};
  /** Bending stiffness in [0.05, 1]: 1 barely bends in wind, small values bow deeply. */
  float stiffness = 0.5f;
  /** Length along the finest knot line, metres. */
  float length() const;
};

/**
 * A few procedural types so the field works without captured data: "meadow" (slim, 35 cm), "fescue" (fine,
 * arching, 25 cm), "broadleaf" (wide, 18 cm).
 */
std::vector<BladeType> proceduralBladeTypes();

/**
 * A type from a captured blade model: its finest level resampled by arc length to 16, 8 and 4 knots (root and
 * tip kept), colour from the model when it has one (else `colour`). Throws sylva::Error naming the model for
 * levels with fewer than 2 knots or a zero length.
 */
BladeType bladeTypeFromModel(const blades::BladeModel& model, const glm::vec3& colour, float stiffness);

/** Every blade of a blade-model file as a type; throws sylva::Error naming the file (empty file: an error).
 */
std::vector<BladeType> loadBladeTypes(const std::filesystem::path& path,
                                      const glm::vec3& colour = {0.2f, 0.45f, 0.1f}, float stiffness = 0.5f);

/** Resamples a knot line (and widths) to `count` knots evenly spaced by arc length; ends kept. */
BladeShapeLod resampleBlade(const std::vector<glm::vec3>& knots, const std::vector<float>& widths, int count);

} // namespace sylva::grass
