// `sylva tree <sub>`: trees from interlocking pieces (docs/trees.md). generate grows a tree of a species from
// a seed into a tree JSON file (atomically); info counts what a tree file holds; species lists the presets
// and prints one as JSON to start a species file from; pieces lists the built-in pieces (and exports them as
// OBJ and glTF for artists); import-piece checks an artist's piece file and prints its rims. Every error is
// one line naming the file and field (or option), found before any output is written.
#include "Commands.hpp"
#include "SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/trees/Import.hpp>
#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/Tree.hpp>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

namespace fs = std::filesystem;

std::string vec3(const glm::vec3& v) {
  auto clean = [](float x) { return std::abs(x) < 5e-7f ? 0.0f : x; };
  return fmt::format("({:.4g}, {:.4g}, {:.4g})", clean(v.x), clean(v.y), clean(v.z));
}

/** "I 3, Y 2, …" for the pieces used by a tree. */
std::string countsByType(const trees::PieceSet& pieces, const trees::TreeStats& stats) {
  std::string out;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    out += fmt::format("{}{} {}", out.empty() ? "" : ", ", pieces[i].name, stats.piecesByType[i]);
  }
  return out;
}

/** The species a tree file names, when it is a preset (for metres); nullopt otherwise. */
std::optional<trees::Species> presetOf(const std::string& name) {
  const std::vector<std::string> names = trees::speciesPresetNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    return std::nullopt;
  }
  return trees::speciesPreset(name);
}

void registerGenerate(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "generate",
      "Grow a tree of a species from a seed and write it as tree JSON (the same seed gives the same "
      "file on every machine)");
  struct Options {
    std::string species;
    std::uint64_t seed = 1;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  command
      ->add_option("--species", o->species,
                   "A preset name (see 'sylva tree species') or a species JSON file (a path with '/' or "
                   "ending in .json)")
      ->required();
  command->add_option("--seed", o->seed, "Seed of the tree's random choices")
      ->check(unsignedInteger())
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "Tree JSON file to write (atomically)")->required();
  command->footer("Examples:\n"
                  "  sylva tree generate --species almond --seed 42 -o almond.json\n"
                  "  sylva tree species --show weeping-willow > willow.json   # edit, then:\n"
                  "  sylva tree generate --species ./willow.json --seed 7 -o willow-tree.json\n");
  command->callback([o] {
    if (lowerExtension(o->out) != ".json") {
      fail("-o {}: a tree file must end in .json", o->out);
    }
    const trees::Species species = trees::resolveSpecies(o->species);
    const trees::PieceSet pieces = trees::standardPieces();
    const trees::TreeTopology tree = trees::generateTree(pieces, species, o->seed);
    trees::validate(tree, pieces, o->out);
    trees::saveTree(o->out, tree, pieces);
    const trees::TreeStats stats = trees::treeStats(pieces, tree);
    std::printf("%s\n", o->out.c_str());
    std::printf("%s, seed %llu: %zu pieces (%s), %zu joints, depth %d, height %.2f m\n", species.name.c_str(),
                static_cast<unsigned long long>(o->seed), stats.pieces, countsByType(pieces, stats).c_str(),
                stats.joints, stats.maxDepth, static_cast<double>(stats.height * species.trunkRadius));
  });
}

void registerTreeInfo(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "info",
      "Print what a tree file holds: pieces by type, joints, quads, depth, branching order and height");
  struct Options {
    std::string file;
    std::string species;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  command->add_option("file", o->file, "Tree JSON file (from 'sylva tree generate')")->required();
  command->add_option(
      "--species", o->species,
      "Species (preset or JSON file) whose trunk radius gives metres (default: the species the "
      "file names, when it is a preset)");
  command->add_flag("--json", o->json, "Print JSON instead of text");
  command->footer("Examples:\n"
                  "  sylva tree info almond.json\n"
                  "  sylva tree info custom.json --species ./my-species.json --json\n");
  command->callback([o] {
    const trees::PieceSet pieces = trees::standardPieces();
    const trees::TreeTopology tree = trees::loadTree(o->file, pieces);
    const std::optional<trees::Species> species =
        o->species.empty() ? presetOf(tree.species) : std::optional(trees::resolveSpecies(o->species));
    const trees::TreeStats stats = trees::treeStats(pieces, tree);
    std::size_t vertices = 0;
    for (const trees::TreeNode& node : tree.nodes) {
      vertices += pieces[static_cast<std::size_t>(node.piece)].vertices.size();
    }
    if (o->json) {
      nlohmann::json byType = nlohmann::json::object();
      for (std::size_t i = 0; i < pieces.size(); ++i) {
        byType[pieces[i].name] = stats.piecesByType[i];
      }
      nlohmann::json out{
          {"file", o->file},         {"species", tree.species},       {"seed", tree.seed},
          {"pieces", stats.pieces},  {"piecesByType", byType},        {"joints", stats.joints},
          {"quads", stats.quads},    {"vertices", vertices},          {"depth", stats.maxDepth},
          {"order", stats.maxOrder}, {"heightRimUnits", stats.height}};
      if (species) {
        out["trunkRadius"] = species->trunkRadius;
        out["heightMetres"] = stats.height * species->trunkRadius;
      }
      std::printf("%s\n", out.dump(2).c_str());
      return;
    }
    std::printf("file     %s\n", o->file.c_str());
    std::printf("species  %s%s, seed %llu\n", tree.species.c_str(),
                species ? fmt::format(" (trunk radius {:g} m)", species->trunkRadius).c_str()
                        : " (not a preset)",
                static_cast<unsigned long long>(tree.seed));
    std::printf("pieces   %zu: %s\n", stats.pieces, countsByType(pieces, stats).c_str());
    std::printf("joints   %zu\n", stats.joints);
    std::printf("quads    %zu (%zu piece vertices)\n", stats.quads, vertices);
    std::printf("depth    %d pieces from the root\n", stats.maxDepth);
    std::printf("order    %d (deepest branching order; the trunk is 0)\n", stats.maxOrder);
    if (species) {
      std::printf("height   %.2f m (%.2f rim units x trunk radius %g m)\n",
                  static_cast<double>(stats.height * species->trunkRadius), static_cast<double>(stats.height),
                  static_cast<double>(species->trunkRadius));
    } else {
      std::printf("height   %.2f rim units (trunk radii; pass --species for metres)\n",
                  static_cast<double>(stats.height));
    }
  });
}

void registerSpecies(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "species", "List the species presets, or print one as species JSON (--show) to copy and edit");
  auto show = std::make_shared<std::string>();
  command->add_option("--show", *show, "Print this preset's species JSON")
      ->check(CLI::IsMember(trees::speciesPresetNames()));
  command->footer("Examples:\n"
                  "  sylva tree species\n"
                  "  sylva tree species --show almond > my-almond.json\n");
  command->callback([show] {
    if (!show->empty()) {
      std::printf("%s\n", trees::toJson(trees::speciesPreset(*show)).dump(2).c_str());
      return;
    }
    std::printf("%-22s %-15s %-10s %s\n", "species", "rule", "max order", "trunk radius");
    for (const std::string& name : trees::speciesPresetNames()) {
      const trees::Species s = trees::speciesPreset(name);
      std::printf("%-22s %-15s %-10d %g m\n", name.c_str(), trees::ruleName(s.rule), s.maxOrder,
                  static_cast<double>(s.trunkRadius));
    }
  });
}

void registerPieces(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "pieces", "List the built-in pieces (rims, quads, vertices); --export writes them as OBJ and glTF for "
                "artists to start from");
  struct Options {
    std::string exportDir;
  };
  auto o = std::make_shared<Options>();
  command->add_option("--export", o->exportDir,
                      "Write every built-in piece to this folder as NAME.obj and NAME.gltf (rims as the "
                      "joints rim_root, rim_leaf_1, ...)");
  command->footer("Examples:\n"
                  "  sylva tree pieces\n"
                  "  sylva tree pieces --export pieces/   # edit pieces/Y.gltf, then check it:\n"
                  "  sylva tree import-piece pieces/Y.gltf\n");
  command->callback([o] {
    const trees::PieceSet pieces = trees::standardPieces();
    std::printf("%-8s %-10s %-6s %-9s %s\n", "piece", "leaf rims", "quads", "vertices", "foliage");
    for (const trees::Piece& p : pieces.pieces) {
      std::printf("%-8s %-10zu %-6zu %-9zu %s\n", p.name.c_str(), p.leafRims(), p.quads.size(),
                  p.vertices.size(), p.bearsFoliage ? "yes" : "no");
    }
    if (!o->exportDir.empty()) {
      for (const trees::Piece& p : pieces.pieces) {
        const fs::path obj = fs::path(o->exportDir) / (p.name + ".obj");
        const fs::path gltf = fs::path(o->exportDir) / (p.name + ".gltf");
        trees::exportPieceObj(p, obj);
        trees::exportPieceGltf(p, gltf);
        std::printf("%s\n%s\n", obj.string().c_str(), gltf.string().c_str());
      }
    }
  });
}

void registerImportPiece(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "import-piece",
      "Check an artist's piece file (OBJ, glTF, Collada, FBX: quads, hexagonal rims marked by "
      "the bones rim_root and rim_leaf_N or, in OBJ, by the boundary loops) and print its rims");
  struct Options {
    std::string file;
    std::string name;
    float tolerance = trees::ImportOptions{}.tolerance;
    float normalTolerance = trees::ImportOptions{}.normalTolerance;
    std::string out;
  };
  auto o = std::make_shared<Options>();
  command->add_option("file", o->file, "Piece file")->required();
  command->add_option("--name", o->name, "Piece name (default: the file name without its extension)");
  command
      ->add_option("--tolerance", o->tolerance,
                   "Largest distance of a rim corner from a regular hexagon, rim units (snapped within it)")
      ->check(finiteRange(1e-6, 0.1))
      ->capture_default_str();
  command
      ->add_option("--normal-tolerance", o->normalTolerance,
                   "Largest angle between the quads next to a rim and the fixed rim normals, radians")
      ->check(finiteRange(1e-4, 1.0))
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "Also write the checked piece (.obj or .gltf, rims snapped)");
  command->footer("Examples:\n"
                  "  sylva tree import-piece branch.gltf\n"
                  "  sylva tree import-piece fork.fbx --name Y -o fork.gltf\n");
  command->callback([o] {
    std::string ext;
    if (!o->out.empty()) {
      ext = lowerExtension(o->out);
      if (ext != ".obj" && ext != ".gltf") {
        fail("-o {}: unsupported extension '{}' (use .obj or .gltf)", o->out, ext);
      }
    }
    trees::ImportOptions options;
    options.name = o->name;
    options.tolerance = o->tolerance;
    options.normalTolerance = o->normalTolerance;
    const trees::Piece piece = trees::importPiece(o->file, options);
    std::printf("%s: piece '%s' is valid: %zu vertices, %zu quads, %zu leaf rim%s%s\n",
                fs::path(o->file).filename().string().c_str(), piece.name.c_str(), piece.vertices.size(),
                piece.quads.size(), piece.leafRims(), piece.leafRims() == 1 ? "" : "s",
                piece.bearsFoliage ? ", bears foliage" : "");
    for (std::size_t r = 0; r < piece.rims.size(); ++r) {
      const glm::mat4& f = piece.rims[r].frame;
      const float radius = glm::length(glm::vec3(f[0]));
      const std::string label = r == 0 ? std::string("root rim") : fmt::format("leaf rim {}", r);
      std::printf("%-11s centre %s, axis %s, radius %.4g, corner 0 towards %s\n", label.c_str(),
                  vec3(glm::vec3(f[3])).c_str(), vec3(glm::normalize(glm::vec3(f[1]))).c_str(),
                  static_cast<double>(radius), vec3(glm::normalize(glm::vec3(f[0]))).c_str());
    }
    if (!o->out.empty()) {
      if (ext == ".obj") {
        trees::exportPieceObj(piece, o->out);
      } else {
        trees::exportPieceGltf(piece, o->out);
      }
      std::printf("%s\n", o->out.c_str());
    }
  });
}

} // namespace

void registerTree(CLI::App& app) {
  auto* command = app.add_subcommand(
      "tree", "Trees from interlocking pieces: generate a tree of a species, inspect tree files, species "
              "presets and pieces, check artist pieces (docs/trees.md)");
  command->require_subcommand(1);
  registerGenerate(*command);
  registerTreeInfo(*command);
  registerSpecies(*command);
  registerPieces(*command);
  registerImportPiece(*command);
}

} // namespace sylva::app
