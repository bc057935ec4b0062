#include <sylva/terrain/Geomorph.hpp>

#include <sylva/terrain/HeightQuery.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::terrain {

GeomorphParams GeomorphParams::of(const QuadtreeConfig& config) {
  GeomorphParams p;
  p.rootSize = config.rootSize;
  p.maxDepth = config.maxDepth;
  p.patchTessLevel = config.patchTessLevel;
  p.lodDistanceFactor = config.lodDistanceFactor;
  // Screen-space-error LOD bounds what a split changes on screen by its threshold already, and its leaves
  // can be much finer than their distance implies: morphing them towards distance-based levels would throw
  // away the detail the error asked for (and move the surface outside the boxes culling trusts).
  p.enabled = config.lodEnabled && config.lodErrorPixels <= 0.0f;
  return p;
}

float morphLevel(float distance, const GeomorphParams& params) {
  return std::log2(params.lodDistanceFactor * params.rootSize / std::max(distance, 1e-3f));
}

float latticeHeight(const HeightField& field, const glm::vec2& xz, int depth, const GeomorphParams& params) {
  if (depth >= params.maxDepth) {
    return heightAt(field, xz.x, xz.y);
  }
  // Same float operations as terrain.glsl latticeHeight.
  const float step =
      params.rootSize / (std::exp2(static_cast<float>(depth)) * static_cast<float>(params.patchTessLevel));
  const glm::vec2 q = xz / step;
  const glm::vec2 c = glm::floor(q);
  const glm::vec2 f = q - c;
  const glm::vec2 p0 = c * step;
  const glm::vec2 p1 = (c + 1.0f) * step;
  const float h00 = heightAt(field, p0.x, p0.y);
  const float h10 = heightAt(field, p1.x, p0.y);
  const float h01 = heightAt(field, p0.x, p1.y);
  const float h11 = heightAt(field, p1.x, p1.y);
  const float a = h00 + (h10 - h00) * f.x;
  const float b = h01 + (h11 - h01) * f.x;
  return a + (b - a) * f.y;
}

float morphedHeight(const HeightField& field, const glm::vec2& xz, const glm::vec3& camera,
                    const GeomorphParams& params) {
  const float h = heightAt(field, xz.x, xz.y);
  if (!params.enabled) {
    return h;
  }
  const float r = glm::length(camera - glm::vec3(xz.x, h, xz.y));
  const float lambda = morphLevel(r, params);
  const int n = std::clamp(static_cast<int>(std::ceil(std::min(lambda, 64.0f))), 0, params.maxDepth);
  const float t = n == 0 ? 0.0f : std::clamp(static_cast<float>(n) - lambda, 0.0f, 1.0f);
  const float fine = latticeHeight(field, xz, n, params);
  if (t == 0.0f) {
    return fine;
  }
  const float coarse = latticeHeight(field, xz, n - 1, params);
  return fine + (coarse - fine) * t;
}

} // namespace sylva::terrain
