#version 450
// Resolves one baked view of an impostor (docs/trees.md "Far field"): from the view's colour (the tree drawn
// with no sun and no fog: albedo times the sky light of its normal) and depth, per texel: coverage, the
// object-space normal from the depth's gradients, the albedo (colour over the sky light of that normal, as
// shadeOutdoor computes it) and the depth relative to the bounding sphere; premultiplied by coverage so mip
// levels average correctly.
#include "../shared/Trees.h"
#include "../common/frame.glsl"
#include "../common/lighting.glsl"

layout(local_size_x = SYLVA_TREE_IMPOSTOR_RESOLVE_GROUP, local_size_y = SYLVA_TREE_IMPOSTOR_RESOLVE_GROUP) in;

layout(binding = SYLVA_TREE_IMPOSTOR_SOURCE_UNIT) uniform sampler2D sourceColour;
layout(binding = SYLVA_TREE_IMPOSTOR_SOURCE_UNIT + 1) uniform sampler2D sourceDepth;
layout(rgba8, binding = 0) uniform writeonly image2D outColour;
layout(rgba8, binding = 1) uniform writeonly image2D outNormal;

uniform mat4 uInverseProjection;
uniform mat3 uBasis;       // columns: right, up, forward (object space) of the view
uniform float uDistance;   // camera to sphere centre (m)
uniform float uRadius;     // bounding radius (m)
uniform vec3 uCentre;      // sphere centre (object space = the bake's world)

int gSize = 0;

bool covered(ivec2 p) {
  return all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, ivec2(gSize))) &&
         texelFetch(sourceDepth, p, 0).r < 1.0;
}

vec3 viewPoint(ivec2 p) {
  float d = texelFetch(sourceDepth, p, 0).r;
  vec4 ndc = vec4((vec2(p) + 0.5) / float(gSize) * 2.0 - 1.0, d * 2.0 - 1.0, 1.0);
  vec4 v = uInverseProjection * ndc;
  return v.xyz / v.w;
}

/** The neighbour step along `axis` whose depth is closest (both sides when possible), as a difference. */
bool gradient(ivec2 p, ivec2 axis, vec3 centre, out vec3 g) {
  bool a = covered(p + axis);
  bool b = covered(p - axis);
  if (!a && !b) {
    return false;
  }
  vec3 pa = a ? viewPoint(p + axis) : vec3(0.0);
  vec3 pb = b ? viewPoint(p - axis) : vec3(0.0);
  if (a && (!b || abs(pa.z - centre.z) <= abs(pb.z - centre.z))) {
    g = pa - centre;
  } else {
    g = centre - pb;
  }
  return true;
}

void main() {
  gSize = textureSize(sourceDepth, 0).x;
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(gSize)))) {
    return;
  }
  if (!covered(p)) {
    imageStore(outColour, p, vec4(0.0));
    imageStore(outNormal, p, vec4(0.0));
    return;
  }
  vec3 c = viewPoint(p);
  vec3 gx;
  vec3 gy;
  vec3 n = vec3(0.0, 0.0, 1.0);
  if (gradient(p, ivec2(1, 0), c, gx) && gradient(p, ivec2(0, 1), c, gy)) {
    vec3 m = cross(gx, gy);
    if (dot(m, m) > 0.0) {
      n = normalize(m);
      n = n.z < 0.0 ? -n : n;
    }
  }
  vec3 nObject = normalize(uBasis * n);
  // The bake is drawn with sun intensity 0 and no fog: colour = albedo · sky light(n). The same function
  // with albedo 1 gives the sky light, whatever lighting.glsl's constants are.
  vec3 world = uCentre + uBasis * vec3(c.xy, c.z + uDistance);
  vec3 sky = shadeOutdoor(vec3(1.0), nObject, world);
  vec3 srgb = texelFetch(sourceColour, p, 0).rgb;
  vec3 linear = mix(srgb / 12.92, pow((srgb + 0.055) / 1.055, vec3(2.4)), step(0.04045, srgb));
  vec3 albedo = clamp(linear / max(sky, vec3(1e-3)), 0.0, 1.0);
  float offset = clamp((c.z + uDistance) / uRadius, -1.0, 1.0); // towards the viewer
  vec3 encoded = mix(12.92 * albedo, 1.055 * pow(albedo, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, albedo));
  imageStore(outColour, p, vec4(encoded, 1.0));
  imageStore(outNormal, p, vec4(nObject * 0.5 + 0.5, 0.5 + 0.5 * offset));
}
