// `sylva texsynth`: texture synthesis from photos (docs/texsynth.md). `quilt` grows a larger texture by image
// quilting; `tiles` builds the trees' bark tile set (one symmetric edge colour, classes plain/fork/crotch);
// `wang` builds a complete Wang tile set and a preview of a random tiling. Inputs and options are checked
// before any work; outputs are written atomically (a tile set directory appears whole or not at all).
#include "Commands.hpp"
#include "flags/SourceOptions.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Image.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/texsynth/Procedural.hpp>
#include <sylva/texsynth/Quilt.hpp>
#include <sylva/texsynth/TileSet.hpp>
#include <sylva/texsynth/TileSetIo.hpp>

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

namespace sylva::app {
namespace {

namespace fs = std::filesystem;
using namespace sylva::texsynth;

/** Parses "WxH" (texels or tiles, 1..limit each); throws naming the option. */
std::pair<int, int> parseExtent(const std::string& option, const std::string& text, int limit) {
  int w = 0;
  int h = 0;
  char x = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 ||
      h < 1 || w > limit || h > limit) {
    fail("{}: expected WxH with each side in 1..{}, got '{}'", option, limit, text);
  }
  return {w, h};
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct QuiltOptions {
  std::string in;
  std::string normal;
  std::string out;
  std::string normalOut;
  std::string size = "512x512";
  int block = QuiltSettings{}.block;
  int overlap = 0;
  double tolerance = QuiltSettings{}.tolerance;
  std::uint64_t seed = 1;
};

void runQuilt(const QuiltOptions& o) {
  if (lowerExtension(o.out) != ".png") {
    fail("--out: {} must be a .png file", o.out);
  }
  const auto [w, h] = parseExtent("--size", o.size, kMaxTextureSide);
  QuiltSettings settings;
  settings.block = o.block;
  settings.overlap = o.overlap;
  settings.tolerance = o.tolerance;
  settings.seed = o.seed;
  const Texture source = loadSourceTexture(o.in, o.normal);
  if (!o.normalOut.empty() && !source.hasNormals()) {
    fail("--normal-out: the input has no normal map (give --normal)");
  }
  validate(settings, source);
  const auto start = std::chrono::steady_clock::now();
  Texture result;
  {
    Progress progress("quilting", static_cast<std::size_t>(quiltBlockCount(w, h, settings)));
    result = quilt(source, w, h, settings, &progress);
  }
  saveImage(o.out, colourImage(result));
  if (!o.normalOut.empty()) {
    saveImage(o.normalOut, normalImage(result, NormalGreen::Up));
  }
  std::printf("wrote %s: %dx%d texels from %s (block %d, overlap %d) in %.1f s\n", o.out.c_str(), w, h,
              source.name.c_str(), settings.block, settings.effectiveOverlap(), secondsSince(start));
}

struct TileOptions {
  std::string in;
  std::string normal;
  std::string out;
  int tile = 128;
  int variants = 8;
  int colours = 2;
  int band = 0;
  int overlap = 0;
  double tolerance = TileSettings{}.tolerance;
  std::uint64_t seed = 1;
  std::string preview = "8x8";
};

TileSettings tileSettings(const TileOptions& o) {
  TileSettings settings;
  settings.tileSize = o.tile;
  settings.band = o.band;
  settings.overlap = o.overlap;
  settings.tolerance = o.tolerance;
  settings.seed = o.seed;
  return settings;
}

void runTiles(const TileOptions& o) {
  checkTileSetOutput(o.out);
  const TileSettings settings = tileSettings(o);
  const std::vector<Texture> photos{loadSourceTexture(o.in, o.normal)};
  validate(settings, photos);
  const auto start = std::chrono::steady_clock::now();
  TileSet set;
  {
    const int colourings = o.colours * o.colours * o.colours * o.colours;
    Progress progress("building bark tiles", static_cast<std::size_t>(3 * colourings * o.variants));
    set = barkTileSet(photos, o.variants, settings, &progress, o.colours);
  }
  saveTileSet(o.out, set);
  std::fputs(describeTileSet(set, o.out, secondsSince(start)).c_str(), stdout);
}

void runWang(const TileOptions& o) {
  checkTileSetOutput(o.out);
  const auto [pw, ph] = parseExtent("--preview", o.preview, 64);
  const TileSettings settings = tileSettings(o);
  const Texture photo = loadSourceTexture(o.in, o.normal);
  validate(settings, {photo});
  if (o.colours < 1 || o.colours > 3) {
    fail("--colours: {} is out of range [1, 3]", o.colours);
  }
  const auto start = std::chrono::steady_clock::now();
  TileSet set;
  {
    const int classes = o.colours * o.colours * o.colours * o.colours;
    Progress progress("building Wang tiles", static_cast<std::size_t>(classes * o.variants));
    set = wangTileSet(photo, o.colours, o.variants, settings, &progress);
  }
  const std::vector<int> grid = tileGrid(set, pw, ph, o.seed);
  const Texture preview = tilingPreview(set, grid, pw, ph);
  saveTileSet(o.out, set, {{"preview.png", colourImage(preview)}});
  std::fputs(describeTileSet(set, o.out, secondsSince(start)).c_str(), stdout);
  std::printf("preview: %s/preview.png, a random %dx%d tiling\n", o.out.c_str(), pw, ph);
}

void addPhotoOptions(CLI::App& command, std::string& in, std::string& normal) {
  command.add_option("--in", in, "Photo (JPEG, PNG or EXR), or 'procedural' for procedural bark")->required();
  command.add_option("--normal", normal, "Normal map of the photo (OpenGL convention: green up), optional");
}

void addSeed(CLI::App& command, std::uint64_t& seed, const char* what) {
  command.add_option("--seed", seed, what)->check(unsignedInteger())->capture_default_str();
}

void addTileOptions(CLI::App& command, TileOptions& o, int defaultTile) {
  o.tile = defaultTile;
  addPhotoOptions(command, o.in, o.normal);
  command.add_option("--out", o.out, "Output directory (tileset.json, color.png, normal.png)")->required();
  command.add_option("--tile", o.tile, "Tile side T, texels")
      ->check(CLI::Range(8, 1024))
      ->capture_default_str();
  command.add_option("--band", o.band, "Frame band of pure photo texels next to each edge, texels (0: T/8)")
      ->check(CLI::Range(0, 512))
      ->capture_default_str();
  command.add_option("--overlap", o.overlap, "Ring where the interior is stitched in, texels (0: T/6)")
      ->check(CLI::Range(0, 512))
      ->capture_default_str();
  command
      .add_option("--tolerance", o.tolerance, "Interior choice: candidates within (1 + tolerance) x min SSD")
      ->check(finiteRange(0.0, 10.0))
      ->capture_default_str();
  addSeed(command, o.seed, "Seed of the strips and interiors (same seed, same tiles)");
}

} // namespace

void registerTexsynth(CLI::App& app) {
  auto* command = app.add_subcommand(
      "texsynth",
      "Texture synthesis from photos: image quilting and edge-constrained tile sets (docs/texsynth.md)");
  command->require_subcommand(1);

  auto* quiltCommand = command->add_subcommand(
      "quilt", "Grow a larger texture from a photo by image quilting (Efros & Freeman 2001); writes a PNG");
  auto q = std::make_shared<QuiltOptions>();
  addPhotoOptions(*quiltCommand, q->in, q->normal);
  quiltCommand->add_option("--out", q->out, "Output colour PNG")->required();
  quiltCommand->add_option("--normal-out", q->normalOut, "Output normal-map PNG (needs --normal)");
  quiltCommand->add_option("--size", q->size, "Output size WxH, texels")->capture_default_str();
  quiltCommand->add_option("--block", q->block, "Block side, texels")
      ->check(CLI::Range(4, 1024))
      ->capture_default_str();
  quiltCommand->add_option("--overlap", q->overlap, "Overlap of neighbouring blocks, texels (0: block/6)")
      ->check(CLI::Range(0, 512))
      ->capture_default_str();
  quiltCommand
      ->add_option("--tolerance", q->tolerance, "Block choice: candidates within (1 + tolerance) x min SSD")
      ->check(finiteRange(0.0, 10.0))
      ->capture_default_str();
  addSeed(*quiltCommand, q->seed, "Seed of the block choice (same seed, same texture)");
  quiltCommand->callback([q] { runQuilt(*q); });

  auto* tilesCommand = command->add_subcommand(
      "tiles",
      "Build the trees' bark tile set: symmetric edge colours (any side matches any side), classes plain, "
      "fork and crotch, one class per edge colouring of each (docs/trees.md \"Bark\")");
  auto t = std::make_shared<TileOptions>();
  t->colours = 1;
  t->variants = 8;
  addTileOptions(*tilesCommand, *t, 128);
  tilesCommand->add_option("--variants", t->variants, "Tiles per class (and edge colouring)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  tilesCommand
      ->add_option("--colours", t->colours,
                   "Symmetric edge colours (1: the paper's one border for all tiles; 2 or 3: Wang tiles, "
                   "colours^4 classes per kind, as sylva render --trees uses with 2)")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  tilesCommand->callback([t] { runTiles(*t); });

  auto* wangCommand = command->add_subcommand(
      "wang", "Build a complete Wang tile set (colours^4 classes) and preview.png of a random tiling");
  auto w = std::make_shared<TileOptions>();
  w->variants = 1;
  addTileOptions(*wangCommand, *w, 64);
  wangCommand->add_option("--colours", w->colours, "Oriented edge colours")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  wangCommand->add_option("--variants", w->variants, "Tiles per class")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  wangCommand->add_option("--preview", w->preview, "Size of the preview tiling WxH, tiles")
      ->capture_default_str();
  wangCommand->callback([w] { runWang(*w); });
}

} // namespace sylva::app
