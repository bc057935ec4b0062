#pragma once
// How a generated tree measures against its species (docs/trees.md "Measuring a tree", issue 29): height,
// trunk radius and slenderness, crown base, width and height, the silhouette's width from base to apex, the
// twig tips and which of them droop, and pieces — the figures foresters and botanical references give, taken
// from the pose the renderer draws.

#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/Tree.hpp>

#include <glm/vec2.hpp>

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sylva::trees {

/** Bins of TreeMeasures::profile, base to apex. */
inline constexpr int kProfileBins = 10;

/** A tree's shape in metres (world space: y up, the base at the origin; woody parts, no foliage). */
struct TreeMeasures {
  float height = 0.0f;      ///< top of the highest branch surface above the base
  float trunkRadius = 0.0f; ///< radius of the trunk at the base
  /** height / trunkRadius: how slender the tree is (grown trees: roughly 40–120). */
  float slenderness = 0.0f;
  /** Height of the lowest point where a branch leaves the trunk (the crown base); the height without one. */
  float crownBase = 0.0f;
  float crownHeight = 0.0f; ///< height − crownBase
  /** The crown's widest horizontal extent over 16 directions (caliper width), surfaces above the crown base.
   */
  float crownWidth = 0.0f;
  /** crownWidth / crownHeight (a column is well below 1, a spreading crown above it). */
  float crownRatio = 0.0f;
  /**
   * The crown's caliper width with its leaves: every leaf cluster a sphere of the species' leafCluster radius
   * (0.6 m when it has none) around the joint that carries it. What a forester's "spread" measures.
   */
  float leafyWidth = 0.0f;
  /** leafyWidth / height: the spread against the height, as nursery and forestry references give them. */
  float spread = 0.0f;
  /** Caliper width of the surfaces in each of kProfileBins equal height bands from the base to the top. */
  std::array<float, kProfileBins> profile{};
  /** Piece instances in the tree. */
  std::size_t pieces = 0;
  /** Branch ends (cap pieces), and those whose axis points below the horizontal where they attach. */
  std::size_t tips = 0;
  /** Of those, the tips whose axis points below the horizontal. */
  std::size_t droopingTips = 0;
  float droopingFraction = 0.0f; ///< droopingTips / tips
};

/**
 * Measures `tree` of `species` drawn in `pose` (bends per joint, randomPose(); empty: straight), at the
 * species' trunk radius, from its mesh at tessellation level 4.
 */
TreeMeasures measureTree(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                         std::span<const glm::vec2> pose);

/** The tree `species` grows from `seed`, measured in the pose the renderer draws it in. */
TreeMeasures measureSpecies(const PieceSet& pieces, const Species& species, std::uint64_t seed);

/** A closed range [lo, hi]. */
struct MeasureRange {
  /** Lower end. */
  float lo = 0.0f;
  /** Upper end. */
  float hi = 0.0f;
  /** Whether lo ≤ v ≤ hi. */
  bool contains(float v) const { return v >= lo && v <= hi; }
};

/**
 * What a preset of a real species is tuned to and tested against (docs/trees.md "Species targets", with the
 * references): height (m), slenderness (height / trunk radius), spread (leafy crown width / height), crown
 * base (share of the height) and the share of drooping twig tips.
 */
struct SpeciesTargets {
  /** Tree height, metres. */
  MeasureRange height;
  /** Height over trunk radius. */
  MeasureRange slenderness;
  /** Leafy crown width over height. */
  MeasureRange spread;
  /** Crown base, as a share of the height. */
  MeasureRange crownBase;
  /** Share of drooping twig tips. */
  MeasureRange drooping;
};

/** The targets of preset `name` (realSpeciesPresetNames()); nullopt for any other name. */
std::optional<SpeciesTargets> speciesTargets(const std::string& name);

/** "height 12.3 m outside [15, 30]; …" for each measure of `m` outside `targets`; empty when all are in. */
std::string targetMisses(const TreeMeasures& m, const SpeciesTargets& targets);

/** The minimum, mean and maximum of each measure over several trees. */
struct MeasureSummary {
  /** Each tree's measures. */
  std::vector<TreeMeasures> trees;
  /** The smallest value of each measure. */
  TreeMeasures min;
  /** The mean of each measure. */
  TreeMeasures mean;
  /** The largest value of each measure. */
  TreeMeasures max;
};
/** The minimum, mean and maximum of each measure over `trees`. */
MeasureSummary summarise(std::vector<TreeMeasures> trees);

/**
 * What `sylva tree measure` prints: one line per tree (seed, height, trunk radius, slenderness, crown base,
 * width, height and ratio, tips and drooping share, pieces), then min / mean / max and the mean silhouette
 * profile; lines end in '\n'. `firstSeed`: the seed of trees[0] (the others follow).
 */
std::string describeMeasures(const std::string& species, std::uint64_t firstSeed,
                             const MeasureSummary& summary);
/** The same as JSON: {"species", "trees": [{"seed", measures…}], "min", "mean", "max"}. */
nlohmann::json describeMeasuresJson(const std::string& species, std::uint64_t firstSeed,
                                    const MeasureSummary& summary);

} // namespace sylva::trees
