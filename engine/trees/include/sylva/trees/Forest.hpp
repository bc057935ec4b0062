#pragma once
// Forests (docs/trees.md): many trees, each its own topology and pose, concatenated so every piece instance
// of every tree can be drawn by piece type and every joint lives in one buffer. Placement on terrain by
// seeded density, slope and height rules.

#include <sylva/core/Geometry.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/trees/JointWind.hpp>
#include <sylva/trees/Skeleton.hpp>

#include <shared/Trees.h>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <limits>
#include <string>
#include <vector>

namespace sylva::trees {

/** One tree of a forest. */
struct ForestTree {
  /** The tree's pieces and joints. */
  TreeTopology topology;
  /** Index into Forest::species. */
  int species = 0;
  /** Base frame: world placement, metres per rim unit (see baseFrame). */
  glm::mat4 base{1.0f};
  /** Rest pose bends per joint (randomPose), radians. */
  std::vector<glm::vec2> pose;
  /** Wind phase offset, seconds (no two trees move in unison). */
  float phase = 0.0f;
};

/** Trees with their pieces and species; jointOffset[t] is tree t's joint 0 in the global joint numbering. */
struct Forest {
  /** The pieces every tree is built from. */
  PieceSet pieces;
  /** The species, indexed by ForestTree::species. */
  std::vector<Species> species;
  /** The trees. */
  std::vector<ForestTree> trees;
  /** Per tree: its joint 0 in the global joint numbering. */
  std::vector<std::uint32_t> jointOffset;
  /** Joints over all trees. */
  std::size_t jointCount = 0;

  /** Recomputes jointOffset and jointCount (call after changing trees). */
  void index();
};

/** Where trees may grow and how many (scene files, `sylva render --trees`). */
struct ForestSettings {
  /** Species mix (preset names or species files), chosen uniformly per tree. */
  std::vector<std::string> species{"almond"};
  /** Trees to place. */
  int count = 100;
  /** Seed of the placement and of every tree's growth. */
  std::uint64_t seed = 1;
  /** Minimum distance between trunks, metres. */
  float spacing = 4.0f;
  /** Steepest ground a tree grows on, degrees. */
  float maxSlope = 30.0f;
  /** Height band, metres (NaN: no limit). */
  float minHeight = std::numeric_limits<float>::quiet_NaN();
  /** Highest ground a tree grows on, metres (NaN: no limit). */
  float maxHeight = std::numeric_limits<float>::quiet_NaN();
  /** Density noise: feature size in metres and the fraction of ground it leaves bare (0: uniform). */
  float clusterSize = 60.0f;
  /** Fraction of the ground the density noise leaves bare, [0, 1). */
  float bare = 0.35f;
  /** Region trees grow in: centre (world x, z metres) and radius in metres; radius 0: the whole terrain. */
  glm::vec2 regionCentre{0.0f};
  /** Region radius, metres (0: the whole terrain). */
  float regionRadius = 0.0f;
  /** Heights of the terrain field are multiplied by this to get drawn heights (terrain exaggeration). */
  float verticalScale = 1.0f;
  /** Relative weight of each species (same order as `species`, each > 0); empty: every species equally. */
  std::vector<float> speciesWeights;
  /** Season of the leaves: 0 summer (each species' leafColour) … 1 full autumn colour (autumnColour). */
  float autumn = 0.0f;
  /**
   * Share of the deciduous species' leaf clusters fallen, 0 … 1 (1: bare winter crowns; evergreen species
   * keep theirs): each species' leafDensity becomes seasonalLeafDensity().
   */
  float leafFall = 0.0f;
  /**
   * Density map over the terrain's footprint: `densityWidth` × `densityHeight` values in [0, 1], row 0 at
   * z = 0 (north), stretched over [0, extentX] × [0, extentZ]; a candidate at p survives with the map's
   * bilinear value there. Empty: no map.
   */
  std::vector<float> densityMap;
  /** Columns of densityMap. */
  int densityWidth = 0;
  /** Rows of densityMap. */
  int densityHeight = 0;
};

/** Throws sylva::Error "<where>.<field>: …" for bad settings (counts ≤ 1,000,000, finite positive sizes). */
void validate(const ForestSettings& settings, const std::string& where);

/**
 * Places up to settings.count trees on `terrain` (dart throwing with the spacing, rules, density noise; fewer
 * when the ground runs out after 40 tries per tree). Deterministic in the seed.
 */
Forest placeForest(const terrain::HeightField& terrain, const ForestSettings& settings);

/**
 * A square grid of `side` × `side` trees `spacing` metres apart on flat ground at y = 0 around the origin
 * (benchmarks, tests); tree i is of species[i % species.size()] (preset names or files).
 */
Forest gridForest(const std::vector<std::string>& species, int side, float spacing, std::uint64_t seed);
/** The same grid from species given as values (each validated). */
Forest gridForestOf(const std::vector<Species>& species, int side, float spacing, std::uint64_t seed);

/** Instances grouped by piece type: instances[first[t] … first[t] + count[t]) are of piece type t. */
struct PackedInstances {
  /** The instances, grouped by piece type. */
  std::vector<gpu::TreeInstanceGpu> instances;
  /** Per piece type: index of its first instance. */
  std::vector<std::uint32_t> first;
  /** Per piece type: its number of instances. */
  std::vector<std::uint32_t> count;
};
/** The forest's piece instances grouped by piece type (what TreeRenderer uploads). */
PackedInstances packInstances(const Forest& forest);

/** A similarity as the GPU's three rows. */
gpu::JointFrame packFrame(const glm::mat4& frame);

/**
 * Every joint frame of every tree (world space), rest pose plus `extraBends` (per global joint, radians;
 * empty: none).
 */
void forestFrames(const Forest& forest, std::span<const glm::vec2> extraBends,
                  std::vector<gpu::JointFrame>& out);

/** The joint springs' rest data of `forest` (one JointWindTree per tree; its phase is the wind offset). */
JointWindRest forestWindRest(const Forest& forest);

/**
 * World box around every tree of `forest` at rest (metres), with a margin of half the tallest tree plus 2 m:
 * every piece lies within a few rim radii of its joints, and bends of at most 30° per joint move a crown by
 * less than that. An empty forest gives a zero box at the origin.
 */
Aabb forestBounds(const Forest& forest);

/** Per piece type: bounding sphere and inverse binds, as the renderer uploads them (ranges left zero). */
gpu::TreePieceGpu pieceTableEntry(const Piece& piece);

/**
 * Size culling (TreeLod::minPixels) as the culling pass takes it (TreeUniforms::cull.zw): a piece is dropped
 * when its bounding sphere's diameter d (metres) < x · distance + y. A perspective camera (`orthoHeight` 0)
 * of vertical field of view `fovY` (radians) gives x = minPixels / focal length in pixels, y = 0; an
 * orthographic one (±`orthoHeight` metres) gives x = 0, y = minPixels · metres per pixel. `height` is the
 * target's height in pixels; minPixels <= 0 or height <= 0 gives (0, 0): nothing is dropped.
 */
glm::vec2 sizeCullTerms(float fovY, float orthoHeight, int height, float minPixels);

/**
 * CPU reference of the culling pass: the visible instance indices of each piece type (sorted), given the
 * frames, the camera's frustum planes (as in TreeUniforms) and position, the draw distance, the slack, the
 * size culling terms of the bounding sphere (sizeCullTerms with TreeLod::minPixels; zero: none) and those of
 * the width (sizeCullTerms with TreeLod::minWidthPixels: a piece is dropped when its root rim, 2 · frame
 * scale metres across, is narrower; zero: none). With a far range (TreeLod::farRange, y > x) and the trees'
 * centres (TreeRenderer::treeCentres: base xyz, crown height w), the pieces of a tree whose crown centre
 * (half its height up) lies at or past the end of the fade band are dropped too: there the tree is its
 * impostor alone and its pieces would draw no pixel.
 */
std::vector<std::vector<std::uint32_t>>
cullInstances(const PackedInstances& packed, std::span<const gpu::TreePieceGpu> pieces,
              std::span<const gpu::JointFrame> frames, const std::array<glm::vec4, 6>& planes,
              glm::vec3 camera, float drawDistance, float slack, glm::vec2 sizeCull = glm::vec2(0.0f),
              glm::vec2 widthCull = glm::vec2(0.0f), std::span<const glm::vec4> treeCentres = {},
              glm::vec2 farRange = glm::vec2(0.0f));

} // namespace sylva::trees
