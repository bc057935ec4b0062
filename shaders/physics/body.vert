#version 450
// A unit sphere generated from gl_VertexID (uAround × uRings quads, two triangles each), placed by the body's
// model matrix (translation, rotation, radius).
#include "../common/frame.glsl"

layout(std430, binding = 0) readonly buffer Bodies {
  mat4 models[];
};

uniform int uAround;
uniform int uRings;

out vec3 vWorld;
out vec3 vNormal;
out vec2 vUv;

void main() {
  int quad = gl_VertexID / 6;
  int corner = gl_VertexID % 6;
  // Corners of the quad's two triangles: (0,0) (1,0) (1,1), (0,0) (1,1) (0,1).
  ivec2 offsets[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
  ivec2 cell = ivec2(quad % uAround, quad / uAround) + offsets[corner];
  vec2 uv = vec2(cell) / vec2(uAround, uRings);
  float theta = uv.x * 6.28318530718;
  float phi = uv.y * 3.14159265359;
  vec3 local = vec3(sin(phi) * cos(theta), cos(phi), sin(phi) * sin(theta));
  mat4 model = models[gl_InstanceID];
  vec4 world = model * vec4(local, 1.0);
  vWorld = world.xyz;
  vNormal = normalize(mat3(model) * local);
  vUv = uv;
  gl_Position = frame.viewProj * world;
}
