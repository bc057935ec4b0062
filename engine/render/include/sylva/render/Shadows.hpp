#pragma once

#include <sylva/core/Geometry.hpp>
#include <sylva/render/Camera.hpp>
#include <sylva/render/Environment.hpp>

#include <glm/glm.hpp>

#include <vector>

namespace sylva::render {

/** How the sun's cascaded shadow maps cover a view (docs/scenes.md, "Shadows"). */
struct ShadowSettings {
  int cascades = 3;        ///< 1..4 cascades (layers of the shadow-map array)
  int size = 2048;         ///< texels per side of each cascade
  float distance = 400.0f; ///< metres along the view direction covered by the cascades (capped by farPlane)
  float lambda = 0.7f;     ///< practical split scheme: 0 = uniform, 1 = logarithmic (Zhang et al. 2006)
  float depthBias = 0.05f; ///< receivers move this many metres towards the sun before the depth compare
  float normalOffset =
      1.5f; ///< receivers move along their normal by this many shadow texels of their cascade
};

/**
 * Casters narrower than this many texels of their cascade may be skipped (size culling, e.g. a tree's twigs):
 * a receiver's filter reads 3 × 3 texels around it, so such a caster only ever made a partial shadow. On the
 * meadow scene's view it changes no pixel (inside a crown the foliage's shadow covers the twigs'); the
 * fly-over's first frame at 640 × 360: 13 pixels by at most 10/255.
 */
inline constexpr float kCasterMinTexels = 3.0f;

/** One cascade: the sun's orthographic view of a slice of the camera frustum. */
struct ShadowCascade {
  float nearDepth = 0.0f;     ///< slice start, metres along the view direction
  float farDepth = 0.0f;      ///< slice end, metres along the view direction
  glm::vec3 centre{0.0f};     ///< bounding sphere of the slice (world metres), before texel snapping
  float radius = 0.0f;        ///< its radius, metres; depends only on fov, aspect and the split depths
  float texelSize = 0.0f;     ///< world metres per shadow-map texel
  glm::mat4 view{1.0f};       ///< world → sun view
  glm::mat4 projection{1.0f}; ///< sun view → clip (orthographic)
  glm::mat4 viewProj{1.0f};   ///< world → clip, to draw the casters into this cascade's layer
  glm::mat4 shadow{1.0f};     ///< world → shadow-map space [0,1]³ (xy texture coordinates, z depth)
  Camera camera; ///< orthographic camera with these matrices (aspect 1) for the existing renderers
};

/** The cascades of one frame. */
struct ShadowCascades {
  /** Nearest first. */
  std::vector<ShadowCascade> cascades;
  /** Split depths along the view direction, metres: cascades + 1 values from the near plane to the far end.
   */
  std::vector<float> splits;
  int size = 0; ///< texels per side of each cascade
};

/**
 * Practical split scheme (Zhang et al. 2006): boundary i of n slices between `nearDepth` and `farDepth`
 * (metres, 0 < near < far) is λ·near·(far/near)^(i/n) + (1 − λ)·(near + (far − near)·i/n). Returns n + 1
 * values, the first exactly `nearDepth` and the last exactly `farDepth`. Throws sylva::Error on bad input.
 */
std::vector<float> cascadeSplits(float nearDepth, float farDepth, int n, float lambda);

/**
 * Bounding sphere of the slice [nearDepth, farDepth] of a symmetric perspective frustum with vertical field
 * of view `fovY` (radians) and `aspect`: returns (distance of the centre along the view axis, radius),
 * metres. Independent of the camera's orientation, so the cascade's size stays the same when the camera
 * turns.
 */
glm::vec2 sliceSphere(float nearDepth, float farDepth, float fovY, float aspect);

/**
 * Fits the cascades of `settings` to `camera` (perspective, `aspect` = width / height) for the sun in
 * direction `sunDirection` (world, towards the sun). Each cascade bounds its frustum slice by a sphere, looks
 * at it from the sun through an orthographic view whose near plane is pulled back to include every corner of
 * `casterBounds` (world metres), and snaps the sphere's centre to whole shadow texels in the sun's view
 * plane, so a camera translation moves the shadow-map grid over the world by whole texels only (no swimming).
 * The sun view's orientation depends on the sun alone. Throws sylva::Error on bad settings.
 */
ShadowCascades fitCascades(const Camera& camera, float aspect, const glm::vec3& sunDirection,
                           const ShadowSettings& settings, const Aabb& casterBounds);

/** The frame-uniform view of `cascades` (render::Environment::shadows): matrices, splits, bias and offsets.
 */
ShadowFrame toFrame(const ShadowCascades& cascades, const ShadowSettings& settings);

/**
 * CPU twin of shaders/common/shadows.glsl's cascade choice: the first cascade whose far split is beyond the
 * view depth |(view · p).z| of world point `p` (metres), or -1 beyond the last one.
 */
int cascadeFor(const ShadowFrame& frame, const glm::mat4& view, const glm::vec3& p);

} // namespace sylva::render
