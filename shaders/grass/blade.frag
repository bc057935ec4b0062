#version 450
// Blade shading: Phong (diffuse + specular) with translucency for light passing through the thin blade from
// behind (after Sousa, GPU Gems 3 ch. 16), root ambient occlusion, per-blade colour; dithered cross-fades
// between levels of detail and into the ground tint far away (docs/grass.md).
#include "grass.glsl"
#include "../common/lighting.glsl"

in vec3 vWorld;
in vec3 vNormal;
in float vAlong;
in float vSide;
flat in vec3 vColour;
flat in uint vInfo;
flat in uvec2 vTile;
flat in float vSimulated;
in float vFlatten;

layout(location = 0) out vec4 outColor;

void main() {
  uint fade = (vInfo >> 24) & 3u;
  if (fade != 0u) {
    // The same threshold for both instances of a cross-fading blade (keyed by its patch index), so the
    // outgoing and incoming levels cover each pixel exactly once.
    uvec2 p = uvec2(gl_FragCoord.xy);
    float t = float(lowbias32(p.x * 1973u ^ p.y * 9277u ^ (vInfo & SYLVA_GRASS_INDEX_MASK) * 26699u) & 0xffffu) / 65536.0;
    float amount = float(vInfo >> 26) / 63.0;
    if (fade == 1u ? t < amount : t >= amount) {
      discard;
    }
  }
  uint view = grass.options.y;
  if (view == 1u) {
    int lod = int((vInfo >> 22) & 3u);
    vec3 c = lod == 0 ? vec3(0.9, 0.2, 0.15) : lod == 1 ? vec3(0.2, 0.85, 0.25) : vec3(0.2, 0.35, 0.95);
    outColor = vec4(toSrgb(c * (0.5 + 0.5 * vAlong)), 1.0);
    return;
  }
  if (view == 2u) {
    uint h = lowbias32(vTile.x * 7919u + vTile.y * 104729u);
    vec3 c = vec3(float(h & 0xffu), float((h >> 8) & 0xffu), float((h >> 16) & 0xffu)) / 255.0;
    // Simulated tiles in white, turning back to their colour over the release ramp.
    c = vSimulated >= 0.0 ? mix(vec3(1.0), c, vSimulated) : c * 0.6;
    outColor = vec4(toSrgb(c * (0.4 + 0.6 * vAlong)), 1.0);
    return;
  }
  vec3 toEye = frame.cameraPos.xyz - vWorld;
  vec3 V = normalize(toEye);
  vec3 N = normalize(vNormal);
  N = dot(N, V) < 0.0 ? -N : N;
  // Blades in a field catch light like the canopy they form: their normals lean towards the sky, more so near
  // the tip, which keeps a sunlit field bright instead of a mass of dark edge-on strips.
  vec3 Nlit = normalize(mix(N, vec3(0.0, 1.0, 0.0), 0.35 + 0.25 * vAlong));
  vec3 L = normalize(frame.sunDirection.xyz);
  float sun = frame.sunDirection.w * sunVisibility(vWorld, N);
  // Darker, greener base; lighter tips.
  vec3 albedo = vColour * mix(0.7, 1.12, vAlong);
  float diffuse = max(dot(Nlit, L), 0.0);
  vec3 H = normalize(L + V);
  float specular = 0.1 * pow(max(dot(Nlit, H), 0.0), 24.0);
  // A trampled blade lies on top of the sward: its whole length sees the sky (no root occlusion), its paler
  // lower part and underside show, and its waxy face gives a broad sheen, so a path reads lighter.
  float flat_ = smoothstep(0.0, 0.5, vFlatten);
  albedo = mix(albedo, vColour * vec3(1.3, 1.3, 1.0), 0.75 * flat_);
  specular += flat_ * 0.18 * pow(max(dot(normalize(mix(N, vec3(0.0, 1.0, 0.0), 0.5)), H), 0.0), 6.0);
  // Translucency: light through the blade when the sun is behind it, strongest looking towards the sun;
  // thinner (brighter) towards the tip.
  float through = max(dot(-N, L), 0.0);
  float towards = pow(max(dot(-V, L), 0.0), 4.0);
  vec3 translucent = vColour * vec3(1.15, 1.3, 0.55) * (0.45 * through + 0.5 * towards) * (0.35 + 0.65 * vAlong);
  float sky = 0.5 + 0.5 * Nlit.y;
  vec3 ambient = mix(vec3(0.18, 0.16, 0.14), vec3(0.32, 0.38, 0.48), sky);
  // Root occlusion: the field shades its own lower parts.
  float occlusion = mix(mix(0.3, 1.0, smoothstep(0.0, 0.55, vAlong)), 0.9, flat_);
  vec3 lit = (albedo * (diffuse * sun * vec3(1.0, 0.96, 0.88) + ambient) + (translucent + specular) * sun) * occlusion;
  outColor = vec4(toSrgb(applyAtmosphere(lit, vWorld)), 1.0);
}
