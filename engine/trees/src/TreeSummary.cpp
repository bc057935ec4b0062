#include <sylva/trees/TreeSummary.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace sylva::trees {

namespace {

std::size_t pieceVertices(const TreeTopology& tree, const PieceSet& pieces) {
  std::size_t vertices = 0;
  for (const TreeNode& node : tree.nodes) {
    vertices += pieces[static_cast<std::size_t>(node.piece)].vertices.size();
  }
  return vertices;
}

std::string vec3(const glm::vec3& v) {
  auto clean = [](float x) { return std::abs(x) < 5e-7f ? 0.0f : x; };
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", clean(v.x), clean(v.y), clean(v.z));
}

} // namespace

std::string describePiece(const std::string& file, const Piece& piece) {
  std::string text = fmt::format(
      "{}: piece '{}' is valid: {} vertices, {} quads, {} leaf rim{}{}\n",
      std::filesystem::path(file).filename().string(), piece.name, piece.vertices.size(), piece.quads.size(),
      piece.leafRims(), piece.leafRims() == 1 ? "" : "s", piece.bearsFoliage ? ", bears foliage" : "");
  for (std::size_t r = 0; r < piece.rims.size(); ++r) {
    const glm::mat4& f = piece.rims[r].frame;
    const std::string label = r == 0 ? std::string("root rim") : fmt::format("leaf rim {}", r);
    text +=
        fmt::format("{:<11} centre {}, axis {}, radius {:.4g}, corner 0 towards {}\n", label,
                    vec3(glm::vec3(f[3])), vec3(glm::normalize(glm::vec3(f[1]))),
                    static_cast<double>(glm::length(glm::vec3(f[0]))), vec3(glm::normalize(glm::vec3(f[0]))));
  }
  return text;
}

std::optional<Species> presetSpecies(const std::string& name) {
  const std::vector<std::string> names = speciesPresetNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    return std::nullopt;
  }
  return speciesPreset(name);
}

std::string piecesByTypeText(const PieceSet& pieces, const TreeStats& stats) {
  std::string out;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    out += fmt::format("{}{} {}", out.empty() ? "" : ", ", pieces[i].name, stats.piecesByType[i]);
  }
  return out;
}

nlohmann::json describeTreeJson(const std::string& file, const TreeTopology& tree, const PieceSet& pieces,
                                const std::optional<Species>& species) {
  const TreeStats stats = treeStats(pieces, tree);
  nlohmann::json byType = nlohmann::json::object();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    byType[pieces[i].name] = stats.piecesByType[i];
  }
  nlohmann::json out{{"file", file},
                     {"species", tree.species},
                     {"seed", tree.seed},
                     {"pieces", stats.pieces},
                     {"piecesByType", byType},
                     {"joints", stats.joints},
                     {"quads", stats.quads},
                     {"vertices", pieceVertices(tree, pieces)},
                     {"depth", stats.maxDepth},
                     {"order", stats.maxOrder},
                     {"heightRimUnits", stats.height}};
  if (species) {
    out["trunkRadius"] = species->trunkRadius;
    out["heightMetres"] = stats.height * species->trunkRadius;
  }
  return out;
}

std::string describeTree(const std::string& file, const TreeTopology& tree, const PieceSet& pieces,
                         const std::optional<Species>& species) {
  const TreeStats stats = treeStats(pieces, tree);
  std::string text = fmt::format("file     {}\n", file);
  text += fmt::format(
      "species  {}{}, seed {}\n", tree.species,
      species ? fmt::format(" (trunk radius {:g} m)", species->trunkRadius) : " (not a preset)", tree.seed);
  text += fmt::format("pieces   {}: {}\n", stats.pieces, piecesByTypeText(pieces, stats));
  text += fmt::format("joints   {}\n", stats.joints);
  text += fmt::format("quads    {} ({} piece vertices)\n", stats.quads, pieceVertices(tree, pieces));
  text += fmt::format("depth    {} pieces from the root\n", stats.maxDepth);
  text += fmt::format("order    {} (deepest branching order; the trunk is 0)\n", stats.maxOrder);
  if (species) {
    text += fmt::format("height   {:.2f} m ({:.2f} rim units x trunk radius {:g} m)\n",
                        static_cast<double>(stats.height * species->trunkRadius),
                        static_cast<double>(stats.height), static_cast<double>(species->trunkRadius));
  } else {
    text += fmt::format("height   {:.2f} rim units (trunk radii; pass --species for metres)\n",
                        static_cast<double>(stats.height));
  }
  return text;
}

} // namespace sylva::trees
