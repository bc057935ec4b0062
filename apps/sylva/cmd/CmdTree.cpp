// `sylva tree <sub>`: trees from interlocking pieces (docs/trees.md). generate grows a tree of a species from
// a seed into a tree JSON file (atomically); info counts what a tree file holds; species lists the presets
// and prints one as JSON to start a species file from; pieces lists the built-in pieces (and exports them as
// OBJ and glTF for artists); import-piece checks an artist's piece file and prints its rims; export writes a
// whole tree as glTF (skinned, LOD chain, atlases, wind) or OBJ, baking its impostor atlas on a headless GL
// context with --impostor (only then: every other export is CPU only). Every error is one line naming the
// file and field (or option), found before any output is written.
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/Export.hpp>
#include <sylva/trees/Foliage.hpp>
#include <sylva/trees/ForestLook.hpp>
#include <sylva/trees/Forest.hpp>
#include <sylva/trees/gpu/ImpostorRenderer.hpp>
#include <sylva/trees/gpu/SpeciesSheet.hpp>
#include <sylva/trees/Import.hpp>
#include <sylva/trees/Measure.hpp>
#include <sylva/trees/Pieces.hpp>
#include <sylva/trees/Skeleton.hpp>
#include <sylva/trees/Species.hpp>
#include <sylva/trees/Tree.hpp>
#include <sylva/trees/TreeSummary.hpp>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

/** --species (required): a preset name or a species JSON file. */
void addSpeciesOption(CLI::App& command, std::string& species) {
  command
      .add_option("--species", species,
                  "A preset name (see 'sylva tree species') or a species JSON file (a path with '/' or "
                  "ending in .json)")
      ->required();
}

namespace fs = std::filesystem;

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
  addSpeciesOption(*command, o->species);
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
                static_cast<unsigned long long>(o->seed), stats.pieces,
                trees::piecesByTypeText(pieces, stats).c_str(), stats.joints, stats.maxDepth,
                static_cast<double>(stats.height * species.trunkRadius));
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
    const std::optional<trees::Species> species = o->species.empty()
                                                      ? trees::presetSpecies(tree.species)
                                                      : std::optional(trees::resolveSpecies(o->species));
    if (o->json) {
      std::printf("%s\n", trees::describeTreeJson(o->file, tree, pieces, species).dump(2).c_str());
    } else {
      std::fputs(trees::describeTree(o->file, tree, pieces, species).c_str(), stdout);
    }
  });
}

void registerMeasure(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "measure", "Measure trees of a species as the renderer draws them: height, trunk radius, slenderness, "
                 "crown base, width and height, silhouette profile, drooping twig tips, pieces");
  struct Options {
    std::string species;
    std::uint64_t seed = 1;
    int seeds = 1;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  addSpeciesOption(*command, o->species);
  command->add_option("--seed", o->seed, "Seed of the first tree (as 'sylva tree generate')")
      ->check(unsignedInteger())
      ->capture_default_str();
  command
      ->add_option("--seeds", o->seeds,
                   "Trees measured: seeds --seed, --seed + 1, …; with several, also "
                   "their min, mean and max")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_flag("--json", o->json, "Print JSON instead of text");
  command->footer("Examples:\n"
                  "  sylva tree measure --species oak --seeds 20\n"
                  "  sylva tree measure --species ./my-species.json --seed 7 --json\n");
  command->callback([o] {
    const trees::Species species = trees::resolveSpecies(o->species);
    const trees::PieceSet pieces = trees::standardPieces();
    std::vector<trees::TreeMeasures> measured;
    {
      Progress progress("measuring trees", static_cast<std::size_t>(o->seeds));
      for (int i = 0; i < o->seeds; ++i) {
        measured.push_back(trees::measureSpecies(pieces, species, o->seed + static_cast<std::uint64_t>(i)));
        progress.advance();
      }
    }
    const trees::MeasureSummary summary = trees::summarise(std::move(measured));
    if (o->json) {
      std::printf("%s\n", trees::describeMeasuresJson(species.name, o->seed, summary).dump(2).c_str());
    } else {
      std::fputs(trees::describeMeasures(species.name, o->seed, summary).c_str(), stdout);
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
    std::fputs(trees::describePiece(o->file, piece).c_str(), stdout);
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

/** "8,3,1" → {8, 3, 1}; one-line errors naming the option. */
/**
 * Bakes the impostor atlas of the exported tree on a headless GL context, as `sylva render --trees-far` bakes
 * a species (ez-tree's oak leaf when fetched, else the procedural leaf); returns it with the seconds from the
 * context's creation to the atlas read back.
 */
std::pair<trees::ImpostorAtlas, double>
bakeImpostor(const ContextFlags& context, const trees::PieceSet& pieces, const trees::Species& species,
             const trees::TreeTopology& topology, const std::vector<glm::vec2>& pose, float scale,
             trees::TreeImpostorBake bake) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<platform::GlContext> glContext = platform::createHeadlessContext(context.options());
  log::info("impostor: baking {} x {} views of {} px ({} px atlas{}{})", bake.views, bake.views, bake.cell,
            bake.views * bake.cell, bake.bark ? ", bark tiles" : "", bake.foliage ? ", foliage" : "");
  std::optional<Image> leaf;
  const fs::path& autoLeaf = trees::kAutoLeafImage;
  if (bake.foliage && fs::exists(autoLeaf)) {
    leaf = trees::loadLeafImage(autoLeaf);
    bake.leafImage = &*leaf;
  }
  const shader::Library library;
  trees::ImpostorAtlas atlas = trees::bakeTreeImpostor(library, pieces, species, topology, pose, scale, bake);
  return {std::move(atlas), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

void registerSheet(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "sheet", "Render a species sheet: one tree of each species side by side at one scale, seen from the "
               "side, each beside a 1.75 m person-sized marker (PNG, on a headless GL context)");
  struct Options {
    std::string species;
    std::uint64_t seed = 1;
    int height = 540;
    std::string out;
    ContextFlags context;
  };
  auto o = std::make_shared<Options>();
  command->add_option("--species", o->species,
                      "Comma-separated presets or species JSON files (default: every "
                      "preset of a real species, the paper's two rules left out)");
  command->add_option("--seed", o->seed, "Seed of every tree")
      ->check(unsignedInteger())
      ->capture_default_str();
  command->add_option("--height", o->height, "Image height, pixels")
      ->check(CLI::Range(16, 8192))
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "PNG file to write (atomically)")->required();
  o->context.add(*command);
  command->footer("Example:\n  sylva tree sheet -o species.png\n  sylva tree sheet --species "
                  "silver-birch,weeping-willow --seed 4 --height 720 -o two.png\n");
  command->callback([o] {
    if (lowerExtension(o->out) != ".png") {
      fail("-o {}: a species sheet is a .png file", o->out);
    }
    std::vector<trees::Species> species;
    for (const std::string& name :
         o->species.empty() ? trees::realSpeciesPresetNames() : commaItems(o->species)) {
      species.push_back(trees::resolveSpecies(name));
    }
    const std::unique_ptr<platform::GlContext> glContext =
        platform::createHeadlessContext(o->context.options());
    trees::SpeciesSheetOptions options;
    options.seed = o->seed;
    options.height = o->height;
    saveImage(o->out, trees::renderSpeciesSheet(shader::Library(), species, options));
    std::printf("%s\n", o->out.c_str());
  });
}

void registerExport(CLI::App& tree) {
  auto* command = tree.add_subcommand(
      "export",
      "Write a tree as glTF 2.0 (.gltf or .glb: skinned mesh on the tree's joints, LOD chain, bark and "
      "impostor atlases, wind parameters) or OBJ (rest pose, finest LOD) for other tools");
  struct Options {
    std::string species;
    std::uint64_t seed = 1;
    std::string out;
    std::string levels = "8,3,1";
    std::string barkAtlas;
    std::string bark = "auto";
    std::string barkPhotos; // empty: the data folder's
    std::string impostorAtlas;
    int impostorViews = 8;
    std::string impostorLayout = "octahedral";
    bool impostor = false;
    int impostorCell = 128;
    bool impostorFoliage = true;
    std::string impostorPng;
    ContextFlags context;
    bool straight = false;
  };
  auto o = std::make_shared<Options>();
  addSpeciesOption(*command, o->species);
  command->add_option("--seed", o->seed, "Seed of the tree's random choices (as 'sylva tree generate')")
      ->check(unsignedInteger())
      ->capture_default_str();
  command->add_option("-o,--out", o->out, "File to write (atomically): .gltf, .glb or .obj (+ .mtl)")
      ->required();
  command
      ->add_option(
          "--levels", o->levels,
          "Phong tessellation level of each LOD, finest first, comma separated (each 1-64; OBJ writes "
          "the first)")
      ->capture_default_str();
  command->add_option("--bark-atlas", o->barkAtlas,
                      "PNG bark texture, embedded (glTF) or written beside the OBJ; mapped by the pieces' "
                      "(u, v), repeating; overrides --bark");
  command
      ->add_option("--bark", o->bark,
                   "Bark tiles per quad as the renderer draws them (docs/trees.md \"Bark\"), in one atlas: "
                   "auto (the species' photos from --bark-photos, else procedural), procedural, a tile-set "
                   "directory from 'sylva texsynth tiles', or none (the species' bark colour)")
      ->capture_default_str();
  command->add_option("--bark-photos", o->barkPhotos,
                      "Directory of <name>_color_1k.jpg bark photos (default: the data folder's "
                      "external/ez-tree/bark; a directory named here must exist)");
  command->add_option(
      "--impostor-atlas", o->impostorAtlas,
      "PNG impostor atlas of N x N views of the tree: adds a camera-facing quad as the last LOD "
      "(glTF only)");
  command
      ->add_option("--impostor-views", o->impostorViews,
                   "Views per side of the impostor atlas (--impostor: 2-64)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  auto* layout =
      command
          ->add_option("--impostor-layout", o->impostorLayout,
                       "Layout of --impostor-atlas: octahedral (full sphere), hemi-octahedral (the atlases "
                       "of 'sylva render --trees-far', upper hemisphere) or grid (yaw steps by rows)")
          ->check(CLI::IsMember({"octahedral", "hemi-octahedral", "grid"}))
          ->capture_default_str();
  command->add_flag("--impostor", o->impostor,
                    "Bake the tree's impostor atlas (hemi-octahedral, --impostor-views x --impostor-cell, "
                    "bark as --bark, foliage) on a headless GL context and embed it (glTF only)");
  command->add_option("--impostor-cell", o->impostorCell, "Pixels per view side of the --impostor bake")
      ->check(CLI::Range(8, 1024))
      ->capture_default_str();
  command->add_flag(
      "--impostor-foliage,!--no-impostor-foliage", o->impostorFoliage,
      "Draw the foliage into the --impostor bake (default; --no-impostor-foliage: bare branches)");
  command->add_option("--impostor-png", o->impostorPng,
                      "Also write the --impostor atlas here as a PNG (atomically; file order, cell (i, j) "
                      "with j counted from the bottom row)");
  o->context.add(*command);
  command->add_flag(
      "--straight", o->straight,
      "Export the straight rest pose (no bends); default: the pose the renderer draws for this seed");
  command->footer("Examples:\n"
                  "  sylva tree export --species almond --seed 42 -o almond.glb\n"
                  "  sylva tree export --species oak --seed 7 --levels 8,3,1 --bark-atlas bark.png \\\n"
                  "      --impostor-atlas oak-impostor.png --impostor-views 8 -o oak.gltf\n"
                  "  sylva tree export --species almond --seed 42 --impostor --impostor-png atlas.png \\\n"
                  "      -o almond.glb   # bakes the atlas (8 x 8 views of 128 px) on a headless context\n"
                  "  sylva tree export --species weeping-willow --seed 3 -o willow.obj   # + willow.mtl\n"
                  "Check a glTF with the Khronos validator: scripts/fetch-node-tools.sh, then\n"
                  "  node tests/support/validate-gltf.mjs almond.glb\n");
  command->callback([o, layout] {
    const std::string ext = lowerExtension(o->out);
    if (ext != ".gltf" && ext != ".glb" && ext != ".obj") {
      fail("-o {}: unsupported extension '{}' (use .gltf, .glb or .obj)", o->out, ext);
    }
    if (o->impostor && !o->impostorAtlas.empty()) {
      fail("--impostor: bakes the impostor atlas; it cannot be combined with --impostor-atlas (give one)");
    }
    if (!o->barkPhotos.empty() && !fs::is_directory(o->barkPhotos)) {
      fail("--bark-photos: no directory '{}'", o->barkPhotos);
    }
    if (ext == ".obj" && !o->impostorAtlas.empty()) {
      fail("--impostor-atlas: OBJ has no LOD chain; export .gltf or .glb for an impostor");
    }
    if (ext == ".obj" && o->impostor) {
      fail("--impostor: OBJ has no LOD chain; export .gltf or .glb for an impostor");
    }
    if (!o->impostorPng.empty() && !o->impostor) {
      fail("--impostor-png {}: needs --impostor (the atlas it writes is baked by the export)",
           o->impostorPng);
    }
    if (!o->impostorPng.empty() && lowerExtension(o->impostorPng) != ".png") {
      fail("--impostor-png {}: the atlas is written as PNG; the file must end in .png", o->impostorPng);
    }
    if (o->impostor) {
      if (layout->count() > 0 && o->impostorLayout != "hemi-octahedral") {
        fail("--impostor-layout {}: --impostor bakes hemi-octahedral atlases", o->impostorLayout);
      }
      if (o->impostorViews < 2) {
        fail("--impostor-views {}: --impostor bakes 2-64 views per side", o->impostorViews);
      }
      if (o->impostorViews * o->impostorCell > 8192) {
        fail("--impostor-views {} x --impostor-cell {}: the atlas would be {} px per side (at most 8192)",
             o->impostorViews, o->impostorCell, o->impostorViews * o->impostorCell);
      }
    }
    trees::TreeExportOptions options;
    options.levels = parseIntegers("--levels", o->levels, 1, 64, "a tessellation level");
    const trees::Species species = trees::resolveSpecies(o->species);
    const trees::PieceSet pieces = trees::standardPieces();
    const trees::TreeTopology tree = trees::generateTree(pieces, species, o->seed);
    trees::BarkSet bark;
    // The bark tiles of --bark: the mesh's atlas (unless --bark-atlas overrides it) and the --impostor bake.
    const bool tiles = o->bark != "none" && (o->barkAtlas.empty() || o->impostor);
    if (tiles) {
      trees::BarkSources sources;
      sources.mode = o->bark;
      if (!o->barkPhotos.empty()) {
        sources.photoDir = o->barkPhotos;
      }
      bark = trees::barkSetFromSource(trees::barkSource(species.bark, sources), sources);
    }
    if (!o->barkAtlas.empty()) {
      options.barkAtlas = loadImage(o->barkAtlas);
    } else if (tiles) {
      trees::useRendererBark(options, bark, pieces, tree);
    }
    if (!o->impostorAtlas.empty()) {
      trees::ImpostorAtlas atlas;
      atlas.image = loadImage(o->impostorAtlas);
      atlas.viewsPerSide = o->impostorViews;
      atlas.layout = o->impostorLayout;
      if (atlas.image.width() % atlas.viewsPerSide != 0 || atlas.image.height() % atlas.viewsPerSide != 0) {
        fail("--impostor-atlas {}: {}x{} pixels do not split into {} x {} equal views", o->impostorAtlas,
             atlas.image.width(), atlas.image.height(), atlas.viewsPerSide, atlas.viewsPerSide);
      }
      options.impostor = std::move(atlas);
    }
    if (!o->straight) {
      options.pose = trees::randomPose(tree, species, o->seed);
    }
    trees::TreeImpostorBake bake;
    double bakeSeconds = 0.0;
    if (o->impostor) {
      bake.views = o->impostorViews;
      bake.cell = o->impostorCell;
      bake.foliage = o->impostorFoliage;
      if (tiles) {
        bake.bark = bark;
      }
      auto [atlas, seconds] =
          bakeImpostor(o->context, pieces, species, tree, options.pose, species.trunkRadius, bake);
      options.impostor = std::move(atlas);
      bakeSeconds = seconds;
    }
    const trees::TreeExportStats stats = ext == ".obj"
                                             ? trees::exportTreeObj(pieces, tree, species, o->out, options)
                                             : trees::exportTreeGltf(pieces, tree, species, o->out, options);
    std::printf("%s\n", o->out.c_str());
    std::string lods;
    for (std::size_t l = 0; l < stats.vertices.size(); ++l) {
      lods += fmt::format("{}LOD{} level {}: {} vertices, {} triangles", l == 0 ? "" : "; ", l,
                          options.levels[l], stats.vertices[l], stats.triangles[l]);
    }
    std::printf("%s, seed %llu: %zu pieces, %zu joints; %s%s (%zu bytes)\n", species.name.c_str(),
                static_cast<unsigned long long>(o->seed), tree.nodes.size(), stats.joints, lods.c_str(),
                options.impostor ? "; impostor quad" : "", stats.bytes);
    if (o->impostor) {
      const trees::ImpostorAtlas& atlas = *options.impostor;
      std::printf("impostor: baked %d x %d hemi-octahedral views of %d px (%dx%d px atlas, bounding sphere "
                  "radius %.2f m) in %.2f s\n",
                  bake.views, bake.views, bake.cell, atlas.image.width(), atlas.image.height(),
                  static_cast<double>(atlas.sphere->w), bakeSeconds);
    }
    if (!o->impostorPng.empty()) {
      savePng(o->impostorPng, options.impostor->image);
      std::printf("%s\n", o->impostorPng.c_str());
    }
  });
}

} // namespace

void registerTree(CLI::App& app) {
  auto* command = app.add_subcommand(
      "tree", "Trees from interlocking pieces: generate a tree of a species, inspect tree files, species "
              "presets and pieces, check artist pieces, export trees as glTF or OBJ (docs/trees.md)");
  command->require_subcommand(1);
  registerGenerate(*command);
  registerTreeInfo(*command);
  registerMeasure(*command);
  registerSpecies(*command);
  registerPieces(*command);
  registerImportPiece(*command);
  registerExport(*command);
  registerSheet(*command);
}

} // namespace sylva::app
