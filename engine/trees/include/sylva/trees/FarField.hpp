#pragma once
// Far-field trees (docs/trees.md "Far field"): beyond a distance trees become impostors; in a band they
// cross-fade by a screen-door dissolve with complementary masks. These are the CPU twins of
// shaders/trees/fade.glsl.

#include <sylva/core/Random.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <shared/Wind.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sylva::trees {

/** 0 nearer than range.x (pieces only), 1 beyond range.y (impostor only), linear between, metres; range.y <=
 * range.x: no far field (always 0). */
inline float farBlend(float distance, glm::vec2 range) {
  if (range.y <= range.x) {
    return 0.0f;
  }
  return std::clamp((distance - range.x) / (range.y - range.x), 0.0f, 1.0f);
}

/** The dissolve threshold of pixel (x, y) for tree `tree`, in (0, 1): a 4 × 4 Bayer matrix shifted per tree.
 */
inline float fadeThreshold(glm::uvec2 pixel, std::uint32_t tree) {
  constexpr std::array<std::uint32_t, 16> kBayer{0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
  const std::uint32_t h = lowbias32(tree * 0x9e3779b9u + 0x632be5abu);
  const glm::uvec2 p = (pixel + glm::uvec2(h & 3u, (h >> 2) & 3u)) & 3u;
  return (static_cast<float>(kBayer[p.y * 4u + p.x]) + 0.5f) / 16.0f;
}

/** Whether a tree's pieces cover the pixel at `blend`; impostorKeeps() is its complement. */
inline bool piecesKeep(float blend, glm::uvec2 pixel, std::uint32_t tree) {
  return blend < fadeThreshold(pixel, tree);
}
/** Whether the impostor covers the pixel at `blend`: the complement of piecesKeep(). */
inline bool impostorKeeps(float blend, glm::uvec2 pixel, std::uint32_t tree) {
  return blend >= fadeThreshold(pixel, tree);
}

// ---- Octahedral impostors (docs/trees.md "Far field"; GLSL twins in shaders/trees/impostor.glsl) ----------
// A species is baked from views × views directions on the upper hemisphere: the vertices of a grid over the
// hemi-octahedral square. Hemi-octahedral rather than full: trees are seen from above or from the side,
// almost never from below, so the whole atlas goes to the upper hemisphere (twice the angular resolution of a
// full octahedron for the same cells); directions below the horizon are clamped onto it.

/** Unit direction (y up; y < 0 is clamped to the horizon) to hemi-octahedral coordinates in [0, 1]². */
glm::vec2 hemiOctEncode(glm::vec3 direction);
/** Hemi-octahedral coordinates in [0, 1]² to a unit direction with y ≥ 0. */
glm::vec3 hemiOctDecode(glm::vec2 uv);

/** The atlas of one species (one texture array layer): views × views cells of cell × cell pixels. */
struct ImpostorLayout {
  /** Views per side of the grid. */
  int views = 8;
  /** Pixels per view. */
  int cell = 128;
  /** The atlas side, pixels. */
  int side() const { return views * cell; }
};

/** The direction (towards the viewer, object frame) baked into cell (i, j): grid vertex (i, j) / (views − 1).
 */
glm::vec3 impostorViewDirection(glm::ivec2 cell, int views);

/**
 * The three baked views to blend for `direction` (object frame, towards the viewer): the corners of the grid
 * triangle holding its hemi-octahedral point, with barycentric weights (sum 1, continuous in the direction:
 * a view's weight falls to 0 on the far edge of every triangle it belongs to).
 */
struct ImpostorViews {
  /** The three views' cells. */
  std::array<glm::ivec2, 3> cells{};
  /** Their barycentric weights (sum 1). */
  glm::vec3 weights{0.0f};
};
/** The three views to blend for `direction` on a grid of `views` × `views`. */
ImpostorViews impostorViews(glm::vec3 direction, int views);

/**
 * The billboard frame of a view direction `forward` (unit, towards the viewer): right = cross(up hint,
 * forward), up = cross(forward, right), with the up hint +y, or −z within 0.1° of straight up. A bake camera
 * at centre + forward · d looking at the centre with this up sees `right` to the right and `up` upwards.
 */
struct ImpostorBasis {
  /** The billboard's right, world. */
  glm::vec3 right{1.0f, 0.0f, 0.0f};
  /** The billboard's up, world. */
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  /** Towards the viewer, world. */
  glm::vec3 forward{0.0f, 0.0f, 1.0f};
};
/** The billboard frame of view direction `forward`. */
ImpostorBasis impostorBasis(glm::vec3 forward);

/**
 * Pixel (x, y) of the atlas (x right, y up as GL stores it) where the point `local` of view `cell` lies:
 * local = (right, up) coordinates on the view plane in units of the bounding radius, [-1, 1] covering the
 * cell.
 */
glm::vec2 impostorAtlasPixel(glm::ivec2 cell, glm::vec2 local, const ImpostorLayout& layout);

/** Rotation of a far tree about +y by `yaw` radians (as baseFrame turns a tree): object → world. */
glm::vec3 yawRotate(glm::vec3 v, float yaw);

// ---- Far trees ------------------------------------------------------------------------------------------

/** A tree drawn as an impostor: no topology, just where, how tall, which species. */
struct FarTree {
  /** Base (world, metres), as ForestTree::base's translation. */
  glm::vec3 position{0.0f};
  /** Crown height, metres (as TreeRenderer::treeCentres() w: the rest pose height times the base scale). */
  float height = 10.0f;
  /** Index of its species (its impostor atlas layer). */
  int species = 0;
  /** The tree index of the dissolve (TreeRenderer's tree index for trees that also have pieces). */
  std::uint32_t id = 0;
  /** Turn about +y, radians (the impostor is turned by it). */
  float yaw = 0.0f;
  /** Trees without pieces: drawn at any distance, never dissolved. */
  bool farOnly = false;
};

/**
 * CPU twin of the impostor cull (shaders/trees/impostor.glsl impostorVisible): whether `tree` is drawn for a
 * camera at `eye` with frustum `planes` (world, normals inwards) and far range `farRange`; `sphere` is its
 * species' bounding sphere in crown heights (ImpostorRenderer::speciesSphere); `lean` the tree's lean in the
 * wind (impostorLean; the sphere is sheared with it, impostorLeanedSphere).
 */
bool impostorVisible(const FarTree& tree, glm::vec4 sphere, const std::array<glm::vec4, 6>& planes,
                     glm::vec3 eye, glm::vec2 farRange, glm::vec2 lean = glm::vec2(0.0f));

/**
 * How far trees sway (docs/trees.md "Far field"). An impostor cannot bend its branches, so the whole tree
 * leans: every point p of it moves by lean · (p.y − base.y) along world (x, z), a shear about its base, which
 * keeps rays straight, so the fragment shader looks the atlas up along the un-sheared ray. The lean follows
 * the wind at the tree quasi-statically, as a spring's rest bend follows its load: lean = k · |u| u (u: the
 * wind velocity at the tree's base (x, z) at the wind's time plus the tree's own offset, m/s), at most
 * `maxLean` long.
 */
struct Forest;

/** How a species' far trees lean in the wind: lean = k · |u| u, u the wind at the base. */
struct ImpostorSway {
  /** k: lean per squared wind speed, 1/(m/s)² (0: the species does not sway). */
  float perSpeedSquared = 0.0f;
  /** Longest lean (metres sideways per metre up; 0.35 ≈ 19°). */
  float maxLean = 0.35f;
};

/**
 * Calibrates a species' sway on tree `tree` of `forest` from its joint springs (JointWind), so that far trees
 * lean as much as their near twins bend: the springs stand `seconds` in a steady wind of `speed` m/s along +x
 * without gusts or turbulence (from rest, long enough to settle: 30 s is over six decay times of the
 * slowest trunk joint), then the joints' downwind displacements d_j at heights y_j above the base are fitted
 * by a lean through the base, lean = Σ d_j y_j / Σ y_j², and k = lean / speed². Deterministic.
 */
ImpostorSway calibrateImpostorSway(const Forest& forest, std::size_t tree, float speed = 5.0f,
                                   float seconds = 30.0f);

/** Seconds added to the wind's clock for far tree `id`, in [0, 600) (impostorWindOffset in impostor.glsl). */
float impostorWindOffset(std::uint32_t id);

/**
 * The lean of far tree `tree` (world x, z metres per metre above its base) in `wind` (its clock plus the
 * tree's impostorWindOffset): sway.perSpeedSquared · |u| u at the tree's base, at most sway.maxLean long
 * (impostorLean in impostor.glsl, operation for operation).
 */
glm::vec2 impostorLean(const FarTree& tree, const ImpostorSway& sway, const gpu::WindUniforms& wind);

/** The bounding sphere (world centre, radius) of a tree whose unleaned sphere is `sphere` (world) and whose
 * base is at height `baseY`, sheared by `lean`: centre + lean · (centre.y − baseY), radius · (1 + |lean|). */
glm::vec4 impostorLeanedSphere(glm::vec4 sphere, float baseY, glm::vec2 lean);

/** The far-field twins of a forest's trees (same index, base, crown height and yaw). */
std::vector<FarTree> farTrees(const Forest& forest);

/** A large far-only field (benchmarks, the horizon around a detailed forest). */
struct FarTreeFieldSettings {
  /** Trees in the field. */
  int count = 100000;
  /** Seed of their places, species and heights. */
  std::uint64_t seed = 1;
  /** An annulus around `centre` (world x, z metres): trees lie between the radii, uniformly by area. */
  glm::vec2 centre{0.0f};
  /** Inner radius of the annulus, metres. */
  float innerRadius = 0.0f;
  /** Outer radius of the annulus, metres. */
  float outerRadius = 2000.0f;
  /** Species 0 … species − 1, uniformly. */
  int species = 1;
  /** Crown heights, uniformly in this range (metres). */
  float minHeight = 8.0f;
  /** Tallest crown, metres. */
  float maxHeight = 16.0f;
  /** Heights of the terrain field times this are drawn heights. */
  float verticalScale = 1.0f;
  /** First tree id (ids are firstId, firstId + 1, …). */
  std::uint32_t firstId = 0;
};

/**
 * `settings.count` far-only trees in the annulus, on flat ground at y = 0 or on `terrain` (points outside
 * its footprint are redrawn, at most 40 tries per tree, so fewer trees when little of the annulus is
 * terrain). Deterministic in the seed. Throws sylva::Error for bad settings.
 */
std::vector<FarTree> farTreeField(const FarTreeFieldSettings& settings,
                                  const terrain::HeightField* terrain = nullptr);

} // namespace sylva::trees
