// The analytic daylight sky of Preetham, Shirley and Smits (1999) with the sun's disc and the light the haze
// scatters towards the camera. Twin of engine/render/src/Sky.cpp (same operations, same order): see
// render::skyRadiance, sunDisc, skyInscatter. Radiance is linear sRGB in the engine's lit-colour scale.
#pragma once
#include "frame.glsl"

const float kSkyPi = 3.14159265358979;
const vec3 kSkyCalibration = vec3(0.0562762, 0.0776169, 0.0857261); // kcd/m² → engine radiance, per channel
const float kSkyMieG = 0.76;
const float kSkyMieStrength = 0.05;
const vec3 kSkySunColour = vec3(1.0, 0.96, 0.88);
const float kSunAngularRadius = 0.01;  // radians
const float kSunDiscRadiance = 40.0;

/** `d` itself above the horizon; below it, the horizon direction of the same azimuth. */
vec3 skyAboveHorizon(vec3 d) {
  if (d.y >= 0.0) {
    return d;
  }
  float h = sqrt(d.x * d.x + d.z * d.z);
  return h > 1e-6 ? vec3(d.x / h, 0.0, d.z / h) : vec3(1.0, 0.0, 0.0);
}

/** Highlight roll-off: above 1, keep the hue and fade towards white (render::skyHighlight). */
vec3 skyHighlight(vec3 c) {
  float m = max(c.r, max(c.g, c.b));
  if (m <= 1.0) {
    return c;
  }
  vec3 hue = c / m;
  return hue + (1.0 - hue) * (1.0 - 1.0 / m);
}

float perezDistribution(float A, float B, float C, float D, float E, float cosTheta, float gamma,
                        float cosGamma) {
  float ct = max(cosTheta, 0.001);
  return (1.0 + A * exp(B / ct)) * (1.0 + C * exp(D * gamma) + E * cosGamma * cosGamma);
}

/** Perez ratio F(θ, γ) / F(0, θs) for one of Y, x, y: coefficients (A, B, C, D) + E. */
float perezRatio(vec4 abcd, float e, float cosTheta, float gamma, float cosGamma, float thetaS,
                 float cosThetaS) {
  return perezDistribution(abcd.x, abcd.y, abcd.z, abcd.w, e, cosTheta, gamma, cosGamma) /
         perezDistribution(abcd.x, abcd.y, abcd.z, abcd.w, e, 1.0, thetaS, cosThetaS);
}

/** Sky radiance along unit world direction `viewDir` with the sun towards unit `sunDir`; no sun disc. */
vec3 skyRadiance(vec3 viewDir, vec3 sunDir, float turbidityIn, float exposure) {
  vec3 v = skyAboveHorizon(viewDir);
  vec3 s = skyAboveHorizon(sunDir);
  float t = clamp(turbidityIn, 1.7, 10.0);
  float thetaS = acos(clamp(s.y, 0.0, 1.0));
  float cosGamma = clamp(dot(v, s), -1.0, 1.0);
  float gamma = acos(cosGamma);

  float chi = (4.0 / 9.0 - t / 120.0) * (kSkyPi - 2.0 * thetaS);
  float zenithY = (4.0453 * t - 4.9710) * tan(chi) - 0.2155 * t + 2.4192;
  float t2 = thetaS * thetaS;
  float t3 = t2 * thetaS;
  float tt = t * t;
  float zenithX = tt * (0.00166 * t3 - 0.00375 * t2 + 0.00209 * thetaS) +
                  t * (-0.02903 * t3 + 0.06377 * t2 - 0.03202 * thetaS + 0.00394) +
                  (0.11693 * t3 - 0.21196 * t2 + 0.06052 * thetaS + 0.25886);
  float zenithYc = tt * (0.00275 * t3 - 0.00610 * t2 + 0.00317 * thetaS) +
                   t * (-0.04214 * t3 + 0.08970 * t2 - 0.04153 * thetaS + 0.00516) +
                   (0.15346 * t3 - 0.26756 * t2 + 0.06670 * thetaS + 0.26688);

  vec4 cY = vec4(0.1787 * t - 1.4630, -0.3554 * t + 0.4275, -0.0227 * t + 5.3251, 0.1206 * t - 2.5771);
  float eY = -0.0670 * t + 0.3703;
  vec4 cx = vec4(-0.0193 * t - 0.2592, -0.0665 * t + 0.0008, -0.0004 * t + 0.2125, -0.0641 * t - 0.8989);
  float ex = -0.0033 * t + 0.0452;
  vec4 cy = vec4(-0.0167 * t - 0.2608, -0.0950 * t + 0.0092, -0.0079 * t + 0.2102, -0.0441 * t - 1.6537);
  float ey = -0.0109 * t + 0.0529;

  float luminance = zenithY * perezRatio(cY, eY, v.y, gamma, cosGamma, thetaS, s.y);
  float x = zenithX * perezRatio(cx, ex, v.y, gamma, cosGamma, thetaS, s.y);
  float y = zenithYc * perezRatio(cy, ey, v.y, gamma, cosGamma, thetaS, s.y);

  float X = x / y * luminance;
  float Z = (1.0 - x - y) / y * luminance;
  vec3 rgb = vec3(3.2406 * X - 1.5372 * luminance - 0.4986 * Z, -0.9689 * X + 1.8758 * luminance + 0.0415 * Z,
                  0.0557 * X - 0.2040 * luminance + 1.0570 * Z);
  return max(rgb * kSkyCalibration * exposure, vec3(0.0));
}

/** The sun's disc along `viewDir` (soft over its outer fifth); zero away from it. */
vec3 sunDisc(vec3 viewDir, vec3 sunDir, float sunIntensity, float exposure) {
  if (dot(viewDir, sunDir) <= 0.0) {
    return vec3(0.0);
  }
  float angle = length(cross(viewDir, sunDir));
  float inside = 1.0 - smoothstep(0.8 * kSunAngularRadius, kSunAngularRadius, angle);
  return kSkySunColour * (kSunDiscRadiance * sunIntensity * exposure * inside);
}

float henyeyGreenstein(float cosAngle, float g) {
  float denominator = 1.0 + g * g - 2.0 * g * cosAngle;
  return (1.0 - g * g) / (4.0 * kSkyPi * denominator * sqrt(denominator));
}

/** Light scattered towards the camera along `viewDir`: the sky there plus the sun-forward Mie glow. */
vec3 skyInscatter(vec3 viewDir, vec3 sunDir, float turbidity, float exposure, float sunIntensity) {
  float glow = kSkyMieStrength * sunIntensity * exposure * henyeyGreenstein(dot(viewDir, sunDir), kSkyMieG);
  return skyHighlight(skyRadiance(viewDir, sunDir, turbidity, exposure) + kSkySunColour * glow);
}

/** The frame's sky as shown (frame.atmosphere.y turbidity, .z exposure; highlight roll-off) along unit
 * `viewDir`, without the sun disc. */
vec3 frameSkyRadiance(vec3 viewDir) {
  vec3 sun = normalize(frame.sunDirection.xyz);
  return skyHighlight(skyRadiance(viewDir, sun, frame.atmosphere.y, frame.atmosphere.z));
}
