#pragma once
// Which blades of the field are drawn this frame, and at which level of detail: the CPU reference of the
// grass culling compute pass (tiles against the frustum, then blades by frustum, distance and orientation).

#include <sylva/grass/BladeType.hpp>
#include <sylva/grass/Field.hpp>

#include <glm/mat4x4.hpp>

#include <array>
#include <cstddef>
#include <vector>

namespace sylva::grass {

/** Culling and LOD distances, metres. */
struct CullSettings {
  /** Blades farther than this from the camera are not drawn. */
  float maxDistance = 120.0f;
  /** 16 knots up to lodDistances[0], 8 up to lodDistances[1], then 4. */
  std::array<float, 2> lodDistances{12.0f, 35.0f};
  /**
   * Beyond orientationDistance, blades seen edge-on (|cos| between the blade's face normal and the horizontal
   * view direction below orientationCos) cover less than a pixel of width and are skipped.
   */
  float orientationDistance = 25.0f;
  float orientationCos = 0.12f;
};

/** Throws sylva::Error naming the field for non-finite, negative or out-of-order distances. */
void validate(const CullSettings& settings);

/** A drawn blade. */
struct VisibleBlade {
  FieldBlade blade;
  int lod = 0;
};

/** What culling did. */
struct CullStats {
  std::size_t tiles = 0;
  std::size_t tilesVisible = 0;
  std::array<std::size_t, 3> bladesPerLod{0, 0, 0};
  std::size_t culledFrustum = 0;
  std::size_t culledDistance = 0;
  std::size_t culledOrientation = 0;
  std::size_t drawn() const { return bladesPerLod[0] + bladesPerLod[1] + bladesPerLod[2]; }
};

/**
 * Culls the field for a camera at `eye` (world metres) with view-projection `viewProj` (OpenGL clip space).
 * Tiles are tested as boxes (terrain heights over the tile plus the tallest blade); a blade is tested as the
 * sphere around its upright extent (root to root + height·scale). `types` gives the blades' heights. Appends
 * the drawn blades to `visible` when given.
 */
CullStats cullField(const FieldLayout& layout, const std::vector<gpu::GrassBlade>& patch,
                    const std::vector<BladeType>& types, const terrain::HeightField& terrain,
                    const DensityMap& density, const glm::mat4& viewProj, const glm::vec3& eye,
                    const CullSettings& settings, std::vector<VisibleBlade>* visible = nullptr);

/** The level of detail for a distance (0, 1 or 2). */
int lodForDistance(const CullSettings& settings, float distance);

} // namespace sylva::grass
