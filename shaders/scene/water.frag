#version 450 core
// The shore pass's water (docs/scenes.md "Water with a folding-textured shore"; CPU twin: engine/scene/src/Shore.cpp). Under water: colour and
// opacity from the true depth, Schlick Fresnel towards the sky colour and a sun glint, like the terrain's still
// water. In the shore band (1 at the waterline, fading over uBand metres of depth and uWet metres above the
// water) the animated folding frame (uSwash) is laid over it with its advance direction up the slope: where the
// frame shows water or foam it is drawn, where it shows sand the ground is darkened as wet sand. Drawn after the
// terrain with alpha blending, depth test on and no depth writes. uView 1 writes the band weight (debug, opaque).
layout(early_fragment_tests) in;
#include "../common/lighting.glsl"

layout(binding = 0) uniform sampler2D uHeights; // R32F world heights, absent samples = 1e20 (always dry)
layout(binding = 1) uniform sampler2D uSwash;   // the folding frame, RGBA8 (sRGB values), row 0 at t = 1
uniform ivec2 uField;          // samples
uniform vec2 uSpacing;         // metres per sample
uniform float uLevel;          // world metres
uniform float uVerticalScale;  // world metres per true metre
uniform float uBand;           // true metres of depth
uniform float uWet;            // true metres above the water
uniform float uTile;           // metres per frame width
uniform float uAspect;         // frame height / width
uniform float uWaterline;      // frame v of the resting water edge
uniform int uView;             // 0 shaded, 1 band weight
in vec3 vWorldPos;
layout(location = 0) out vec4 outColor;

const float kMinShoreSlope = 0.02; // Shore.hpp
const int kSwashDirections = 8;
const float kDepthScale = 12.0;    // true metres over which shallow water turns deep (terrain water)

float heightSample(ivec2 i) {
  return texelFetch(uHeights, i, 0).r;
}

// heightAt (Bilinear), world metres.
float heightAt(vec2 xz) {
  vec2 g = clamp(xz / uSpacing, vec2(0.0), vec2(uField - 1));
  ivec2 i0 = min(ivec2(floor(g)), uField - 2);
  vec2 f = g - vec2(i0);
  float h00 = heightSample(i0);
  float h10 = heightSample(i0 + ivec2(1, 0));
  float h01 = heightSample(i0 + ivec2(0, 1));
  float h11 = heightSample(i0 + ivec2(1, 1));
  return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

// shoreGradient: true slope vector, central differences over ± half a sample, clamped to the footprint.
vec2 shoreGradient(vec2 xz) {
  vec2 extent = vec2(uField - 1) * uSpacing;
  vec2 lo = clamp(xz - 0.5 * uSpacing, vec2(0.0), extent);
  vec2 hi = clamp(xz + 0.5 * uSpacing, vec2(0.0), extent);
  vec2 d = vec2(0.0);
  if (hi.x > lo.x) {
    d.x = (heightAt(vec2(hi.x, xz.y)) - heightAt(vec2(lo.x, xz.y))) / (hi.x - lo.x);
  }
  if (hi.y > lo.y) {
    d.y = (heightAt(vec2(xz.x, hi.y)) - heightAt(vec2(xz.x, lo.y))) / (hi.y - lo.y);
  }
  return abs(d.x) < 1e10 && abs(d.y) < 1e10 ? d / uVerticalScale : vec2(0.0);
}

float shoreBand(float depth) {
  return depth >= 0.0 ? 1.0 - smoothstep(0.0, uBand, depth) : 1.0 - smoothstep(0.0, uWet, -depth);
}

vec3 fromSrgb(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c));
}

void main() {
  vec2 xz = vWorldPos.xz;
  float depth = (uLevel - heightAt(xz)) / uVerticalScale;
  float band = shoreBand(depth);

  // swashCoords: rows along the depth contours, u along one of 8 fixed axes around the uphill direction.
  vec2 grad = shoreGradient(xz);
  float slope = max(length(grad), kMinShoreSlope);
  float v = uWaterline + (-depth / slope) / (uTile * uAspect);
  float arc = 6.28318530718 / float(kSwashDirections);
  float angle = dot(grad, grad) > 0.0 ? atan(grad.y, grad.x) : 0.0;
  float sector = angle / arc;
  float k0 = floor(sector);
  float blend = smoothstep(0.3, 0.7, sector - k0);
  float a0 = k0 * arc;
  float a1 = a0 + arc;
  float row = 1.0 - clamp(v, 0.0, 1.0); // texture t: row 0 at the top
  vec2 t0 = vec2(sin(a0), -cos(a0));
  vec2 t1 = vec2(sin(a1), -cos(a1));
  vec2 uv0 = vec2(dot(xz, t0) / uTile, row);
  vec2 uv1 = vec2(dot(xz, t1) / uTile, row);
  // Texture gradients from the screen derivatives of xz and the row, taken before any discard: which direction
  // is uv0 changes between neighbouring pixels at a sector end, so dFdx(uv0) would be meaningless there.
  vec2 dxz = dFdx(xz), dyz = dFdy(xz);
  float dxRow = dFdx(row), dyRow = dFdy(row);
  vec2 dx0 = vec2(dot(dxz, t0) / uTile, dxRow), dy0 = vec2(dot(dyz, t0) / uTile, dyRow);
  vec2 dx1 = vec2(dot(dxz, t1) / uTile, dxRow), dy1 = vec2(dot(dyz, t1) / uTile, dyRow);

  if (!(depth > -uWet)) {
    discard; // dry ground beyond the wet strip (or absent samples)
  }
  if (uView == 1) {
    outColor = vec4(band, band, band, 1.0);
    return;
  }

  // The water body (none above the waterline).
  vec3 toEye = normalize(frame.cameraPos.xyz - vWorldPos);
  vec3 sun = normalize(frame.sunDirection.xyz);
  vec3 rgbW = vec3(0.0);
  float aW = 0.0;
  if (depth > 0.0) {
    float deep = 1.0 - exp(-depth / kDepthScale);
    vec3 water = mix(vec3(0.05, 0.30, 0.36), vec3(0.005, 0.04, 0.12), deep);
    float cosView = clamp(toEye.y, 0.0, 1.0);
    float fresnel = 0.02 + 0.6 * pow(1.0 - cosView, 5.0);
    vec3 sky = mix(frame.fogColor.rgb, vec3(0.25, 0.42, 0.72), 0.5);
    float glint = pow(max(dot(reflect(-toEye, vec3(0.0, 1.0, 0.0)), sun), 0.0), 400.0) * frame.sunDirection.w;
    rgbW = applyAtmosphere(mix(water * (0.35 + 0.65 * max(sun.y, 0.0)), sky, fresnel) + vec3(glint), vWorldPos);
    aW = clamp(mix(0.55, 0.97, deep) + fresnel, 0.0, 1.0);
  }

  // The swash layer: the frame's water and foam drawn, its sand turned into a darkening of the ground.
  vec4 raw = mix(textureGrad(uSwash, uv0, dx0, dy0), textureGrad(uSwash, uv1, dx1, dy1), blend);
  float waterish = smoothstep(-0.1, 0.05, raw.b - raw.r);
  float wetSand = clamp(1.0 - dot(raw.rgb, vec3(0.2126, 0.7152, 0.0722)) / 0.75, 0.0, 1.0);
  vec3 rgbS = shadeOutdoor(fromSrgb(raw.rgb) * waterish, vec3(0.0, 1.0, 0.0), vWorldPos);
  float aS = band * mix(0.35 * wetSand, 0.95, waterish) * smoothstep(0.05, 0.4, v);

  float a = aS + aW * (1.0 - aS);
  vec3 rgb = (rgbS * aS + rgbW * aW * (1.0 - aS)) / max(a, 1e-6);
  outColor = vec4(toSrgb(rgb), a);
}
