#pragma once

#include <sylva/render/Environment.hpp>

#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace sylva::render {

/**
 * The analytic sky of Preetham, Shirley and Smits (1999, "A practical analytic model for daylight") with the
 * sun's disc, the aerial perspective built on it, and the geometry of the sun's lens flare. CPU references of
 * shaders/common/sky.glsl, shaders/common/atmosphere.glsl (mode 1) and shaders/render/flare.vert: the same
 * float operations in the same order. Pure CPU, thread-safe.
 *
 * Radiance is linear sRGB in the range the lit colours of the engine use (not physical units): Preetham's
 * luminance in kcd/m² is multiplied per channel by kSkyCalibration (which also white-balances to the warm
 * direct sun) and by the exposure, so that at turbidity 3, sun 40° up and exposure 1 the horizon averaged
 * over all azimuths equals the engine's old fog colour (0.62, 0.72, 0.85).
 */

/** Parameters of the sky and its haze (mirrors gpu::FrameUniforms: see skyParamsFrom). */
struct SkyParams {
  float turbidity = 3.0f;      ///< 1.7 (very clear) .. 10 (hazy); clamped to that range
  float exposure = 1.0f;       ///< scale on sky radiance (and on the sun's disc and glow)
  float hazeDensity = 0.0012f; ///< aerial perspective extinction, per metre
  float sunIntensity = 1.1f;   ///< the sun's strength (FrameUniforms::sunDirection.w): disc and forward glow
};

/** Per-channel scale from Preetham's luminance (kcd/m², linear sRGB) to engine radiance at exposure 1. */
inline constexpr glm::vec3 kSkyCalibration{0.0562762f, 0.0776169f, 0.0857261f};
/** Henyey–Greenstein asymmetry of the sun-forward (Mie) glow in the haze. */
inline constexpr float kSkyMieG = 0.76f;
/** Strength of that glow (times sunIntensity · exposure · HG phase). */
inline constexpr float kSkyMieStrength = 0.05f;
/** Colour of direct sunlight (as in shaders/common/lighting.glsl). */
inline constexpr glm::vec3 kSunColour{1.0f, 0.96f, 0.88f};
/** Angular radius of the drawn sun disc, radians (about twice the real sun's, so it reads at 720p). */
inline constexpr float kSunAngularRadius = 0.01f;
/** Radiance of the sun's disc per unit sunIntensity · exposure (saturates 8-bit output: a white disc). */
inline constexpr float kSunDiscRadiance = 40.0f;

/** The sky parameters a frame carries: turbidity, exposure (atmosphere.y/z), haze density (fog density), sun.
 */
SkyParams skyParamsFrom(const Environment& environment);

/**
 * Perez et al. distribution F(θ, γ) = (1 + A e^{B / cos θ})(1 + C e^{D γ} + E cos² γ) for the view's zenith
 * angle θ (given as cos θ, clamped ≥ 0.001) and its angle γ to the sun (radians, with cos γ).
 */
float perezDistribution(const std::array<float, 5>& coefficients, float cosTheta, float gamma,
                        float cosGamma);

/** Preetham's Perez coefficients A..E for luminance Y and chromaticities x, y at `turbidity`. */
struct PerezCoefficients {
  std::array<float, 5> Y; ///< A..E of luminance
  std::array<float, 5> x; ///< A..E of chromaticity x
  std::array<float, 5> y; ///< A..E of chromaticity y
};
/** The Perez coefficients at `turbidity` (Preetham et al. 1999). */
PerezCoefficients perezCoefficients(float turbidity);

/** Zenith luminance (kcd/m²) and chromaticity (x, y) for `turbidity` and the sun's zenith angle (radians). */
glm::vec3 zenithLuminanceChromaticity(float turbidity, float sunZenith);

/** CIE xyY → linear sRGB (D65 primaries). */
glm::vec3 xyYToLinearSrgb(float x, float y, float Y);

/**
 * The sky's highlight roll-off: a colour whose largest channel m exceeds 1 keeps its hue (c / m) and fades
 * towards white by 1 − 1/m, so the bright sky around the sun turns white instead of clipping channel by
 * channel (which the blue-heavy calibration would tint cyan). Identity for m ≤ 1; the result never exceeds 1.
 */
glm::vec3 skyHighlight(const glm::vec3& c);

/**
 * Sky radiance (linear sRGB, engine scale) seen along world direction `viewDir` (unit, towards the sky) with
 * the sun towards `sunDir` (unit). Directions below the horizon see the horizon in their azimuth; a sun below
 * the horizon is treated as on it. No sun disc.
 */
glm::vec3 skyRadiance(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params);

/** The sun's disc along `viewDir`: kSunDiscRadiance · sunIntensity · exposure · kSunColour inside
 * kSunAngularRadius (angle measured by |view × sun|), with a soft edge over its outer fifth; zero elsewhere.
 */
glm::vec3 sunDisc(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params);

/** What the sky pass draws: skyHighlight(skyRadiance) + sunDisc. */
glm::vec3 skyWithSun(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params);

/**
 * Exposure that keeps the sky's brightness steady as the sun and the turbidity change: the ratio of
 * Preetham's luminance Y averaged over 64 horizon azimuths at turbidity 3 and sun 40° up (the calibration
 * point) to the same average for `sunDir` and `turbidity`. Exactly 1 at the calibration point. Multiply a
 * scene's exposure by it when the sun or the haze is animated; Preetham's absolute luminance grows about
 * threefold from T = 3 to 10.
 */
float skyAutoExposure(const glm::vec3& sunDir, float turbidity);

/** Henyey–Greenstein phase function for `cosAngle` between light and view and asymmetry `g` (per steradian).
 */
float henyeyGreenstein(float cosAngle, float g);

/**
 * Light the air scatters towards the camera along `viewDir`: the sky radiance in that direction (towards the
 * horizon for directions below it) plus the sun-forward Mie glow kSkyMieStrength · sunIntensity · exposure ·
 * HG(view·sun, kSkyMieG) · kSunColour, through skyHighlight.
 */
glm::vec3 skyInscatter(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params);

/**
 * Aerial perspective: a surface of linear colour `lit` seen `distance` metres away along unit `viewDir`
 * (camera → surface, world space) becomes lit · T + skyInscatter · (1 − T), T = exp(−hazeDensity · distance).
 */
glm::vec3 aerial(const glm::vec3& lit, const glm::vec3& viewDir, float distance, const glm::vec3& sunDir,
                 const SkyParams& params);

/**
 * World-space unit view direction through normalised device coordinates `ndc` ([-1, 1]², y up) of a symmetric
 * perspective `viewProj` = P · V with world → view `view`: how shaders/render/sky.vert builds its rays.
 */
glm::vec3 skyViewDirection(const glm::mat4& viewProj, const glm::mat4& view, const glm::vec2& ndc);

/** One ghost of the lens flare: a soft disc on the line from the sun's screen position through the centre. */
struct FlareGhost {
  glm::vec2 centre; ///< normalised device coordinates
  float radius;     ///< in NDC y units (a circle on screen: x extent radius / aspect)
  glm::vec3 colour; ///< additive linear colour at full visibility and sunIntensity 1
  int halo; ///< 1 = the glow around the sun (falls off from the centre), 0 = a ghost (ring-brightened disc)
};

/** The flare's ghost table: position t along sun → centre (0 = sun, 1 = screen centre, 2 = mirrored sun). */
struct FlareGhostDesc {
  float t;          ///< position along sun → screen centre
  float radius;     ///< NDC y units, as FlareGhost::radius
  glm::vec3 colour; ///< linear tint
  int halo;         ///< 1: the glow around the sun, 0: a ghost
};
/** Ghosts of the lens flare. */
inline constexpr int kFlareGhostCount = 8;
/** The table, shared with shaders/render/flare.vert (same values and order). */
const std::array<FlareGhostDesc, kFlareGhostCount>& flareGhostTable();

/** Ghost geometry for the sun at `sunNdc`: centre = sunNdc · (1 − t), table radius and colour. */
std::vector<FlareGhost> flareGhosts(const glm::vec2& sunNdc);

/** Additive brightness of a flare sprite at `r` = distance from its centre over its radius (0 beyond 1). */
float flareSpriteProfile(float r, int halo);

/** Number of depth samples of the sun's visibility test (one work group of
 * shaders/render/flare_visibility.comp). */
inline constexpr int kFlareSamples = 64;

/**
 * Offset of visibility sample `index` (0..kFlareSamples−1) in units of the sample disc's radius: a Vogel
 * (golden-angle) spiral, r = sqrt((index + 0.5) / N), angle = index · 2.39996323.
 */
glm::vec2 flareSampleOffset(int index);

/**
 * The sun's projection: xy = window pixel position (origin bottom-left, pixel centres at +0.5) of direction
 * `sunDir` under `viewProj` on a `width`×`height` target; z = 1 when the sun is in front of the camera (clip
 * w > 0), else 0; w = radius of the sample disc in pixels: the sun's angular radius projected at the screen
 * centre, at least `minRadiusPixels`.
 */
glm::vec4 sunScreenPosition(const glm::mat4& viewProj, const glm::vec3& sunDir, int width, int height,
                            float minRadiusPixels);

/**
 * CPU reference of the flare's visibility test: the fraction of the kFlareSamples pixels of the disc around
 * the sun whose window depth (`depth(x, y)`, x right, y up from the bottom row) is ≥ 1 (nothing drawn there).
 * Samples off the target count as hidden; the sun behind the camera gives 0.
 */
template <typename DepthAt>
float flareVisibility(const glm::vec4& sunScreen, int width, int height, DepthAt&& depth) {
  if (sunScreen.z < 0.5f) {
    return 0.0f;
  }
  int visible = 0;
  for (int i = 0; i < kFlareSamples; ++i) {
    const glm::vec2 p = glm::vec2(sunScreen) + flareSampleOffset(i) * sunScreen.w;
    const glm::ivec2 pixel(static_cast<int>(glm::floor(p.x)), static_cast<int>(glm::floor(p.y)));
    if (pixel.x >= 0 && pixel.y >= 0 && pixel.x < width && pixel.y < height &&
        depth(pixel.x, pixel.y) >= 1.0f) {
      ++visible;
    }
  }
  return static_cast<float>(visible) / static_cast<float>(kFlareSamples);
}

} // namespace sylva::render
