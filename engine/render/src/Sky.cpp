#include <sylva/render/Sky.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {

namespace {

constexpr float kPi = 3.14159265358979f;

float smoothStep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

/** `d` itself above the horizon; below it, the horizon direction of the same azimuth. */
glm::vec3 aboveHorizon(const glm::vec3& d) {
  if (d.y >= 0.0f) {
    return d;
  }
  const float h = std::sqrt(d.x * d.x + d.z * d.z);
  return h > 1e-6f ? glm::vec3(d.x / h, 0.0f, d.z / h) : glm::vec3(1.0f, 0.0f, 0.0f);
}

} // namespace

glm::vec3 skyHighlight(const glm::vec3& c) {
  const float m = std::max(c.r, std::max(c.g, c.b));
  if (m <= 1.0f) {
    return c;
  }
  const glm::vec3 hue = c / m;
  return hue + (1.0f - hue) * (1.0f - 1.0f / m);
}

SkyParams skyParamsFrom(const Environment& environment) {
  SkyParams params;
  params.turbidity = environment.turbidity;
  params.exposure = environment.exposure;
  params.hazeDensity = environment.fogDensity;
  params.sunIntensity = environment.sunIntensity;
  return params;
}

float perezDistribution(const std::array<float, 5>& c, float cosTheta, float gamma, float cosGamma) {
  const float ct = std::max(cosTheta, 0.001f);
  return (1.0f + c[0] * std::exp(c[1] / ct)) *
         (1.0f + c[2] * std::exp(c[3] * gamma) + c[4] * cosGamma * cosGamma);
}

PerezCoefficients perezCoefficients(float t) {
  PerezCoefficients c;
  c.Y = {0.1787f * t - 1.4630f, -0.3554f * t + 0.4275f, -0.0227f * t + 5.3251f, 0.1206f * t - 2.5771f,
         -0.0670f * t + 0.3703f};
  c.x = {-0.0193f * t - 0.2592f, -0.0665f * t + 0.0008f, -0.0004f * t + 0.2125f, -0.0641f * t - 0.8989f,
         -0.0033f * t + 0.0452f};
  c.y = {-0.0167f * t - 0.2608f, -0.0950f * t + 0.0092f, -0.0079f * t + 0.2102f, -0.0441f * t - 1.6537f,
         -0.0109f * t + 0.0529f};
  return c;
}

glm::vec3 zenithLuminanceChromaticity(float t, float thetaS) {
  const float chi = (4.0f / 9.0f - t / 120.0f) * (kPi - 2.0f * thetaS);
  const float luminance = (4.0453f * t - 4.9710f) * std::tan(chi) - 0.2155f * t + 2.4192f;
  const float t2 = thetaS * thetaS;
  const float t3 = t2 * thetaS;
  const float tt = t * t;
  const float x = tt * (0.00166f * t3 - 0.00375f * t2 + 0.00209f * thetaS) +
                  t * (-0.02903f * t3 + 0.06377f * t2 - 0.03202f * thetaS + 0.00394f) +
                  (0.11693f * t3 - 0.21196f * t2 + 0.06052f * thetaS + 0.25886f);
  const float y = tt * (0.00275f * t3 - 0.00610f * t2 + 0.00317f * thetaS) +
                  t * (-0.04214f * t3 + 0.08970f * t2 - 0.04153f * thetaS + 0.00516f) +
                  (0.15346f * t3 - 0.26756f * t2 + 0.06670f * thetaS + 0.26688f);
  return {luminance, x, y};
}

glm::vec3 xyYToLinearSrgb(float x, float y, float luminance) {
  const float X = x / y * luminance;
  const float Z = (1.0f - x - y) / y * luminance;
  return {3.2406f * X - 1.5372f * luminance - 0.4986f * Z, -0.9689f * X + 1.8758f * luminance + 0.0415f * Z,
          0.0557f * X - 0.2040f * luminance + 1.0570f * Z};
}

glm::vec3 skyRadiance(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params) {
  const glm::vec3 v = aboveHorizon(viewDir);
  const glm::vec3 s = aboveHorizon(sunDir);
  const float turbidity = std::clamp(params.turbidity, 1.7f, 10.0f);
  const float thetaS = std::acos(std::clamp(s.y, 0.0f, 1.0f));
  const float cosGamma = std::clamp(glm::dot(v, s), -1.0f, 1.0f);
  const float gamma = std::acos(cosGamma);
  const PerezCoefficients c = perezCoefficients(turbidity);
  const glm::vec3 zenith = zenithLuminanceChromaticity(turbidity, thetaS);
  const float luminance =
      zenith.x * perezDistribution(c.Y, v.y, gamma, cosGamma) / perezDistribution(c.Y, 1.0f, thetaS, s.y);
  const float x =
      zenith.y * perezDistribution(c.x, v.y, gamma, cosGamma) / perezDistribution(c.x, 1.0f, thetaS, s.y);
  const float y =
      zenith.z * perezDistribution(c.y, v.y, gamma, cosGamma) / perezDistribution(c.y, 1.0f, thetaS, s.y);
  const glm::vec3 rgb = xyYToLinearSrgb(x, y, luminance) * kSkyCalibration * params.exposure;
  return glm::max(rgb, glm::vec3(0.0f));
}

namespace {

/** Preetham's Y (kcd/m²) averaged over 64 horizon azimuths. */
float meanHorizonLuminance(const glm::vec3& sunDir, float turbidity) {
  const glm::vec3 s = aboveHorizon(sunDir);
  const float t = std::clamp(turbidity, 1.7f, 10.0f);
  const float thetaS = std::acos(std::clamp(s.y, 0.0f, 1.0f));
  const PerezCoefficients c = perezCoefficients(t);
  const float zenith = zenithLuminanceChromaticity(t, thetaS).x;
  const float reference = perezDistribution(c.Y, 1.0f, thetaS, s.y);
  float sum = 0.0f;
  const int n = 64;
  for (int i = 0; i < n; ++i) {
    const float azimuth = 2.0f * kPi * (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
    const glm::vec3 v(std::cos(azimuth), 0.0f, std::sin(azimuth));
    const float cosGamma = std::clamp(glm::dot(v, s), -1.0f, 1.0f);
    sum += zenith * perezDistribution(c.Y, 0.0f, std::acos(cosGamma), cosGamma) / reference;
  }
  return sum / static_cast<float>(n);
}

} // namespace

float skyAutoExposure(const glm::vec3& sunDir, float turbidity) {
  const float e = 40.0f * kPi / 180.0f;
  static const float reference = meanHorizonLuminance(glm::vec3(std::cos(e), std::sin(e), 0.0f), 3.0f);
  return reference / meanHorizonLuminance(sunDir, turbidity);
}

glm::vec3 sunDisc(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params) {
  if (glm::dot(viewDir, sunDir) <= 0.0f) {
    return glm::vec3(0.0f);
  }
  const float angle = glm::length(glm::cross(viewDir, sunDir));
  const float inside = 1.0f - smoothStep(0.8f * kSunAngularRadius, kSunAngularRadius, angle);
  return kSunColour * (kSunDiscRadiance * params.sunIntensity * params.exposure * inside);
}

glm::vec3 skyWithSun(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params) {
  return skyHighlight(skyRadiance(viewDir, sunDir, params)) + sunDisc(viewDir, sunDir, params);
}

float henyeyGreenstein(float cosAngle, float g) {
  const float denominator = 1.0f + g * g - 2.0f * g * cosAngle;
  return (1.0f - g * g) / (4.0f * kPi * denominator * std::sqrt(denominator));
}

glm::vec3 skyInscatter(const glm::vec3& viewDir, const glm::vec3& sunDir, const SkyParams& params) {
  const float glow = kSkyMieStrength * params.sunIntensity * params.exposure *
                     henyeyGreenstein(glm::dot(viewDir, sunDir), kSkyMieG);
  return skyHighlight(skyRadiance(viewDir, sunDir, params) + kSunColour * glow);
}

glm::vec3 aerial(const glm::vec3& lit, const glm::vec3& viewDir, float distance, const glm::vec3& sunDir,
                 const SkyParams& params) {
  const float transmittance = std::exp(-params.hazeDensity * distance);
  return lit * transmittance + skyInscatter(viewDir, sunDir, params) * (1.0f - transmittance);
}

glm::vec3 skyViewDirection(const glm::mat4& viewProj, const glm::mat4& view, const glm::vec2& ndc) {
  // Rows 0 and 1 of P · V are P00 and P11 times unit rows of the view rotation (symmetric frustum).
  const float p00 = glm::length(glm::vec3(viewProj[0][0], viewProj[1][0], viewProj[2][0]));
  const float p11 = glm::length(glm::vec3(viewProj[0][1], viewProj[1][1], viewProj[2][1]));
  const glm::vec3 inView(ndc.x / p00, ndc.y / p11, -1.0f);
  return glm::normalize(glm::transpose(glm::mat3(view)) * inView);
}

const std::array<FlareGhostDesc, kFlareGhostCount>& flareGhostTable() {
  // Keep in step with kGhosts in shaders/render/flare.vert.
  static const std::array<FlareGhostDesc, kFlareGhostCount> table{{
      {0.0f, 0.30f, {0.32f, 0.27f, 0.20f}, 1},
      {0.30f, 0.045f, {0.22f, 0.14f, 0.07f}, 0},
      {0.55f, 0.09f, {0.08f, 0.16f, 0.10f}, 0},
      {0.80f, 0.03f, {0.14f, 0.17f, 0.28f}, 0},
      {1.10f, 0.14f, {0.06f, 0.05f, 0.12f}, 0},
      {1.35f, 0.06f, {0.20f, 0.09f, 0.07f}, 0},
      {1.65f, 0.10f, {0.07f, 0.12f, 0.16f}, 0},
      {2.00f, 0.20f, {0.05f, 0.08f, 0.10f}, 0},
  }};
  return table;
}

std::vector<FlareGhost> flareGhosts(const glm::vec2& sunNdc) {
  std::vector<FlareGhost> ghosts;
  for (const FlareGhostDesc& g : flareGhostTable()) {
    ghosts.push_back({sunNdc * (1.0f - g.t), g.radius, g.colour, g.halo});
  }
  return ghosts;
}

float flareSpriteProfile(float r, int halo) {
  if (r >= 1.0f) {
    return 0.0f;
  }
  if (halo != 0) {
    return (1.0f - r) * (1.0f - r);
  }
  return (1.0f - smoothStep(0.8f, 1.0f, r)) * (0.4f + 0.6f * r * r);
}

glm::vec2 flareSampleOffset(int index) {
  const float r = std::sqrt((static_cast<float>(index) + 0.5f) / static_cast<float>(kFlareSamples));
  const float angle = static_cast<float>(index) * 2.39996323f;
  return {r * std::cos(angle), r * std::sin(angle)};
}

glm::vec4 sunScreenPosition(const glm::mat4& viewProj, const glm::vec3& sunDir, int width, int height,
                            float minRadiusPixels) {
  const glm::vec4 clip = viewProj * glm::vec4(sunDir, 0.0f);
  const float p11 = glm::length(glm::vec3(viewProj[0][1], viewProj[1][1], viewProj[2][1]));
  const float radius = std::max(p11 * kSunAngularRadius * 0.5f * static_cast<float>(height), minRadiusPixels);
  if (clip.w <= 0.0f) {
    return {0.0f, 0.0f, 0.0f, radius};
  }
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const glm::vec2 pixel =
      (ndc * 0.5f + 0.5f) * glm::vec2(static_cast<float>(width), static_cast<float>(height));
  return {pixel, 1.0f, radius};
}

} // namespace sylva::render
