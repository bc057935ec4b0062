#pragma once

#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/Quadtree.hpp>

#include <glm/glm.hpp>

/**
 * Terrain geomorphing (CPU reference of shaders/terrain/terrain.glsl `terrainMorphedHeight`): the height
 * drawn at a lattice point is a function of its world xz and the camera only, blended continuously between
 * the surfaces that two quadtree depths can represent, so a patch that splits or merges lands on (nearly) the
 * surface it replaces. See docs/terrain-lod.md, "Geomorphing".
 *
 * Spaces: world metres, y up; heights as in the HeightField (already exaggerated when the scene exaggerates).
 */
namespace sylva::terrain {

/** The LOD distances the morph follows: those of the Quadtree config the selection was made with. */
struct GeomorphParams {
  /** Root node edge length, metres. */
  float rootSize = 256.0f;
  /** Deepest quadtree depth; at and beyond its band the morph is the plain bilinear surface. */
  int maxDepth = 5;
  /** Base tessellation level T: a depth-d patch has vertices every rootSize / (2^d · T) metres. */
  int patchTessLevel = 16;
  /** LOD distance factor F: a node of size s splits when the camera is closer than F · s (metres). */
  float lodDistanceFactor = 2.0f;
  /** False: no morph (the plain bilinear height); also when the config has LOD disabled. */
  bool enabled = true;

  /**
   * The parameters of `config`: enabled when config.lodEnabled and distance LOD (screen-space-error LOD
   * bounds what a split changes on screen by its threshold, so it draws without a morph).
   */
  static GeomorphParams of(const QuadtreeConfig& config);
};

/**
 * Continuous LOD level at `distance` metres from the camera: λ = log2(F · rootSize / distance). Every
 * selected leaf containing a point at that distance has depth ≥ λ (its node did not split, so its box
 * distance, ≤ the point's distance, is ≥ F · size).
 */
float morphLevel(float distance, const GeomorphParams& params);

/**
 * Height of the surface a depth-`depth` patch represents at world `xz` (metres): the bilinear interpolation
 * of heightAt over the lattice of that depth's vertices, spacing rootSize / (2^depth · T) from the origin.
 * depth ≥ maxDepth gives heightAt itself.
 */
float latticeHeight(const HeightField& field, const glm::vec2& xz, int depth, const GeomorphParams& params);

/**
 * The morphed height at world `xz` (metres) for a camera at `camera`: with r the distance from the camera to
 * (x, heightAt(xz), z), λ = morphLevel(r), n = clamp(⌈λ⌉, 0, maxDepth) and t = clamp(n − λ, 0, 1) (0 when
 * n = 0), mix(latticeHeight(n), latticeHeight(n − 1), t). Continuous in xz and in the camera; equal to
 * heightAt where λ ≥ maxDepth (near the camera) and when !params.enabled.
 */
float morphedHeight(const HeightField& field, const glm::vec2& xz, const glm::vec3& camera,
                    const GeomorphParams& params);

} // namespace sylva::terrain
