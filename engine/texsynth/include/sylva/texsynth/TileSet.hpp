#pragma once

#include <sylva/texsynth/Texture.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sylva {
class Progress;
}

namespace sylva::texsynth {

/**
 * Edges of a T × T tile. Row 0 is edge 0 (bottom: row 0 is uploaded first, so it is v = 0 in GL), column T−1
 * is edge 1 (right), row T−1 is edge 2 (top), column 0 is edge 3 (left). Edges 0 and 2 are read by increasing
 * column, edges 1 and 3 by increasing row.
 */
enum Edge : int { kEdgeBottom = 0, kEdgeRight = 1, kEdgeTop = 2, kEdgeLeft = 3 };

/**
 * An edge colour. Two tiles may meet along edges of the same colour; their edge texel lines are then
 * bit-identical (shared), and the bands next to the edge come from the two sides of one source strip so the
 * texture continues across.
 *
 * ORIENTED (symmetric = false): Wang matching on an axis-aligned grid: A.edge1 == B.edge3 for B right of A,
 * A.edge2 == C.edge0 for C above A. Edges 0/2 come from one horizontal source strip and edges 1/3 from one
 * vertical source strip, both unrotated (so bark grooves keep their direction), so matching edges are
 * identical in every channel.
 *
 * SYMMETRIC: the line is a palindrome (P[i] == P[T−1−i]) and the same on all four edges of every tile that
 * has the colour; its band is the same on all four edges, rotated by the edge's quarter turn. Such an edge
 * matches any edge of any tile with the colour, in either direction, under any 90° rotation of either tile;
 * the texture continues across as a reflection. Normals: the band's second half mirrors the first (the
 * component along the edge negated) and on the line the component across the edge is 0, so lines also agree
 * in normal when expressed in the edge's frame (along its reading direction).
 *
 * Every line's first and last texel is the set's one corner texel (tile corners are shared by up to four
 * tiles), with a flat normal (0, 0, 1).
 */
struct EdgeColour {
  std::string name;                                   ///< e.g. "wang0" or "bark", unique in the set
  bool symmetric = false;                             ///< its texel line reads the same both ways
  bool operator==(const EdgeColour&) const = default; ///< same name and symmetry
};

/** A class of tiles: the same four edge colours; variants differ only in their interiors. */
struct TileClass {
  /** e.g. "wang-0101" (its edge colours, bottom, right, top, left). */
  std::string name;
  /** Colour id of edges 0 (bottom), 1 (right), 2 (top), 3 (left). */
  std::array<int, 4> edges{};
  /** How the interiors were chosen (free text, e.g. "plain", "rough half"). */
  std::string interior;
  /** Number of tiles (variants) of the class. */
  int tileCount = 0;
  /** Same name, edges, interior and count. */
  bool operator==(const TileClass&) const = default;
};

/**
 * A set of edge-constrained tiles: colours, classes and the tiles ordered by class (class 0's tiles first).
 * Every tile is a tileSize × tileSize Texture with the set's channels (3, or 6 with normals).
 */
struct TileSet {
  /** Tile side T, texels. */
  int tileSize = 128;
  /** Width of the frame bands of pure source texels next to each edge, texels. */
  int band = 16;
  /** Width of the ring inside the frame where the interior is stitched in with min-error cuts, texels. */
  int overlap = 21;
  /** 3 (RGB) or 6 (RGB + normal). */
  int channels = 3;
  std::vector<EdgeColour> colours; ///< by colour id
  std::vector<TileClass> classes;  ///< by class index
  std::vector<Texture> tiles;      ///< ordered by class, class 0's first

  /** Index of the first tile of `classIndex`. */
  int firstTile(int classIndex) const;
  /** Number of tiles of `classIndex`. */
  int tileCount(int classIndex) const { return classes.at(static_cast<std::size_t>(classIndex)).tileCount; }
  /** The class of tile `tile`. */
  int classOf(int tile) const;
  /** Colour id of edge `edge` of tile `tile`. */
  int edgeColour(int tile, int edge) const {
    return classes.at(static_cast<std::size_t>(classOf(tile))).edges.at(static_cast<std::size_t>(edge));
  }
};

/** Settings of tile construction. */
struct TileSettings {
  /** Tile side T, texels (8..1024). */
  int tileSize = 128;
  /** Frame band width, texels; 0 picks T / 8 (at least 1). */
  int band = 0;
  /** Overlap ring width, texels; 0 picks T / 6 (at least 1). band + overlap must be at most T / 2. */
  int overlap = 0;
  /** Interior choice tolerance: candidates within (1 + tolerance) · min SSD (0..10). */
  double tolerance = 0.1;
  /** Seed of strip positions and interior choice. */
  std::uint64_t seed = 1;
  /** Most interior candidate positions per source (16..1,000,000), on a regular grid. */
  int maxCandidates = 2048;

  /** `band`, or T / 8 (at least 1) when 0. */
  int effectiveBand() const;
  /** `overlap`, or T / 6 (at least 1) when 0. */
  int effectiveOverlap() const;
};

/** Throws a one-line sylva::Error naming the field for bad settings or the photo for a too-small photo. */
void validate(const TileSettings& settings, const std::vector<Texture>& photos);

/**
 * A complete Wang tile set (Cohen et al. 2003) for `colourCount` oriented colours (1..3): one class per
 * assignment of colours to the 4 edges (K⁴ classes; class index = e0 + K·e1 + K²·e2 + K³·e3), each with
 * `variantsPerClass` tiles (1..64). Each colour's strip is a different seeded region of `source`.
 */
TileSet wangTileSet(const Texture& source, int colourCount, int variantsPerClass,
                    const TileSettings& settings, Progress* progress = nullptr);

/** Bark classes: 0 plain bark quads, 1 quads next to a fork, 2 quads in a fork's crotch. */
enum BarkClass : int { kBarkPlain = 0, kBarkFork = 1, kBarkCrotch = 2 };

/**
 * The trees' bark set: `edgeColours` (K, 1..3) SYMMETRIC colours (all sharing the corner texel) and, for each
 * of the three bark kinds (BarkClass), one class per assignment of the colours to the four edges — class
 * kind · K⁴ + e0 + K·e1 + K²·e2 + K³·e3 — of `variantsPerClass` tiles (1..64). With K = 1 that is the paper's
 * case: three classes whose tiles all share one border. With K > 1 any colouring of a mesh's edges finds its
 * tiles, and borders vary (Cohen et al. 2003 with symmetric colours). Interiors: kind 0 from all candidates,
 * kind 1 from the rougher half (luminance variance), kind 2 from the roughest quarter, each with its own seed
 * stream. `photos` (1..16) share a channel count; the edge bands come from photos[0].
 */
TileSet barkTileSet(const std::vector<Texture>& photos, int variantsPerClass, const TileSettings& settings,
                    Progress* progress = nullptr, int edgeColours = 1);

/**
 * A stochastic tiling of w × h tiles (1..4096 each), row-major with row 0 at the bottom (tile (x, y + 1) is
 * above (x, y)): each tile is drawn uniformly among the tiles whose left edge matches its left neighbour's
 * right edge and whose bottom edge matches its lower neighbour's top edge. Throws sylva::Error when no tile
 * fits (an incomplete set).
 */
std::vector<int> tileGrid(const TileSet& set, int w, int h, std::uint64_t seed);

/**
 * A closed ring of n tiles (1..4096) around a tube: tile j's right edge meets tile j+1's left edge and tile
 * n−1's right edge meets tile 0's left edge. Seam colours are drawn first (so the ring closes; for n = 6 the
 * hexagonal rim's constraint), then each tile among those with the two seam colours on edges 3 and 1.
 * Throws sylva::Error when no tile fits.
 */
std::vector<int> tileRing(const TileSet& set, int n, std::uint64_t seed);

/**
 * Edge `edge` of a tile as T texels read in the edge's direction (edges 0/2 by increasing column, 1/3 by
 * increasing row), all channels as stored (tile frame).
 */
std::vector<float> edgeLine(const Texture& tile, int edge);

/** Tiles laid out in a grid (tiles[i] at column i % columns, row i / columns), `grid` as from tileGrid. */
Texture tilingPreview(const TileSet& set, const std::vector<int>& grid, int w, int h);

} // namespace sylva::texsynth
