#pragma once
// Bark from tiles (docs/trees.md "Bark", seed 000 §5.1): every quad of every piece instance shows one tile of
// a texture array, chosen per instance and per quad by a hash among the tiles of the quad's class. Tiles of
// every class share one border (texsynth's symmetric edge colour), so any two quads meet seamlessly whatever
// their tiles and orientations, across rims too. Each quad gets a rotation that puts the tile's y axis along
// the branch (bark grooves follow the wood). CPU side here; shaders/trees/piece.tese and piece.frag are the
// GPU twins of tileCoord() and chooseTile().

#include <sylva/core/Image.hpp>
#include <sylva/trees/Forest.hpp>
#include <sylva/texsynth/TileSet.hpp>
#include <sylva/trees/Piece.hpp>

#include <shared/Trees.h>

#include <glm/vec2.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva::trees {

/**
 * Per quad of `piece`: the tile rotation r ∈ {0, 1, 2, 3}, the quad corner that is the tile's origin. The
 * tile's x axis runs from corner r to corner r + 1 and its y axis from corner r to corner r + 3 (mod 4), so
 * tiles are never mirrored; r is chosen so y points away from the root rim (graph distance over quad edges).
 */
std::vector<std::uint8_t> quadTileRotations(const Piece& piece);

/**
 * Tile coordinates (x, y) ∈ [0, 1]² of the quad point with tessellation coordinates `uv` (GL quad domain:
 * corners 0…3 at (0,0), (1,0), (1,1), (0,1)) for tile rotation `rotation`.
 */
glm::vec2 tileCoord(glm::vec2 uv, int rotation);

/** The tile seed of a piece instance, from its root joint (unique per piece instance of a forest). */
std::uint32_t instanceTileSeed(std::uint32_t rootJoint);

/** The tile (layer within a bark set) of quad `quad`: first + hash(seed, quad) mod count; count > 0. */
std::uint32_t chooseTile(std::uint32_t seed, std::uint32_t quad, std::uint32_t first, std::uint32_t count);

/**
 * The texel (column, row) a tile coordinate samples in a T × T tile: edge lines (x or y = 0 or 1) are the
 * tile's outermost texel rows and columns, which neighbouring tiles share.
 */
glm::ivec2 tileTexel(glm::vec2 xy, int tileSize);

/**
 * One bark set: tiles (T × T, RGB or RGBA 8-bit colour; optional tangent-space normal maps of the same size,
 * n = 2c − 1, x along the tile's x, y along its y) in class order: class c's tiles are
 * colour[classFirst[c] … classFirst[c] + classCount[c]).
 */
struct BarkSet {
  std::string name;
  int tileSize = 0;
  std::vector<Image> colour;
  std::vector<Image> normal;
  std::array<std::uint32_t, SYLVA_TREE_MAX_TILE_CLASSES> classFirst{};
  std::array<std::uint32_t, SYLVA_TREE_MAX_TILE_CLASSES> classCount{};
};

/** Throws sylva::Error "<where>: …" for sets with missing classes, mixed sizes or out-of-range tiles. */
void validate(const BarkSet& set, const std::string& where);

/**
 * The tile (index into set.colour) of quad `quad` of the piece instance with root joint `rootJoint` whose
 * class is `tileClass`: chooseTile() among the class's tiles; classes without tiles use class 0's, as the
 * renderer does.
 */
std::uint32_t barkTile(const BarkSet& set, std::uint32_t rootJoint, std::uint32_t quad,
                       std::uint32_t tileClass);

/**
 * A bark set from a texsynth tile set (texsynth::barkTileSet or a loaded tile-set directory): 8-bit colour
 * tiles, normal maps (n = 2c − 1, y along the tile's rows) when the set has normals, classes in order.
 * Throws sylva::Error naming `name` when the set has more classes than SYLVA_TREE_MAX_TILE_CLASSES.
 */
BarkSet barkSetFromTiles(const texsynth::TileSet& tiles, const std::string& name);

/** Where a forest's bark tiles come from (`sylva render --trees-bark`, scene files). */
struct BarkSources {
  /**
   * "auto": each species' photos (Species::bark) from photoDir when they are there, else procedural bark;
   * "procedural": procedural bark for every species; otherwise a tile-set directory (`sylva texsynth tiles`)
   * for every species.
   */
  std::string mode = "auto";
  /** Directory of `<name>_color_1k.jpg` and `<name>_normal_1k.jpg` (scripts/fetch-sample-data.sh). */
  std::filesystem::path photoDir = "data/external/ez-tree/bark";
  /** Synthesised sets are kept here and reused (empty: no cache). */
  std::filesystem::path cacheDir;
  /** Tile construction (tile size, seed, …). */
  texsynth::TileSettings tiles = defaultBarkTiles();
  /** Tiles per class. */
  int variants = 4;
  /** Photos are halved until their side is at most this many texels (bark scale and synthesis time). */
  int photoSide = 256;

  static texsynth::TileSettings defaultBarkTiles();
};

/**
 * The bark sets of `forest` (one per distinct source among its species) and, in speciesSet, the set of each
 * species. Logs where every set comes from; throws sylva::Error naming the file for unreadable photos or
 * tile sets.
 */
std::vector<BarkSet> barkSetsFor(const Forest& forest, const BarkSources& sources,
                                 std::vector<int>& speciesSet);

/** Which source a species' bark comes from under `sources`: the photo name, "procedural", or the directory.
 */
std::string barkSource(const std::string& photo, const BarkSources& sources);
/** The bark set of one source (see barkSource): loaded, cached or synthesised. Throws naming the file. */
BarkSet barkSetFromSource(const std::string& source, const BarkSources& sources);

/**
 * A bark set's colour tiles in one image for exports: tile i at column i % columns, row i / columns (image
 * rows top-down); a tile's row 0 (its edge 0) is its cell's top row.
 */
struct BarkAtlas {
  Image image;
  int columns = 1;
  int rows = 1;
  int tileSize = 0;
};
BarkAtlas barkAtlas(const BarkSet& set);
/**
 * UVs (glTF convention: v down the image) of a quad's four corners showing `tile` with `rotation`: the texel
 * centres of the tile's outermost rows and columns, as the renderer samples them.
 */
std::array<glm::vec2, 4> barkAtlasUv(const BarkAtlas& atlas, std::uint32_t tile, int rotation);

/** The packed quad table entry of every quad of `piece`: tile class | rotation << 8. */
std::vector<std::uint32_t> quadTileTable(const Piece& piece);

} // namespace sylva::trees
