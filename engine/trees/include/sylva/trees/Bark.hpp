#pragma once
// Bark from tiles (docs/trees.md "Bark", seed 000 §5.1): every quad of every piece instance shows tiles of a
// texture array, chosen per instance and per quad, as many stacked along its grain as keep them about square
// (tileRepeat: a stretched piece takes more). Tile edges carry symmetric edge colours (texsynth: a
// palindromic line, the same on any side), so two quads meet seamlessly whatever their orientations when
// their shared edge has one colour. Rim edges all have colour 0 (any of a rim's six rotations is valid);
// every interior edge of a piece instance gets a colour by a hash of the instance and the edge (Wang tiles,
// Cohen et al. 2003), and the quad shows a tile of its class with exactly its four edge colours. With one
// colour this is the paper's case (one border for all tiles). Each quad gets a rotation that puts the tile's
// y axis along the branch. CPU side here; shaders/trees/piece.tese and piece.frag are the GPU twins.

#include <sylva/core/Files.hpp>
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
#include <utility>
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

/** An edge id of a piece that is a rim (boundary) edge: its colour is always 0. */
constexpr std::uint8_t kRimEdge = 255;

/**
 * The tile layout of a piece's quads: rotation per quad (quadTileRotations) and, per quad, the ids of its
 * four edges in quad-edge order (edge e runs from corner e to corner e + 1); edges shared by two quads have
 * ids 0 … 254, rim edges kRimEdge.
 */
struct PieceTiling {
  /** Per quad: the corner its tile's x axis starts at (quadTileRotations). */
  std::vector<std::uint8_t> rotation;
  /** Per quad: the ids of its four edges, quad-edge order. */
  std::vector<std::array<std::uint8_t, 4>> edges;
  /**
   * Per quad, how many tiles its grain takes (tileRepeat): x the quad's length along the tile's y over its
   * width at stretch 1, y how much that ratio grows per unit of TreeNode::stretch − 1, both in 1/16 (0 …
   * 255). Quads whose side edges (tile x = 0 or 1) are not side edges of their neighbours too, or lie on a
   * rim, keep one tile: x = 16, y = 0 (their whole group: every quad reachable over side edges).
   */
  std::vector<std::array<std::uint8_t, 2>> repeat;
  /**
   * Per quad, bit 0 (tile side 1) and bit 1 (tile side 3): the side's tile y runs from its higher vertex id
   * to its lower. A side along the grain of several sub-tiles has a colour per part, counted from its lower
   * vertex id, so the two quads sharing it agree whichever way each runs.
   */
  std::vector<std::uint8_t> sideFlip;
};
/** Throws sylva::Error naming the piece when it has more than 255 interior edges. */
PieceTiling pieceTiling(const Piece& piece);

/** Most tiles one quad takes along its grain. */
constexpr std::uint32_t kMaxTileRepeat = SYLVA_TREE_MAX_TILE_REPEAT;

/** A piece instance's stretch as tiling reads it: round(stretch · 16), clamped to 1 … 255 (8 bits). */
std::uint32_t tileStretch(float stretch);

/**
 * Tiles stacked along the grain of quad `quad` in an instance of stretch `stretch` (tileStretch units):
 * round(x + (stretch / 16 − 1) · y) of PieceTiling::repeat in 1/16, clamped to 1 … kMaxTileRepeat, in integer
 * arithmetic (the shaders compute the same bits). Tiles then keep their shape however long a piece grows;
 * every quad of a group takes the same count, so neighbours' sub-tile edges meet.
 */
std::uint32_t tileRepeat(const PieceTiling& tiling, std::size_t quad, std::uint32_t stretch);

/** The colour (0 … colours − 1) of edge `edge` of the piece instance with tile seed `seed`. */
std::uint32_t edgeColour(std::uint32_t seed, std::uint8_t edge, std::uint32_t colours);

/** The colour of part `part` (0 … repeat − 1, from its lower vertex id) of an edge along the grain of a quad
 * with `repeat` sub-tiles: part 0 is edgeColour(). */
std::uint32_t sideEdgeColour(std::uint32_t seed, std::uint8_t edge, std::uint32_t part,
                             std::uint32_t colours);

/** The colour of the edge between sub-tiles `sub` − 1 and `sub` (1 … repeat − 1) of quad `quad`. */
std::uint32_t innerEdgeColour(std::uint32_t seed, std::uint32_t quad, std::uint32_t sub,
                              std::uint32_t colours);

/**
 * The edge colouring index of sub-tile `sub` of `repeat` along quad `quad`'s grain, e0 + K·e1 + K²·e2 + K³·e3
 * over the TILE's edges 0 … 3 (tile edge k is quad edge (rotation + k) mod 4), K = colours. Tile edges 1 and
 * 3 take the colour of their part of the quad edge (sideEdgeColour); edge 0 of sub-tile 0 and edge 2 of the
 * last are the quad's, the others innerEdgeColour().
 */
std::uint32_t quadColouring(const PieceTiling& tiling, std::size_t quad, std::uint32_t seed,
                            std::uint32_t colours, std::uint32_t sub = 0, std::uint32_t repeat = 1);

/**
 * The texel (column, row) a tile coordinate samples in a T × T tile: edge lines (x or y = 0 or 1) are the
 * tile's outermost texel rows and columns, which neighbouring tiles share.
 */
glm::ivec2 tileTexel(glm::vec2 xy, int tileSize);

/**
 * One bark set: tiles (T × T, RGB or RGBA 8-bit colour; optional tangent-space normal maps of the same size,
 * n = 2c − 1, x along the tile's x, y along its y) in class order: class c's tiles are
 * colour[classFirst[c] … classFirst[c] + classCount[c]), made of K⁴ blocks (K = edgeColours) of
 * classCount[c] / K⁴ variants, block b holding the tiles whose edges are coloured b = e0 + K·e1 + K²·e2 +
 * K³·e3.
 */
struct BarkSet {
  /** The set's source (a photo name, "procedural" or a tile-set directory). */
  std::string name;
  /** Tile side T, texels. */
  int tileSize = 0;
  /** Symmetric edge colours K (1: the paper's one border for every tile). */
  int edgeColours = 1;
  /** The colour tiles, in class order. */
  std::vector<Image> colour;
  /** The normal-map tiles, in the same order (empty: none). */
  std::vector<Image> normal;
  /** Per class: index of its first tile. */
  std::array<std::uint32_t, SYLVA_TREE_MAX_TILE_CLASSES> classFirst{};
  /** Per class: its number of tiles. */
  std::array<std::uint32_t, SYLVA_TREE_MAX_TILE_CLASSES> classCount{};
};

/** Throws sylva::Error "<where>: …" for sets with missing classes, mixed sizes or out-of-range tiles. */
void validate(const BarkSet& set, const std::string& where);

/** K⁴: the edge colourings of a tile with K colours. */
std::uint32_t colourings(int edgeColours);

/**
 * The tile (index into set.colour) of sub-tile `sub` of `repeat` (tileRepeat) of quad `quad` of `piece` in
 * the piece instance with root joint `rootJoint`: in the quad's class (classes without tiles use class 0's,
 * as the renderer does), the block of its edge colouring, the variant by chooseTile() of quad + 256 · sub.
 */
std::uint32_t barkTile(const BarkSet& set, const Piece& piece, const PieceTiling& tiling,
                       std::uint32_t rootJoint, std::uint32_t quad, std::uint32_t sub = 0,
                       std::uint32_t repeat = 1);

/**
 * Where tile coordinate `y` along the grain (0 … 1 over the quad) falls among `repeat` stacked sub-tiles:
 * the sub-tile (0 … repeat − 1) and the coordinate within it (0 … 1).
 */
std::pair<std::uint32_t, float> subTile(float y, std::uint32_t repeat);

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
  /** Directory of `<name>_color_1k.jpg` and `<name>_normal_1k.jpg`: by default the data folder's, which
   * scripts/fetch-sample-data.sh fills (dataDirectory(), whatever the working directory). */
  std::filesystem::path photoDir = dataPath("external/ez-tree/bark");
  /** Synthesised sets are kept here and reused (empty: no cache). */
  std::filesystem::path cacheDir;
  /** Tile construction (tile size, seed, …). */
  texsynth::TileSettings tiles = defaultBarkTiles();
  /** Symmetric edge colours of the tiles (1: one border for all; 2: Wang tiles, 16 colourings). */
  int edgeColours = 2;
  /** Tiles per class and edge colouring. */
  int variants = 1;
  /** Photos are halved until their side is at most this many texels (bark scale and synthesis time). */
  int photoSide = 256;

  /** The tile settings bark sets are synthesised with by default. */
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
  /** The atlas, RGB or RGBA 8-bit. */
  Image image;
  /** Tiles per atlas row. */
  int columns = 1;
  /** Tile rows. */
  int rows = 1;
  /** Tile side, texels. */
  int tileSize = 0;
};
/** The colour tiles of `set` in one atlas image. */
BarkAtlas barkAtlas(const BarkSet& set);
/**
 * UVs (glTF convention: v down the image) of a quad's four corners showing `tile` with `rotation`: the texel
 * centres of the tile's outermost rows and columns, as the renderer samples them.
 */
std::array<glm::vec2, 4> barkAtlasUv(const BarkAtlas& atlas, std::uint32_t tile, int rotation);

/**
 * The quad table of `piece` as the renderer uploads it, per quad x: tile class | rotation << 8 | side flips
 * << 10 | repeat ratio << 16 | its growth << 24 (PieceTiling), y: its four edge ids (quad edge e in bits
 * 8e … 8e + 7).
 */
std::vector<glm::uvec2> quadTileTable(const Piece& piece);

} // namespace sylva::trees
