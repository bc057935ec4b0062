#pragma once
// Species (docs/trees.md): the assembly rule and its parameters per branching order. The paper's two rules
// (alternate I and Y; choose uniformly at random) and a seeded stochastic grammar whose probabilities, branch
// lengths and bends are set per order, with presets after published parameter tables (Weber & Penn 1995).

#include <nlohmann/json_fwd.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::trees {

/** How pieces are chosen at each open leaf rim. */
enum class AssemblyRule {
  /** The paper's first rule: Y and I alternate with depth. */
  Alternate,
  /** The paper's second rule: I or Y with equal probability. */
  UniformRandom,
  /** The stochastic grammar: per-order probabilities, segment counts and bends. */
  Grammar,
};

/** Grammar parameters of one branching order (0: the trunk). Probabilities are per open rim. */
struct OrderParams {
  /** I pieces an axis of this order has before it may split, and after which it must split or end. */
  int minSegments = 2;
  /** Most I pieces before the axis must split or end. */
  int maxSegments = 5;
  /** Probabilities of a split once allowed: symmetric fork Y, trifurcation Psi, side branch ⊢ (stem goes on).
   */
  float fork = 0.3f;
  /** Probability of a trifurcation Psi once allowed. */
  float trifurcation = 0.0f;
  /** Probability of a side branch once allowed. */
  float sideBranch = 0.3f;
  /** Fork asymmetry: one child's bone scale is 1 − asymmetry, the other's 1 (0: symmetric). */
  float asymmetry = 0.0f;
  /** Random pose: bend amplitude per joint, radians (paper Fig. 6). */
  float bend = 0.1f;
  /** Systematic droop towards the ground per joint, radians (weeping forms), applied along the bone's tilt.
   */
  float droop = 0.0f;
  /**
   * Length of the I and Branch pieces on axes of this order, × their modelled length (TreeNode::stretch),
   * varied ±15 % per piece; 1 keeps the pieces as modelled. Longer segments make slender stems: an I is 5
   * rim radii long as modelled and narrows to 0.875 of its radius.
   */
  float stretch = 1.0f;
  /**
   * Radius of a side branch relative to its stem at a Branch piece (0: the piece's own 0.5 and 0.85); the
   * stem then keeps √(1 − sideRadius²) of its radius (the pipe model, Leonardo's rule: cross-sections are
   * conserved).
   */
  float sideRadius = 0.0f;
  /**
   * Side branches per whorl (conifers: spruce, fir, pine), 0 or 1: none (side branches one at a time), 2 … 6:
   * a side branch on this order starts a whorl of that many Branch pieces, each short (stretch 0.5) and
   * turned 6 / whorl rim steps from the last, so their side branches leave at one height all round; the stem
   * then grows minSegments … maxSegments I pieces (the internode) before the next whorl.
   */
  int whorl = 0;
};

/** What a species' leaf clusters are made of. */
enum class FoliageKind {
  /** Broad leaves: the leaf image on FoliageSettings::cloud's cards. */
  Broadleaf,
  /** Needle sprays (conifers): FoliageSettings::needles' shoots of needles. */
  Needles,
};

/** A species: rule, limits, per-order grammar, size and colours. */
struct Species {
  /** Name (a preset's, or the file's "name"). */
  std::string name = "almond";
  /** How the tree is assembled (the paper's alternate or uniform rules, or the grammar). */
  AssemblyRule rule = AssemblyRule::Grammar;
  /** Deepest branching order; axes of this order end in caps. */
  int maxOrder = 4;
  /** Depth limit (pieces from the root) for the alternate and uniform rules, and a hard cap for all. */
  int maxDepth = 24;
  /** At most this many pieces per tree (a recursion limit; open rims beyond it are capped). */
  int maxPieces = 4000;
  /** Rims narrower than this many trunk radii end in a cap. */
  float minRadius = 0.04f;
  /** Trunk radius at the base, metres (the piece unit). */
  float trunkRadius = 0.18f;
  /** Random scale per tree, ± fraction. */
  float sizeVariation = 0.15f;
  /** Grammar parameters per branching order (the last entry for deeper orders). */
  std::vector<OrderParams> orders{OrderParams{}};
  /** Bark colour, linear RGB (without bark tiles). */
  glm::vec3 barkColour{0.33f, 0.25f, 0.19f};
  /** Summer leaf colour, linear RGB. */
  glm::vec3 leafColour{0.22f, 0.42f, 0.14f};
  /** Leaf colour in full autumn colour, linear RGB (ForestSettings::autumn blends towards it). */
  glm::vec3 autumnColour{0.62f, 0.42f, 0.12f};
  /**
   * Radius of the leaf cluster on each twig tip, metres (the foliage billboard's sphere, ± the foliage
   * settings' variation); 0: sized from the twig by FoliageSettings (radiusScale, minRadius, maxRadius).
   */
  float leafCluster = 0.0f;
  /**
   * Leaves along twigs: every piece on an axis of this branching order or deeper carries a leaf cluster too
   * (hanging willow shoots, birch twigs), not only the twig tips; 0: tips only.
   */
  int leafOrder = 0;
  /** Broad leaves or needle sprays (JSON "foliage": "broadleaf" or "needles"). */
  FoliageKind foliage = FoliageKind::Broadleaf;
  /** Share of the leaf clusters the crown carries, 0 … 1 (1: every twig tip; ForestSettings::leafFall thins
   * it). */
  float leafDensity = 1.0f;
  /** Keeps its leaves through the year (the spruce); deciduous species lose them to ForestSettings::leafFall.
   */
  bool evergreen = false;
  /**
   * Bark photos the bark tiles are synthesised from (docs/trees.md "Bark"): one of barkPhotoNames()
   * (ez-tree's oak, birch, pine, willow) or "procedural" (no photos needed).
   */
  std::string bark = "oak";
  /** Wind: Young's modulus of the wood, Pa; wood density kg/m³; damping ratio. */
  float youngModulus = 9e9f;
  /** Wood density, kg/m³. */
  float woodDensity = 700.0f;
  /** Damping ratio of the joint springs. */
  float damping = 0.1f;

  /** Parameters of order `o` (the last entry for deeper orders). */
  const OrderParams& order(int o) const;
};

/**
 * Throws sylva::Error "<where>.<field>: <reason>" for any value out of range: probabilities outside [0, 1] or
 * summing over 1, segment counts min > max or negative, maxOrder/maxDepth/maxPieces outside their limits
 * (≤ 16, ≤ 64, ≤ 200,000), non-finite numbers.
 */
void validate(const Species& species, const std::string& where);

/**
 * The leaf colour at `autumn` ∈ [0, 1]: 0 the summer leafColour, 1 the autumnColour, linear in between (the
 * season's turn; values outside are clamped).
 */
glm::vec3 seasonalLeafColour(const Species& species, float autumn);

/**
 * The share of leaf clusters a species carries after `leafFall` ∈ [0, 1] of the season's leaves have fallen:
 * leafDensity × (1 − leafFall) for deciduous species, leafDensity for evergreen ones (values outside are
 * clamped).
 */
float seasonalLeafDensity(const Species& species, float leafFall);

/** Valid values of Species::bark: oak, birch, pine, willow, procedural. */
const std::vector<std::string>& barkPhotoNames();

/** Names of the built-in presets (almond, quaking-aspen, black-tupelo, weeping-willow, …). */
std::vector<std::string> speciesPresetNames();
/** The presets of real species (speciesPresetNames() without the paper's two rules). */
std::vector<std::string> realSpeciesPresetNames();
/** A built-in preset; throws sylva::Error "unknown species '<name>' (known: …)". */
Species speciesPreset(const std::string& name);
/** A preset name or a species JSON file path (anything with a '/' or ending in .json). */
Species resolveSpecies(const std::string& nameOrPath);

/** Species JSON (version 1); strict: unknown fields and bad values name the file and field. */
nlohmann::json toJson(const Species& species);
/** A species from its JSON; errors name `where` and the field. */
Species speciesFromJson(const nlohmann::json& json, const std::string& where);
/** Reads a species file; errors name the file and field. */
Species loadSpecies(const std::filesystem::path& path);

/** "alternate", "uniform-random" or "grammar". */
const char* ruleName(AssemblyRule rule);

} // namespace sylva::trees
