#include <sylva/trees/Measure.hpp>

#include <sylva/trees/Export.hpp>
#include <sylva/trees/Foliage.hpp>
#include <sylva/trees/Skeleton.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <type_traits>

namespace sylva::trees {

namespace {

constexpr int kDirections = 16;
/** Tessellation level of the measured mesh: fine enough that its surfaces follow the pieces within 1 %. */
constexpr int kMeasureLevel = 4;

/** Horizontal extents along kDirections directions over half a turn. */
struct Calipers {
  std::array<float, kDirections> lo;
  std::array<float, kDirections> hi;
  Calipers() {
    lo.fill(std::numeric_limits<float>::infinity());
    hi.fill(-std::numeric_limits<float>::infinity());
  }
  void add(const glm::vec3& p) {
    for (int k = 0; k < kDirections; ++k) {
      const double a = std::numbers::pi * k / kDirections;
      const float t = p.x * static_cast<float>(std::cos(a)) + p.z * static_cast<float>(std::sin(a));
      lo[k] = std::min(lo[k], t);
      hi[k] = std::max(hi[k], t);
    }
  }
  /** The widest extent (0 when nothing was added). */
  float width() const {
    float w = 0.0f;
    for (int k = 0; k < kDirections; ++k) {
      w = std::max(w, hi[k] - lo[k]);
    }
    return w;
  }
};

} // namespace

TreeMeasures measureTree(const PieceSet& pieces, const TreeTopology& tree, const Species& species,
                         std::span<const glm::vec2> pose) {
  TreeExportOptions options;
  options.levels = {kMeasureLevel};
  options.pose.assign(pose.begin(), pose.end());
  const TreeMesh mesh = buildTreeMesh(pieces, tree, species, options, "tree measure");
  const std::vector<glm::vec3>& positions = mesh.lods.front().positions;
  const std::vector<glm::mat4>& frames = mesh.jointFrames;

  TreeMeasures m;
  m.pieces = tree.nodes.size();
  m.trunkRadius = glm::length(glm::vec3(frames[0][0]));
  const float base = frames[0][3].y;
  for (const glm::vec3& p : positions) {
    m.height = std::max(m.height, p.y - base);
  }
  m.crownBase = m.height;
  for (const TreeNode& node : tree.nodes) {
    const Piece& piece = pieces[static_cast<std::size_t>(node.piece)];
    const glm::mat4& attach = frames[node.rootJoint];
    if (node.parent >= 0 && node.order >= 1 && tree.nodes[static_cast<std::size_t>(node.parent)].order == 0) {
      m.crownBase = std::min(m.crownBase, attach[3].y - base);
    }
    if (piece.leafRims() == 0) {
      ++m.tips;
      // The bone of a joint frame is its local +y: the way the cap grows from where it attaches.
      if (glm::normalize(glm::vec3(attach[1])).y < 0.0f) {
        ++m.droopingTips;
      }
    }
  }
  m.crownBase = std::max(m.crownBase, 0.0f);
  Calipers crown;
  std::array<Calipers, kProfileBins> bands;
  for (const glm::vec3& p : positions) {
    const float y = p.y - base;
    if (y >= m.crownBase) {
      crown.add(p);
    }
    if (m.height > 0.0f) {
      const int bin = std::clamp(static_cast<int>(y / m.height * kProfileBins), 0, kProfileBins - 1);
      bands[static_cast<std::size_t>(bin)].add(p);
    }
  }
  m.crownWidth = crown.width();
  // The leaves: a sphere around the root joint of every piece that carries a leaf cluster.
  const float cluster = species.leafCluster > 0.0f ? species.leafCluster : 0.6f;
  for (const TreeNode& node : tree.nodes) {
    if (!carriesLeaves(pieces[static_cast<std::size_t>(node.piece)], node, species)) {
      continue;
    }
    const glm::vec3 c(frames[node.rootJoint][3]);
    for (int k = 0; k < kDirections; ++k) {
      const double a = std::numbers::pi * k / kDirections;
      const glm::vec3 d(static_cast<float>(std::cos(a)), 0.0f, static_cast<float>(std::sin(a)));
      crown.add(c + cluster * d);
      crown.add(c - cluster * d);
    }
  }
  m.leafyWidth = crown.width();
  for (int b = 0; b < kProfileBins; ++b) {
    m.profile[static_cast<std::size_t>(b)] = bands[static_cast<std::size_t>(b)].width();
  }
  m.slenderness = m.trunkRadius > 0.0f ? m.height / m.trunkRadius : 0.0f;
  m.crownHeight = m.height - m.crownBase;
  m.crownRatio = m.crownHeight > 0.0f ? m.crownWidth / m.crownHeight : 0.0f;
  m.droopingFraction = m.tips > 0 ? static_cast<float>(m.droopingTips) / static_cast<float>(m.tips) : 0.0f;
  m.spread = m.height > 0.0f ? m.leafyWidth / m.height : 0.0f;
  return m;
}

TreeMeasures measureSpecies(const PieceSet& pieces, const Species& species, std::uint64_t seed) {
  const TreeTopology tree = generateTree(pieces, species, seed);
  const std::vector<glm::vec2> pose = randomPose(tree, species, seed);
  return measureTree(pieces, tree, species, pose);
}

namespace {

/** Applies `f(field of out, field of each tree…)` to every measure. */
template <typename F> void eachField(TreeMeasures& out, const TreeMeasures& t, F&& f) {
  f(out.height, t.height);
  f(out.trunkRadius, t.trunkRadius);
  f(out.slenderness, t.slenderness);
  f(out.crownBase, t.crownBase);
  f(out.crownHeight, t.crownHeight);
  f(out.crownWidth, t.crownWidth);
  f(out.crownRatio, t.crownRatio);
  f(out.leafyWidth, t.leafyWidth);
  f(out.spread, t.spread);
  f(out.droopingFraction, t.droopingFraction);
  for (int b = 0; b < kProfileBins; ++b) {
    f(out.profile[static_cast<std::size_t>(b)], t.profile[static_cast<std::size_t>(b)]);
  }
  f(out.pieces, t.pieces);
  f(out.tips, t.tips);
  f(out.droopingTips, t.droopingTips);
}

} // namespace

MeasureSummary summarise(std::vector<TreeMeasures> trees) {
  MeasureSummary s;
  s.trees = std::move(trees);
  if (s.trees.empty()) {
    return s;
  }
  s.min = s.trees.front();
  s.max = s.trees.front();
  TreeMeasures sum{};
  for (const TreeMeasures& t : s.trees) {
    eachField(s.min, t, [](auto& a, auto b) { a = std::min(a, b); });
    eachField(s.max, t, [](auto& a, auto b) { a = std::max(a, b); });
    eachField(sum, t, [](auto& a, auto b) { a += b; });
  }
  const std::size_t n = s.trees.size();
  s.mean = sum;
  eachField(s.mean, sum, [n](auto& a, auto b) {
    if constexpr (std::is_integral_v<std::decay_t<decltype(a)>>) {
      a = (b + n / 2) / n; // rounded
    } else {
      a = b / static_cast<float>(n);
    }
  });
  return s;
}

namespace {

std::string row(const std::string& label, const TreeMeasures& m) {
  return fmt::format(
      "{:<6} {:6.2f} m {:6.3f} m {:6.1f} {:6.2f} m {:6.2f} m {:6.2f} m {:5.2f} {:6.2f} {:5} {:5.1f} % {:6}\n",
      label, m.height, m.trunkRadius, m.slenderness, m.crownBase, m.crownWidth, m.crownHeight, m.crownRatio,
      m.spread, m.tips, 100.0f * m.droopingFraction, m.pieces);
}

nlohmann::json toJson(const TreeMeasures& m) {
  return {{"height", m.height},
          {"trunkRadius", m.trunkRadius},
          {"slenderness", m.slenderness},
          {"crownBase", m.crownBase},
          {"crownWidth", m.crownWidth},
          {"crownHeight", m.crownHeight},
          {"crownRatio", m.crownRatio},
          {"leafyWidth", m.leafyWidth},
          {"spread", m.spread},
          {"profile", m.profile},
          {"tips", m.tips},
          {"droopingTips", m.droopingTips},
          {"droopingFraction", m.droopingFraction},
          {"pieces", m.pieces}};
}

} // namespace

std::string describeMeasures(const std::string& species, std::uint64_t firstSeed, const MeasureSummary& s) {
  std::string text = fmt::format("{}: {} tree{} (metres; woody parts; spread: leafy crown width / height)\n",
                                 species, s.trees.size(), s.trees.size() == 1 ? "" : "s");
  text += fmt::format("{:<6} {:>8} {:>8} {:>6} {:>8} {:>8} {:>8} {:>5} {:>6} {:>5} {:>7} {:>6}\n", "seed",
                      "height", "trunk r", "H/r", "crown@", "width", "crown h", "W/H", "spread", "tips",
                      "droop", "pieces");
  for (std::size_t i = 0; i < s.trees.size(); ++i) {
    text += row(std::to_string(firstSeed + i), s.trees[i]);
  }
  if (s.trees.size() > 1) {
    text += row("min", s.min) + row("mean", s.mean) + row("max", s.max);
  }
  const TreeMeasures& m = s.trees.size() > 1 ? s.mean : s.trees.front();
  const float widest = *std::max_element(m.profile.begin(), m.profile.end());
  text += "silhouette width, base to apex (share of the widest band):";
  for (float w : m.profile) {
    text += fmt::format(" {:.2f}", widest > 0.0f ? w / widest : 0.0f);
  }
  text += "\n";
  if (const std::optional<SpeciesTargets> targets = speciesTargets(species)) {
    std::size_t inside = 0;
    std::string firstMiss;
    for (std::size_t i = 0; i < s.trees.size(); ++i) {
      const std::string miss = targetMisses(s.trees[i], *targets);
      inside += miss.empty() ? 1 : 0;
      if (!miss.empty() && firstMiss.empty()) {
        firstMiss = fmt::format(" (seed {}: {})", firstSeed + i, miss);
      }
    }
    text += fmt::format("species targets (docs/trees.md): {} of {} trees inside{}\n", inside, s.trees.size(),
                        firstMiss);
  }
  return text;
}

std::optional<SpeciesTargets> speciesTargets(const std::string& name) {
  // {height m, slenderness, spread, crown base share, drooping share}; references in docs/trees.md.
  static const std::map<std::string, SpeciesTargets> table{
      {"almond", {{4, 10}, {25, 60}, {0.8f, 1.8f}, {0.15f, 0.45f}, {0.1f, 0.7f}}},
      {"apple", {{2, 9}, {18, 50}, {0.9f, 2.0f}, {0.15f, 0.5f}, {0.2f, 0.9f}}},
      {"black-tupelo", {{12, 30}, {50, 120}, {0.25f, 0.7f}, {0.15f, 0.6f}, {0.2f, 0.8f}}},
      {"california-black-oak", {{9, 25}, {30, 80}, {0.8f, 1.6f}, {0.15f, 0.45f}, {0.2f, 0.8f}}},
      {"european-larch", {{20, 45}, {50, 120}, {0.25f, 0.6f}, {0.05f, 0.35f}, {0.3f, 0.9f}}},
      {"norway-spruce", {{20, 45}, {50, 130}, {0.25f, 0.55f}, {0.0f, 0.25f}, {0.4f, 1.0f}}},
      {"lombardy-poplar", {{15, 30}, {35, 100}, {0.1f, 0.3f}, {0.05f, 0.3f}, {0.0f, 0.1f}}},
      {"oak-sapling", {{2.5f, 4.5f}, {110, 260}, {0.3f, 1.1f}, {0.3f, 0.65f}, {0.0f, 0.7f}}},
      {"quaking-aspen", {{12, 20}, {50, 120}, {0.25f, 0.7f}, {0.15f, 0.6f}, {0.1f, 0.7f}}},
      {"sassafras", {{6, 18}, {25, 80}, {0.4f, 1.5f}, {0.15f, 0.6f}, {0.0f, 0.6f}}},
      {"silver-birch", {{15, 25}, {50, 120}, {0.25f, 0.6f}, {0.15f, 0.6f}, {0.6f, 1.0f}}},
      {"weeping-willow", {{8, 18}, {30, 80}, {0.8f, 1.8f}, {0.1f, 0.45f}, {0.8f, 1.0f}}},
  };
  const auto it = table.find(name);
  return it == table.end() ? std::nullopt : std::optional<SpeciesTargets>(it->second);
}

std::string targetMisses(const TreeMeasures& m, const SpeciesTargets& t) {
  std::string out;
  auto check = [&](const char* what, float v, const MeasureRange& r) {
    if (!r.contains(v)) {
      out += fmt::format("{}{} {:.2f} outside [{}, {}]", out.empty() ? "" : "; ", what, v, r.lo, r.hi);
    }
  };
  check("height", m.height, t.height);
  check("slenderness", m.slenderness, t.slenderness);
  check("spread", m.spread, t.spread);
  check("crown base", m.height > 0.0f ? m.crownBase / m.height : 0.0f, t.crownBase);
  check("drooping", m.droopingFraction, t.drooping);
  return out;
}

nlohmann::json describeMeasuresJson(const std::string& species, std::uint64_t firstSeed,
                                    const MeasureSummary& s) {
  nlohmann::json trees = nlohmann::json::array();
  for (std::size_t i = 0; i < s.trees.size(); ++i) {
    nlohmann::json t = toJson(s.trees[i]);
    t["seed"] = firstSeed + i;
    trees.push_back(std::move(t));
  }
  return {{"species", species},
          {"trees", trees},
          {"min", toJson(s.min)},
          {"mean", toJson(s.mean)},
          {"max", toJson(s.max)}};
}

} // namespace sylva::trees
