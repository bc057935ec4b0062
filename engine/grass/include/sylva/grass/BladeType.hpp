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
  /** Knot positions, blade space (metres), root first. */
  std::vector<glm::vec3> knots;
  /** Full width at each knot, metres. */
  std::vector<float> widths;
};

/** A blade type. */
struct BladeType {
  /** The type's name (the blade model's name, or a procedural type's). */
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

/**
 * Sizes a grass blade can plausibly have, metres: from a 5 mm sprout to 5 m giant reed, at most 30 cm wide
 * and at least 0.1 mm at its widest (an all-zero width profile draws nothing). A model outside them is almost
 * always a unit mistake (millimetres read as metres) or a broken capture; `extreme` lets it through on
 * purpose.
 */
struct BladeSizeLimits {
  /** Shortest length, metres. */
  float minLength = 0.005f;
  /** Longest length, metres. */
  float maxLength = 5.0f;
  float minWidth = 1e-4f; ///< of the widest knot
  float maxWidth = 0.3f;  ///< of the widest knot
};

/**
 * Throws sylva::Error, naming the model, its size and how to allow it, when `model` (its finest level) is
 * outside `limits`.
 */
void checkBladeSize(const blades::BladeModel& model, const BladeSizeLimits& limits = {});

/**
 * Every blade of a blade-model file as a type; throws sylva::Error naming the file (empty file: an error),
 * and for a blade outside BladeSizeLimits unless `extreme` is set.
 */
std::vector<BladeType> loadBladeTypes(const std::filesystem::path& path,
                                      const glm::vec3& colour = {0.2f, 0.45f, 0.1f}, float stiffness = 0.5f,
                                      bool extreme = false);

/** Resamples a knot line (and widths) to `count` knots evenly spaced by arc length; ends kept. */
BladeShapeLod resampleBlade(const std::vector<glm::vec3>& knots, const std::vector<float>& widths, int count);

} // namespace sylva::grass
