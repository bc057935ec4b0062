#pragma once
// Which blades of the field are drawn this frame, and at which level of detail: the CPU reference of the
// grass culling compute passes (tiles against the frustum, then blades by frustum, distance and orientation),
// with the dithered cross-fades between levels and out to the draw distance.

#include <sylva/grass/GrassField.hpp>

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
   * Width of the cross-fade band centred on each LOD distance: inside it a blade is drawn at both levels with
   * complementary dither masks, the finer one fading out as the distance grows.
   */
  float lodFade = 3.0f;
  /** Width of the band before maxDistance over which blades dissolve (dithered) into the ground tint. */
  float farFade = 25.0f;
  /**
   * Beyond orientationDistance, blades seen edge-on (|cos| between the blade's face normal and the horizontal
   * view direction below orientationCos) cover less than a pixel of width and are skipped.
   */
  float orientationDistance = 25.0f;
  float orientationCos = 0.12f;
};

/**
 * Throws sylva::Error naming the field for non-finite or negative values, LOD distances out of order, and
 * bands that overlap (each LOD band must end before the next begins and before the far fade).
 */
void validate(const CullSettings& settings);

/**
 * `settings` with every distance (draw, LOD, fade bands, orientation) multiplied by `factor` > 0: the same
 * rules over a shorter or longer range (valid settings stay valid). The interactive quality steps' grass.
 */
CullSettings scaled(const CullSettings& settings, float factor);

/** How a drawn instance is dithered: Full is drawn everywhere; FadeOut where the pixel's dither threshold is
 * ≥ fade; FadeIn where it is < fade (so a FadeOut and a FadeIn of the same fade cover each pixel once). */
enum class Fade : int { Full = 0, FadeOut = 1, FadeIn = 2 };

/** A drawn instance: a blade at one level (a blade in a cross-fade band gives two). */
struct VisibleBlade {
  FieldBlade blade;
  int lod = 0;
  Fade fade = Fade::Full;
  /** Fade amount in [0, 1]. */
  float amount = 0.0f;
};

/** What culling did. */
struct CullStats {
  /** Tiles looked at: the window of tiles within the draw distance (tileWindow). */
  std::size_t tiles = 0;
  std::size_t tilesVisible = 0;
  /** Instances in each level's list (a blade in a cross-fade band is in two lists). */
  std::array<std::size_t, 3> bladesPerLod{0, 0, 0};
  /** Distinct blades drawn. */
  std::size_t blades = 0;
  std::size_t culledFrustum = 0;
  std::size_t culledDistance = 0;
  std::size_t culledOrientation = 0;
  std::size_t drawn() const { return blades; }
  std::size_t instances() const { return bladesPerLod[0] + bladesPerLod[1] + bladesPerLod[2]; }
};

/**
 * Culls `field` for a camera at `eye` (world metres) with view-projection `viewProj` (OpenGL clip space).
 * Tiles are tested as boxes (the tile's terrain height range plus the tallest blade); a blade as the sphere
 * around its upright extent (root to root + length·scale). Appends the drawn instances to `visible`.
 */
CullStats cullField(const GrassField& field, const glm::mat4& viewProj, const glm::vec3& eye,
                    const CullSettings& settings, std::vector<VisibleBlade>* visible = nullptr);

/** The level of detail for a distance (0, 1 or 2), ignoring the cross-fade bands. */
int lodForDistance(const CullSettings& settings, float distance);

/**
 * The instances a blade at `distance` gives (one, or two inside a cross-fade band), appended to `out` as
 * (lod, fade, amount) with `blade` unset; none beyond maxDistance. The culling shader's rule.
 */
void lodInstances(const CullSettings& settings, float distance, std::vector<VisibleBlade>& out);

} // namespace sylva::grass
