#include <sylva/render/Shadows.hpp>

#include <sylva/core/Error.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sylva::render {

std::vector<float> cascadeSplits(float nearDepth, float farDepth, int n, float lambda) {
  if (!(nearDepth > 0.0f) || !(farDepth > nearDepth)) {
    fail("shadows: cascade range needs 0 < near < far (got near {:g}, far {:g})", nearDepth, farDepth);
  }
  if (n < 1) {
    fail("shadows: cascades must be at least 1 (got {})", n);
  }
  if (!(lambda >= 0.0f && lambda <= 1.0f)) {
    fail("shadows: lambda must be in [0, 1] (got {:g})", lambda);
  }
  std::vector<float> splits(static_cast<std::size_t>(n) + 1);
  const double ratio = static_cast<double>(farDepth) / static_cast<double>(nearDepth);
  for (int i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n);
    const double logarithmic = nearDepth * std::pow(ratio, t);
    const double uniform = nearDepth + (static_cast<double>(farDepth) - nearDepth) * t;
    splits[static_cast<std::size_t>(i)] = static_cast<float>(lambda * logarithmic + (1.0 - lambda) * uniform);
  }
  splits.front() = nearDepth;
  splits.back() = farDepth;
  return splits;
}

glm::vec2 sliceSphere(float nearDepth, float farDepth, float fovY, float aspect) {
  const double tanY = std::tan(0.5 * static_cast<double>(fovY));
  const double tanX = tanY * static_cast<double>(aspect);
  const double k2 = tanX * tanX + tanY * tanY; // squared lateral reach of a corner per metre of depth
  const double d0 = nearDepth;
  const double d1 = farDepth;
  // Centre t on the axis equidistant from the near and far corners: (t − d0)² + k²d0² = (d1 − t)² + k²d1².
  double t = 0.5 * (d0 + d1) * (1.0 + k2);
  if (t >= d1) {
    // Wide slices: the far corners' circle is the binding one.
    t = d1;
    return {static_cast<float>(t), static_cast<float>(std::sqrt(k2) * d1)};
  }
  const double r = std::sqrt((t - d0) * (t - d0) + k2 * d0 * d0);
  return {static_cast<float>(t), static_cast<float>(r)};
}

namespace {

/** Orthonormal sun basis: right, up, back (towards the sun); depends on the sun direction only. */
struct SunBasis {
  glm::vec3 right;
  glm::vec3 up;
  glm::vec3 back;
};

SunBasis sunBasis(const glm::vec3& sunDirection) {
  const float len = glm::length(sunDirection);
  if (!(len > 0.0f) || !std::isfinite(len)) {
    fail("shadows: sun direction must be a finite non-zero vector");
  }
  SunBasis b;
  b.back = sunDirection / len;
  const glm::vec3 forward = -b.back;
  const glm::vec3 reference = std::abs(forward.y) > 0.99f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0, 1, 0);
  b.right = glm::normalize(glm::cross(forward, reference));
  b.up = glm::cross(b.right, forward);
  return b;
}

std::array<glm::vec3, 8> boxCorners(const Aabb& box) {
  std::array<glm::vec3, 8> out{};
  for (int k = 0; k < 8; ++k) {
    out[static_cast<std::size_t>(k)] = {(k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                        (k & 4) ? box.max.z : box.min.z};
  }
  return out;
}

} // namespace

ShadowCascades fitCascades(const Camera& camera, float aspect, const glm::vec3& sunDirection,
                           const ShadowSettings& settings, const Aabb& casterBounds) {
  if (settings.cascades < 1 || settings.cascades > 4) {
    fail("shadows: cascades must be 1..4 (got {})", settings.cascades);
  }
  if (settings.size < 16 || settings.size > 16384) {
    fail("shadows: size must be 16..16384 texels (got {})", settings.size);
  }
  if (!(settings.distance > 0.0f)) {
    fail("shadows: distance must be > 0 metres (got {:g})", settings.distance);
  }
  if (camera.orthoHeight > 0.0f) {
    fail("shadows: the viewing camera must be perspective");
  }
  const SunBasis sun = sunBasis(sunDirection);
  const float farDepth = std::min(settings.distance, camera.farPlane);

  ShadowCascades out;
  out.size = settings.size;
  out.splits = cascadeSplits(camera.nearPlane, farDepth, settings.cascades, settings.lambda);

  // Depth range shared by every cascade and independent of the camera: from just outside the casters on the
  // sun's side to just beyond them on the other, so one depth bias means the same metres everywhere and a
  // fixed point keeps its depth when the camera moves. (Receivers are expected inside the caster bounds; the
  // shader clamps deeper ones to the far plane.)
  const std::array<glm::vec3, 8> corners = boxCorners(casterBounds);
  float casterTop = -1e30f;
  float casterBottom = 1e30f;
  for (const glm::vec3& c : corners) {
    const float z = glm::dot(sun.back, c);
    casterTop = std::max(casterTop, z);
    casterBottom = std::min(casterBottom, z);
  }
  const float margin = std::max(1.0f, 1e-3f * (casterTop - casterBottom));
  const float eyeZ = casterTop + 2.0f * margin; // the sun camera stands just outside the casters
  const float nearPlane = margin;
  const float farPlane = eyeZ - casterBottom + margin;
  const glm::vec3 forward = camera.forward();
  struct Sphere {
    glm::vec3 centre;
    float radius;
  };
  std::vector<Sphere> spheres;
  for (int i = 0; i < settings.cascades; ++i) {
    const glm::vec2 s = sliceSphere(out.splits[static_cast<std::size_t>(i)],
                                    out.splits[static_cast<std::size_t>(i) + 1], camera.fovY, aspect);
    spheres.push_back({camera.position + forward * s.x, s.y});
  }

  for (int i = 0; i < settings.cascades; ++i) {
    const Sphere& sphere = spheres[static_cast<std::size_t>(i)];
    ShadowCascade cascade;
    cascade.nearDepth = out.splits[static_cast<std::size_t>(i)];
    cascade.farDepth = out.splits[static_cast<std::size_t>(i) + 1];
    cascade.centre = sphere.centre;
    cascade.radius = sphere.radius;
    // Half extent H with 2 texels to spare on each side (snapping moves the centre by ≤ half a texel; PCF
    // reads a texel and a half around the receiver): H = r + 2·(2H / size).
    const float size = static_cast<float>(settings.size);
    const float half = sphere.radius / (1.0f - 4.0f / size);
    cascade.texelSize = 2.0f * half / size;
    // Snap the centre to whole texels in the sun's view plane: the grid's origin stays at world texel
    // multiples whatever the camera does.
    const float sx = std::round(glm::dot(sun.right, sphere.centre) / cascade.texelSize) * cascade.texelSize;
    const float sy = std::round(glm::dot(sun.up, sphere.centre) / cascade.texelSize) * cascade.texelSize;
    // View: rows right, up, back; translation exactly (−sx, −sy, −eyeZ).
    glm::mat4 view(1.0f);
    for (int c = 0; c < 3; ++c) {
      view[c][0] = sun.right[c];
      view[c][1] = sun.up[c];
      view[c][2] = sun.back[c];
    }
    view[3] = glm::vec4(-sx, -sy, -eyeZ, 1.0f);
    cascade.view = view;
    Camera& cam = cascade.camera;
    cam.position = sun.right * sx + sun.up * sy + sun.back * eyeZ;
    cam.target = cam.position - sun.back;
    cam.up = sun.up;
    cam.orthoHeight = half;
    cam.nearPlane = nearPlane;
    cam.farPlane = farPlane;
    cascade.projection = cam.projection(1.0f);
    cascade.viewProj = cascade.projection * cascade.view;
    const glm::mat4 toUnit =
        glm::translate(glm::mat4(1.0f), glm::vec3(0.5f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.5f));
    cascade.shadow = toUnit * cascade.viewProj;
    out.cascades.push_back(cascade);
  }
  return out;
}

ShadowFrame toFrame(const ShadowCascades& cascades, const ShadowSettings& settings) {
  ShadowFrame frame;
  const int n = static_cast<int>(cascades.cascades.size());
  if (n > 4) {
    fail("shadows: at most 4 cascades fit the frame block (got {})", n);
  }
  frame.cascades = n;
  if (n == 0) {
    return frame;
  }
  const Camera& cam = cascades.cascades.front().camera;
  frame.depthBias = settings.depthBias / (cam.farPlane - cam.nearPlane); // metres → [0,1] depth
  frame.texel = 1.0f / static_cast<float>(cascades.size);
  frame.normalOffset = settings.normalOffset;
  for (int i = 0; i < 4; ++i) {
    if (i < n) {
      frame.splits[i] = cascades.cascades[static_cast<std::size_t>(i)].farDepth;
      frame.matrices[i] = cascades.cascades[static_cast<std::size_t>(i)].shadow;
    } else {
      frame.splits[i] = 0.0f;
      frame.matrices[i] = glm::mat4(1.0f);
    }
  }
  return frame;
}

int cascadeFor(const ShadowFrame& frame, const glm::mat4& view, const glm::vec3& p) {
  const float depth = -(view * glm::vec4(p, 1.0f)).z;
  for (int i = 0; i < frame.cascades; ++i) {
    if (depth < frame.splits[i]) {
      return i;
    }
  }
  return -1;
}

} // namespace sylva::render
