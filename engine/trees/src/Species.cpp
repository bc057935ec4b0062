#include <sylva/trees/Species.hpp>
#include "internal/Finite.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <algorithm>
#include <map>

namespace sylva::trees {
namespace {

using internal::finite;

OrderParams order(int minSegments, int maxSegments, float fork, float trifurcation, float sideBranch,
                  float asymmetry, float bend, float droop, float stretch = 1.0f, float sideRadius = 0.0f) {
  return OrderParams{minSegments, maxSegments, fork,  trifurcation, sideBranch,
                     asymmetry,   bend,        droop, stretch,      sideRadius};
}

Species base(const std::string& name) {
  Species s;
  s.name = name;
  return s;
}

// Presets. The paper's almond (co-dominant Y forks) and its two rules; the others follow the shapes of
// Weber & Penn's published tables (1995, Table 1 and their examples): excurrent trunks with many side
// branches (aspen, tupelo, poplar, larch, birch), decurrent crowns that fork (oak, sassafras, apple, willow),
// hanging twigs (willow, birch, by droop). Their per-level counts and angles map onto our pieces as segment
// counts, split probabilities and bends; segment lengths (stretch) and side-branch radii (the pipe model) set
// proportions. docs/trees.md "Species targets" gives the measured shape each preset is tuned and tested to.
const std::map<std::string, std::function<Species()>>& presets() {
  static const std::map<std::string, std::function<Species()>> table{
      {"almond",
       [] {
         Species s = base("almond");
         s.maxOrder = 4;
         s.trunkRadius = 0.14f;
         s.minRadius = 0.02f;
         s.orders = {order(1, 2, 0.85f, 0.05f, 0.0f, 0.1f, 0.12f, 0.0f, 1.8f),
                     order(1, 2, 0.8f, 0.0f, 0.1f, 0.15f, 0.15f, 0.02f, 4.0f, 0.4f),
                     order(1, 2, 0.7f, 0.0f, 0.2f, 0.2f, 0.18f, 0.04f, 3.5f, 0.45f),
                     order(1, 2, 0.4f, 0.0f, 0.4f, 0.2f, 0.18f, 0.04f, 3.0f, 0.5f)};
         s.leafColour = {0.27f, 0.45f, 0.16f};
         s.autumnColour = {0.62f, 0.5f, 0.16f};
         s.leafCluster = 1.1f;
         return s;
       }},
      {"norway-spruce",
       [] {
         Species s = base("norway-spruce");
         s.maxOrder = 2;
         s.maxDepth = 64;
         s.trunkRadius = 0.35f;
         s.minRadius = 0.012f;
         // A straight leader with whorls of three branches and a long internode between them; the branches
         // reach out nearly level, their shoots hang (the comb form), needles all along.
         s.orders = {order(1, 1, 0.0f, 0.0f, 1.0f, 0.0f, 0.015f, 0.0f, 2.7f, 0.22f),
                     order(1, 3, 0.0f, 0.0f, 0.7f, 0.0f, 0.05f, 0.1f, 4.0f, 0.5f),
                     order(1, 2, 0.0f, 0.0f, 0.0f, 0.0f, 0.08f, 0.25f, 3.0f, 0.5f)};
         s.orders[0].whorl = 3;
         s.foliage = FoliageKind::Needles;
         s.barkColour = {0.3f, 0.2f, 0.15f};
         s.leafColour = {0.1f, 0.22f, 0.09f};
         // Evergreen: the needles keep their colour through autumn and stay through winter.
         s.autumnColour = s.leafColour;
         s.evergreen = true;
         s.leafCluster = 0.7f;
         s.woodDensity = 450.0f;
         s.youngModulus = 1.0e10f;
         return s;
       }},
      {"paper-alternate",
       [] {
         Species s = base("paper-alternate");
         s.rule = AssemblyRule::Alternate;
         s.maxDepth = 9;
         s.orders = {order(1, 1, 0, 0, 0, 0, 0.1f, 0)};
         return s;
       }},
      {"paper-random",
       [] {
         Species s = base("paper-random");
         s.rule = AssemblyRule::UniformRandom;
         s.maxDepth = 9;
         s.orders = {order(1, 1, 0, 0, 0, 0, 0.1f, 0)};
         return s;
       }},
      {"quaking-aspen",
       [] {
         Species s = base("quaking-aspen");
         s.maxOrder = 3;
         s.trunkRadius = 0.18f;
         s.minRadius = 0.015f;
         s.orders = {order(2, 14, 0.0f, 0.0f, 0.8f, 0.0f, 0.05f, 0.0f, 3.0f, 0.3f),
                     order(1, 3, 0.35f, 0.0f, 0.45f, 0.2f, 0.15f, 0.05f, 4.0f, 0.45f),
                     order(1, 2, 0.5f, 0.0f, 0.3f, 0.2f, 0.2f, 0.05f, 3.5f, 0.5f)};
         s.barkColour = {0.62f, 0.6f, 0.52f};
         s.leafColour = {0.38f, 0.52f, 0.17f};
         s.autumnColour = {0.85f, 0.66f, 0.1f};
         s.leafCluster = 0.9f;
         return s;
       }},
      {"black-tupelo",
       [] {
         Species s = base("black-tupelo");
         s.maxOrder = 3;
         s.trunkRadius = 0.2f;
         s.minRadius = 0.015f;
         s.orders = {order(2, 14, 0.0f, 0.0f, 0.8f, 0.0f, 0.05f, 0.0f, 3.0f, 0.3f),
                     order(1, 3, 0.3f, 0.0f, 0.5f, 0.25f, 0.12f, 0.12f, 4.5f, 0.45f),
                     order(1, 2, 0.4f, 0.0f, 0.3f, 0.2f, 0.2f, 0.1f, 3.5f, 0.5f)};
         s.leafColour = {0.2f, 0.38f, 0.12f};
         s.autumnColour = {0.66f, 0.12f, 0.08f};
         s.leafCluster = 0.9f;
         return s;
       }},
      {"weeping-willow",
       [] {
         Species s = base("weeping-willow");
         s.maxOrder = 3;
         s.trunkRadius = 0.3f;
         s.minRadius = 0.01f;
         // Arching limbs that branch along their length; from them, long thin shoots that hang straight down,
         // leafy all along (leafOrder 3).
         s.orders = {order(1, 2, 0.7f, 0.2f, 0.1f, 0.1f, 0.08f, 0.0f, 2.0f),
                     order(1, 3, 0.3f, 0.0f, 0.6f, 0.2f, 0.1f, -0.05f, 3.0f, 0.45f),
                     order(1, 4, 0.1f, 0.0f, 0.8f, 0.2f, 0.12f, 0.12f, 4.0f, 0.4f),
                     order(3, 4, 0.0f, 0.0f, 0.0f, 0.2f, 0.05f, 0.5f, 10.0f, 0.5f)};
         s.barkColour = {0.3f, 0.26f, 0.2f};
         s.leafColour = {0.45f, 0.55f, 0.2f};
         s.autumnColour = {0.8f, 0.68f, 0.14f};
         s.leafCluster = 0.7f;
         s.leafOrder = 3;
         s.youngModulus = 6e9f;
         return s;
       }},
      {"california-black-oak",
       [] {
         Species s = base("california-black-oak");
         s.maxOrder = 5;
         s.trunkRadius = 0.3f;
         s.minRadius = 0.025f;
         s.orders = {order(1, 2, 0.7f, 0.2f, 0.1f, 0.25f, 0.1f, 0.0f, 3.0f),
                     order(1, 2, 0.5f, 0.1f, 0.3f, 0.3f, 0.25f, 0.04f, 5.5f, 0.35f),
                     order(1, 2, 0.4f, 0.0f, 0.4f, 0.3f, 0.3f, 0.08f, 4.5f, 0.4f),
                     order(1, 2, 0.4f, 0.0f, 0.4f, 0.3f, 0.3f, 0.08f, 3.0f, 0.45f)};
         s.barkColour = {0.22f, 0.2f, 0.18f};
         s.leafColour = {0.2f, 0.33f, 0.12f};
         s.autumnColour = {0.55f, 0.38f, 0.12f};
         s.leafCluster = 2.0f;
         s.youngModulus = 11e9f;
         s.woodDensity = 850.0f;
         return s;
       }},
      {"oak-sapling",
       [] {
         Species s = base("oak-sapling");
         s.maxOrder = 3;
         s.trunkRadius = 0.02f;
         s.minRadius = 0.15f;
         // A young oak as nurseries sell it (a standard): a clear, straight stem about half its height, then
         // a small crown of a few ascending branches.
         s.orders = {order(2, 3, 0.0f, 0.0f, 0.7f, 0.0f, 0.03f, 0.0f, 8.0f, 0.4f),
                     order(1, 3, 0.3f, 0.0f, 0.4f, 0.2f, 0.15f, 0.02f, 10.0f, 0.5f),
                     order(1, 2, 0.2f, 0.0f, 0.4f, 0.2f, 0.2f, 0.04f, 5.0f, 0.5f)};
         s.barkColour = {0.36f, 0.33f, 0.29f};
         s.leafColour = {0.22f, 0.38f, 0.13f};
         s.autumnColour = {0.58f, 0.4f, 0.13f};
         s.leafCluster = 0.35f;
         s.youngModulus = 11e9f;
         s.woodDensity = 850.0f;
         return s;
       }},
      {"sassafras",
       [] {
         Species s = base("sassafras");
         s.maxOrder = 4;
         s.trunkRadius = 0.25f;
         s.minRadius = 0.015f;
         s.orders = {order(1, 3, 0.1f, 0.1f, 0.6f, 0.1f, 0.08f, 0.0f, 2.0f, 0.35f),
                     order(1, 3, 0.5f, 0.1f, 0.3f, 0.2f, 0.2f, 0.05f, 3.0f, 0.4f),
                     order(1, 2, 0.5f, 0.0f, 0.2f, 0.1f, 0.2f, 0.0f, 3.0f, 0.45f),
                     order(1, 2, 0.3f, 0.0f, 0.4f, 0.1f, 0.2f, 0.0f, 3.0f, 0.5f)};
         s.leafColour = {0.3f, 0.48f, 0.16f};
         s.autumnColour = {0.82f, 0.32f, 0.08f};
         s.leafCluster = 0.9f;
         return s;
       }},
      {"lombardy-poplar",
       [] {
         Species s = base("lombardy-poplar");
         s.maxOrder = 2;
         s.trunkRadius = 0.4f;
         s.minRadius = 0.02f;
         // One straight leader to the top with many thin, short, steeply rising side branches close along it.
         s.orders = {order(1, 30, 0.0f, 0.0f, 0.95f, 0.0f, 0.02f, -0.12f, 1.3f, 0.22f),
                     order(1, 3, 0.2f, 0.0f, 0.4f, 0.1f, 0.04f, -0.15f, 1.3f, 0.5f)};
         s.leafColour = {0.24f, 0.44f, 0.15f};
         s.autumnColour = {0.78f, 0.66f, 0.16f};
         s.leafCluster = 0.75f;
         return s;
       }},
      {"european-larch",
       [] {
         Species s = base("european-larch");
         s.maxOrder = 2;
         s.trunkRadius = 0.3f;
         s.minRadius = 0.02f;
         // A leader to the top; tiers of thin side branches, longest low down (the trunk thins upwards and
         // the branches with it), twigs hanging from them.
         s.orders = {order(1, 30, 0.0f, 0.0f, 0.97f, 0.0f, 0.02f, 0.0f, 2.5f, 0.25f),
                     order(1, 4, 0.0f, 0.0f, 0.6f, 0.1f, 0.06f, 0.12f, 5.0f, 0.5f),
                     order(0, 1, 0.2f, 0.0f, 0.3f, 0.1f, 0.1f, 0.15f, 3.0f, 0.5f)};
         s.leafColour = {0.33f, 0.47f, 0.2f};
         s.autumnColour = {0.8f, 0.58f, 0.12f};
         s.leafCluster = 1.0f;
         // Soft needles in tufts on the shoots (a deciduous conifer: they turn golden in autumn).
         s.foliage = FoliageKind::Needles;
         return s;
       }},
      {"silver-birch",
       [] {
         Species s = base("silver-birch");
         s.maxOrder = 3;
         s.trunkRadius = 0.2f;
         s.minRadius = 0.012f;
         // A slender leader, ascending branches, and fine twigs hanging from them, leafy along their length.
         s.orders = {order(2, 14, 0.0f, 0.0f, 0.75f, 0.0f, 0.04f, 0.0f, 3.0f, 0.3f),
                     order(1, 3, 0.3f, 0.0f, 0.5f, 0.2f, 0.1f, 0.08f, 4.5f, 0.45f),
                     order(1, 3, 0.2f, 0.0f, 0.5f, 0.2f, 0.12f, 0.25f, 4.0f, 0.5f),
                     order(2, 2, 0.0f, 0.0f, 0.0f, 0.2f, 0.05f, 0.45f, 8.0f, 0.5f)};
         s.barkColour = {0.8f, 0.78f, 0.72f};
         s.leafColour = {0.35f, 0.5f, 0.18f};
         s.autumnColour = {0.86f, 0.7f, 0.16f};
         s.leafCluster = 0.8f;
         s.leafOrder = 3;
         return s;
       }},
      {"apple",
       [] {
         Species s = base("apple");
         s.maxOrder = 4;
         s.trunkRadius = 0.15f;
         s.minRadius = 0.02f;
         s.orders = {order(1, 2, 0.6f, 0.3f, 0.1f, 0.2f, 0.15f, 0.0f, 1.8f),
                     order(1, 2, 0.5f, 0.1f, 0.3f, 0.3f, 0.25f, 0.1f, 3.0f, 0.4f),
                     order(1, 2, 0.4f, 0.0f, 0.3f, 0.3f, 0.25f, 0.12f, 3.0f, 0.45f),
                     order(1, 2, 0.4f, 0.0f, 0.4f, 0.3f, 0.25f, 0.12f, 2.5f, 0.5f)};
         s.leafColour = {0.25f, 0.42f, 0.14f};
         s.autumnColour = {0.6f, 0.45f, 0.14f};
         s.leafCluster = 1.1f;
         return s;
       }},
  };
  return table;
}

/** Fails `<where>/<field>: <reason>` where `where` reads `<file>: <JSON pointer of the object>`. */
void check(bool ok, const std::string& where, const char* field, const std::string& reason) {
  if (!ok) {
    fail("{}/{}: {}", where, field, reason);
  }
}

glm::vec3 colour(const JsonNode& node) {
  node.arrayOf(3, "r, g, b");
  return glm::vec3(static_cast<float>(node[std::size_t{0}].number(0, 1)),
                   static_cast<float>(node[std::size_t{1}].number(0, 1)),
                   static_cast<float>(node[std::size_t{2}].number(0, 1)));
}

} // namespace

const OrderParams& Species::order(int o) const {
  return orders[static_cast<std::size_t>(std::clamp(o, 0, static_cast<int>(orders.size()) - 1))];
}

const char* ruleName(AssemblyRule rule) {
  switch (rule) {
  case AssemblyRule::Alternate:
    return "alternate";
  case AssemblyRule::UniformRandom:
    return "uniform-random";
  case AssemblyRule::Grammar:
    return "grammar";
  }
  return "grammar";
}

void validate(const Species& s, const std::string& file) {
  const std::string where = file + ": ";
  check(!s.name.empty(), where, "name", "must not be empty");
  check(s.maxOrder >= 0 && s.maxOrder <= 16, where, "maxOrder", "must be in [0, 16]");
  check(s.maxDepth >= 1 && s.maxDepth <= 64, where, "maxDepth", "must be in [1, 64]");
  check(s.maxPieces >= 2 && s.maxPieces <= 200000, where, "maxPieces", "must be in [2, 200000]");
  check(std::isfinite(s.minRadius) && s.minRadius > 0.0f && s.minRadius < 1.0f, where, "minRadius",
        "must be in (0, 1)");
  check(std::isfinite(s.trunkRadius) && s.trunkRadius > 0.001f && s.trunkRadius <= 10.0f, where,
        "trunkRadius", "must be in (0.001, 10] metres");
  check(std::isfinite(s.sizeVariation) && s.sizeVariation >= 0.0f && s.sizeVariation < 1.0f, where,
        "sizeVariation", "must be in [0, 1)");
  check(!s.orders.empty() && s.orders.size() <= 17, where, "orders", "needs 1 … 17 entries");
  check(finite(s.barkColour) && finite(s.leafColour) && finite(s.autumnColour), where, "colours",
        "must be finite");
  check(std::isfinite(s.leafCluster) && s.leafCluster >= 0.0f && s.leafCluster <= 10.0f, where, "leafCluster",
        "must be in [0, 10] metres");
  check(s.leafOrder >= 0 && s.leafOrder <= 16, where, "leafOrder", "must be in [0, 16]");
  check(std::isfinite(s.leafDensity) && s.leafDensity >= 0.0f && s.leafDensity <= 1.0f, where, "leafDensity",
        "must be in [0, 1]");
  check(std::find(barkPhotoNames().begin(), barkPhotoNames().end(), s.bark) != barkPhotoNames().end(), where,
        "bark", "must be one of oak, birch, pine, willow, procedural");
  check(std::isfinite(s.youngModulus) && s.youngModulus >= 1e6f && s.youngModulus <= 1e12f, where,
        "youngModulus", "must be in [1e6, 1e12] Pa");
  check(std::isfinite(s.woodDensity) && s.woodDensity >= 50.0f && s.woodDensity <= 2000.0f, where,
        "woodDensity", "must be in [50, 2000] kg/m³");
  check(std::isfinite(s.damping) && s.damping > 0.0f && s.damping <= 1.0f, where, "damping",
        "must be in (0, 1]");
  for (std::size_t i = 0; i < s.orders.size(); ++i) {
    const OrderParams& o = s.orders[i];
    const std::string w = fmt::format("{}: /orders/{}", file, i);
    check(o.minSegments >= 0 && o.minSegments <= 64, w, "minSegments", "must be in [0, 64]");
    check(o.maxSegments >= o.minSegments && o.maxSegments <= 64, w, "maxSegments",
          "must be in [minSegments, 64]");
    for (auto [v, name] : {std::pair{o.fork, "fork"},
                           {o.trifurcation, "trifurcation"},
                           {o.sideBranch, "sideBranch"},
                           {o.asymmetry, "asymmetry"}}) {
      check(std::isfinite(v) && v >= 0.0f && v <= 1.0f, w, name, "must be in [0, 1]");
    }
    check(o.fork + o.trifurcation + o.sideBranch <= 1.0f + 1e-5f, w, "fork",
          "fork + trifurcation + sideBranch must be ≤ 1");
    check(o.asymmetry < 0.9f, w, "asymmetry", "must be < 0.9");
    check(std::isfinite(o.bend) && o.bend >= 0.0f && o.bend <= 0.5f, w, "bend",
          "must be in [0, 0.5] radians");
    check(std::isfinite(o.droop) && std::abs(o.droop) <= 0.5f, w, "droop", "must be in [-0.5, 0.5] radians");
    check(std::isfinite(o.stretch) && o.stretch >= 0.5f && o.stretch <= 12.0f, w, "stretch",
          "must be in [0.5, 12]");
    check(o.whorl >= 0 && o.whorl <= 6, w, "whorl", "must be in [0, 6]");
    check(o.sideRadius == 0.0f || (o.sideRadius >= 0.05f && o.sideRadius <= 0.95f), w, "sideRadius",
          "must be 0 (the piece's own) or in [0.05, 0.95]");
  }
}

std::vector<std::string> speciesPresetNames() {
  std::vector<std::string> names;
  for (const auto& [name, make] : presets()) {
    names.push_back(name);
  }
  return names;
}

std::vector<std::string> realSpeciesPresetNames() {
  std::vector<std::string> names;
  for (const std::string& name : speciesPresetNames()) {
    if (name.rfind("paper-", 0) != 0) {
      names.push_back(name);
    }
  }
  return names;
}

float seasonalLeafDensity(const Species& species, float leafFall) {
  const float fall = std::isfinite(leafFall) ? std::clamp(leafFall, 0.0f, 1.0f) : 0.0f;
  return species.evergreen ? species.leafDensity : species.leafDensity * (1.0f - fall);
}

glm::vec3 seasonalLeafColour(const Species& species, float autumn) {
  const float t = std::isfinite(autumn) ? std::clamp(autumn, 0.0f, 1.0f) : 0.0f;
  return species.leafColour * (1.0f - t) + species.autumnColour * t; // exact at both ends
}

const std::vector<std::string>& barkPhotoNames() {
  static const std::vector<std::string> kNames{"oak", "birch", "pine", "willow", "procedural"};
  return kNames;
}

Species speciesPreset(const std::string& name) {
  const auto it = presets().find(name);
  if (it == presets().end()) {
    std::string known;
    for (const std::string& n : speciesPresetNames()) {
      known += (known.empty() ? "" : ", ") + n;
    }
    fail("unknown species '{}' (known: {})", name, known);
  }
  Species s = it->second();
  // Bark photos by the look of the real bark: smooth pale (birch, aspen), furrowed (oaks and most), scaly
  // (larch), deeply ridged (willow, poplar).
  static const std::map<std::string, std::string> kBark{
      {"quaking-aspen", "birch"}, {"silver-birch", "birch"},    {"european-larch", "pine"},
      {"norway-spruce", "pine"},  {"weeping-willow", "willow"}, {"lombardy-poplar", "willow"}};
  if (const auto b = kBark.find(name); b != kBark.end()) {
    s.bark = b->second;
  }
  validate(s, "species '" + name + "'");
  return s;
}

Species resolveSpecies(const std::string& nameOrPath) {
  if (nameOrPath.find('/') != std::string::npos || (nameOrPath.size() > 5 && nameOrPath.ends_with(".json"))) {
    return loadSpecies(nameOrPath);
  }
  return speciesPreset(nameOrPath);
}

nlohmann::json toJson(const Species& s) {
  nlohmann::json orders = nlohmann::json::array();
  for (const OrderParams& o : s.orders) {
    orders.push_back({{"minSegments", o.minSegments},
                      {"maxSegments", o.maxSegments},
                      {"fork", o.fork},
                      {"trifurcation", o.trifurcation},
                      {"sideBranch", o.sideBranch},
                      {"asymmetry", o.asymmetry},
                      {"bend", o.bend},
                      {"droop", o.droop},
                      {"stretch", o.stretch},
                      {"sideRadius", o.sideRadius},
                      {"whorl", o.whorl}});
  }
  return {{"version", 1},
          {"name", s.name},
          {"rule", ruleName(s.rule)},
          {"maxOrder", s.maxOrder},
          {"maxDepth", s.maxDepth},
          {"maxPieces", s.maxPieces},
          {"minRadius", s.minRadius},
          {"trunkRadius", s.trunkRadius},
          {"sizeVariation", s.sizeVariation},
          {"orders", orders},
          {"barkColour", {s.barkColour.r, s.barkColour.g, s.barkColour.b}},
          {"leafColour", {s.leafColour.r, s.leafColour.g, s.leafColour.b}},
          {"autumnColour", {s.autumnColour.r, s.autumnColour.g, s.autumnColour.b}},
          {"leafCluster", s.leafCluster},
          {"leafOrder", s.leafOrder},
          {"foliage", s.foliage == FoliageKind::Needles ? "needles" : "broadleaf"},
          {"leafDensity", s.leafDensity},
          {"evergreen", s.evergreen},
          {"bark", s.bark},
          {"youngModulus", s.youngModulus},
          {"woodDensity", s.woodDensity},
          {"damping", s.damping}};
}

Species speciesFromJson(const nlohmann::json& json, const std::string& where) {
  requireJsonVersion(json, 1, where);
  const JsonNode root(json, where, "");
  root.object({"version",      "name",         "rule",          "maxOrder", "maxDepth",    "maxPieces",
               "minRadius",    "trunkRadius",  "sizeVariation", "orders",   "barkColour",  "leafColour",
               "autumnColour", "leafCluster",  "leafOrder",     "foliage",  "leafDensity", "evergreen",
               "bark",         "youngModulus", "woodDensity",   "damping"});
  Species s;
  s.name = root["name"].string();
  if (root.has("rule")) {
    const std::string rule = root["rule"].choice({"alternate", "uniform-random", "grammar"});
    s.rule = rule == "alternate"        ? AssemblyRule::Alternate
             : rule == "uniform-random" ? AssemblyRule::UniformRandom
                                        : AssemblyRule::Grammar;
  }
  if (root.has("maxOrder"))
    s.maxOrder = root["maxOrder"].integer(0, 16);
  if (root.has("maxDepth"))
    s.maxDepth = root["maxDepth"].integer(1, 64);
  if (root.has("maxPieces"))
    s.maxPieces = root["maxPieces"].integer(2, 200000);
  if (root.has("minRadius"))
    s.minRadius = static_cast<float>(root["minRadius"].number(1e-4, 0.99));
  if (root.has("trunkRadius"))
    s.trunkRadius = static_cast<float>(root["trunkRadius"].number(0.002, 10));
  if (root.has("sizeVariation"))
    s.sizeVariation = static_cast<float>(root["sizeVariation"].number(0, 0.99));
  if (root.has("barkColour"))
    s.barkColour = colour(root["barkColour"]);
  if (root.has("leafColour"))
    s.leafColour = colour(root["leafColour"]);
  if (root.has("autumnColour"))
    s.autumnColour = colour(root["autumnColour"]);
  if (root.has("leafCluster"))
    s.leafCluster = static_cast<float>(root["leafCluster"].number(0, 10));
  if (root.has("leafOrder"))
    s.leafOrder = root["leafOrder"].integer(0, 16);
  if (root.has("leafDensity"))
    s.leafDensity = static_cast<float>(root["leafDensity"].number(0, 1));
  if (root.has("evergreen"))
    s.evergreen = root["evergreen"].boolean();
  if (root.has("foliage"))
    s.foliage = root["foliage"].choice({"broadleaf", "needles"}) == "needles" ? FoliageKind::Needles
                                                                              : FoliageKind::Broadleaf;
  if (root.has("bark"))
    s.bark = root["bark"].choice({"oak", "birch", "pine", "willow", "procedural"});
  if (root.has("youngModulus"))
    s.youngModulus = static_cast<float>(root["youngModulus"].number(1e6, 1e12));
  if (root.has("woodDensity"))
    s.woodDensity = static_cast<float>(root["woodDensity"].number(50, 2000));
  if (root.has("damping"))
    s.damping = static_cast<float>(root["damping"].number(0.001, 1));
  if (root.has("orders")) {
    const JsonNode orders = root["orders"];
    const std::size_t n = orders.array(1, 17);
    s.orders.clear();
    for (std::size_t i = 0; i < n; ++i) {
      const JsonNode o = orders[i];
      o.object({"minSegments", "maxSegments", "fork", "trifurcation", "sideBranch", "asymmetry", "bend",
                "droop", "stretch", "sideRadius", "whorl"});
      OrderParams p;
      if (o.has("minSegments"))
        p.minSegments = o["minSegments"].integer(0, 64);
      if (o.has("maxSegments"))
        p.maxSegments = o["maxSegments"].integer(0, 64);
      if (p.maxSegments < p.minSegments)
        o["maxSegments"].error("must be ≥ minSegments");
      if (o.has("fork"))
        p.fork = static_cast<float>(o["fork"].number(0, 1));
      if (o.has("trifurcation"))
        p.trifurcation = static_cast<float>(o["trifurcation"].number(0, 1));
      if (o.has("sideBranch"))
        p.sideBranch = static_cast<float>(o["sideBranch"].number(0, 1));
      if (p.fork + p.trifurcation + p.sideBranch > 1.0f + 1e-5f) {
        o.error("fork + trifurcation + sideBranch must be ≤ 1");
      }
      if (o.has("asymmetry"))
        p.asymmetry = static_cast<float>(o["asymmetry"].number(0, 0.89));
      if (o.has("bend"))
        p.bend = static_cast<float>(o["bend"].number(0, 0.5));
      if (o.has("droop"))
        p.droop = static_cast<float>(o["droop"].number(-0.5, 0.5));
      if (o.has("stretch"))
        p.stretch = static_cast<float>(o["stretch"].number(0.5, 12));
      if (o.has("whorl"))
        p.whorl = o["whorl"].integer(0, 6);
      if (o.has("sideRadius")) {
        p.sideRadius = static_cast<float>(o["sideRadius"].number(0, 0.95));
        if (p.sideRadius != 0.0f && p.sideRadius < 0.05f)
          o["sideRadius"].error("must be 0 (the piece's own) or in [0.05, 0.95]");
      }
      s.orders.push_back(p);
    }
  }
  validate(s, where);
  return s;
}

Species loadSpecies(const std::filesystem::path& path) {
  return speciesFromJson(loadJsonFile(path), path.filename().string());
}

} // namespace sylva::trees
