#pragma once
// Which blades of the field are drawn this frame, and at which level of detail: the CPU reference of the
// grass culling compute passes (tiles against the frustum, then blades by frustum, distance and orientation),
// with the dithered cross-fades between levels and out to the draw distance.

#include <sylva/grass/GrassField.hpp>

#include <glm/mat4x4.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
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
  /** The |cos| below which a blade beyond orientationDistance counts as edge-on. */
  float orientationCos = 0.12f;
  /**
   * Near the camera the field thickens into tufts: each blade of a tile gets up to nearLayers − 1 more beside
   * it (other blades of the patch, rooted within tuftRadius of it). Layer L (1 … nearLayers − 1) is drawn up
   * to nearLayerReach(L) = reach·√((nearLayers − L)/(nearLayers − 1)) metres, reach = nearDistance but never
   * past the start of the first level-of-detail band (tuft blades are level 0), and dithered out over the
   * last quarter of that, so the density rises smoothly to nearLayers times the field's towards the camera
   * without popping. 1: the field's density everywhere. Capped at the layers a tile's range can hold (patch
   * blades / blades per tile). In a simulated tile a tuft blade follows its field blade's simulated bend
   * (docs/grass.md).
   */
  int nearLayers = 8;
  /** Distance the near layers reach, metres (see nearLayers). */
  float nearDistance = 8.0f;
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
  /** The blade. */
  FieldBlade blade;
  /** Its level of detail (0: finest). */
  int lod = 0;
  /** Whether it is drawn whole or fading in or out of a cross-fade band. */
  Fade fade = Fade::Full;
  /** Fade amount in [0, 1]. */
  float amount = 0.0f;
};

/** What culling did. */
struct CullStats {
  /** Tiles looked at: the window of tiles within the draw distance (tileWindow). */
  std::size_t tiles = 0;
  /** Of those, tiles inside the frustum. */
  std::size_t tilesVisible = 0;
  /** Instances in each level's list (a blade in a cross-fade band is in two lists). */
  std::array<std::size_t, 3> bladesPerLod{0, 0, 0};
  /** Distinct blades drawn. */
  std::size_t blades = 0;
  /** Blades culled by the frustum. */
  std::size_t culledFrustum = 0;
  /** Blades culled beyond the draw distance (or dissolved in the far fade). */
  std::size_t culledDistance = 0;
  /** Blades culled as edge-on. */
  std::size_t culledOrientation = 0;
  /** Of the distinct blades drawn, those of the near layers (tuft blades, CullSettings::nearLayers). */
  std::size_t tuftBlades = 0;
  /** Distinct blades drawn (as `blades`). */
  std::size_t drawn() const { return blades; }
  /** Instances drawn over all levels (a blade in a cross-fade band counts twice). */
  std::size_t instances() const { return bladesPerLod[0] + bladesPerLod[1] + bladesPerLod[2]; }
};

/**
 * Culls `field` for a camera at `eye` (world metres) with view-projection `viewProj` (OpenGL clip space).
 * Tiles are tested as boxes (the tile's terrain height range plus the tallest blade); a blade as the sphere
 * around its upright extent (root to root + length·scale). Appends the drawn instances to `visible`.
 */
CullStats cullField(const GrassField& field, const glm::mat4& viewProj, const glm::vec3& eye,
                    const CullSettings& settings, std::vector<VisibleBlade>* visible = nullptr);

/** How far (metres) the near layers reach at most: nearDistance, but never into the first LOD band. */
float nearReach(const CullSettings& settings);

/** The near layers a tile of `layout` draws: settings.nearLayers, capped at patchBlades / bladesPerTile (≥
 * 1). */
int nearLayerCount(const CullSettings& settings, const FieldLayout& layout, std::uint32_t patchBlades);

/** How far (metres) near layer `layer` (1 ≤ layer < `layers`) is drawn (CullSettings::nearLayers). */
float nearLayerReach(const CullSettings& settings, int layer, int layers);

/**
 * Half the side of the square (metres, centred on its field blade) a tuft blade is rooted in: half the
 * field's mean blade spacing, tileSize / (2·√bladesPerTile), so tufts fill the ground between the field's
 * blades.
 */
float tuftRadius(const FieldLayout& layout);

/**
 * The tuft blades of tile (tx, tz) within their layers' reach of `eye` (world metres): blade j of the tile's
 * range for j in bladesPerTile … layers·bladesPerTile − 1 is layer L = j / bladesPerTile, beside field blade
 * i = j mod bladesPerTile (FieldBlade::guide = i), rooted at that blade's root plus (its own placement / tile
 * size − ½)·2·tuftRadius, on the terrain. It is drawn only where its field blade is (inside the terrain, on
 * valid heights, kept by the density) and its own root is on valid terrain. `visit` gets the blade and its
 * layer's reach. cullField's and the blade pass's near loop.
 */
void forEachTuftBlade(const GrassField& field, int tx, int tz, const glm::vec3& eye,
                      const CullSettings& settings,
                      const std::function<void(const FieldBlade&, float reach)>& visit);

/** A tuft blade's fade at `distance` from the eye within its layer's `reach` (metres): Full, or FadeOut over
 * the last quarter of the reach. */
void tuftFade(float reach, float distance, VisibleBlade& v);

/** The level of detail for a distance (0, 1 or 2), ignoring the cross-fade bands. */
int lodForDistance(const CullSettings& settings, float distance);

/**
 * The instances a blade at `distance` gives (one, or two inside a cross-fade band), appended to `out` as
 * (lod, fade, amount) with `blade` unset; none beyond maxDistance. The culling shader's rule.
 */
void lodInstances(const CullSettings& settings, float distance, std::vector<VisibleBlade>& out);

} // namespace sylva::grass
