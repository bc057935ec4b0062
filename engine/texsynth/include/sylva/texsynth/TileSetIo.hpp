#pragma once

#include <sylva/texsynth/TileSet.hpp>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace sylva::texsynth {

/** Version of tileset.json this build reads and writes. */
constexpr int kTileSetVersion = 1;

/** The atlas layout named by tileset.json. */
struct AtlasLayout {
  int columns = 1; ///< tiles per atlas row
  int rows = 1;    ///< tile rows
  /** Colour atlas file name in the set's directory. */
  std::string colour = "color.png";
  /** Normal atlas file name, "" when the set has no normals. */
  std::string normal;
};

/** A tile set without its tiles, as described by tileset.json. */
struct TileSetDescription {
  TileSet set;       ///< everything but `tiles`
  AtlasLayout atlas; ///< where the tiles are stored
  /** Tiles over all classes. */
  int tileTotal() const;
};

/**
 * The atlas grid for n tiles: columns = ceil(sqrt(n)), rows = ceil(n / columns). Tile i sits at column
 * i % columns, row i / columns; atlas row 0 is the top of the PNG (its first rows), and inside a cell the
 * tile's row 0 (edge 0, v = 0) is the cell's first (top) PNG row: rows are stored in upload order.
 */
AtlasLayout atlasLayout(int tileCount, bool normals);

/** tileset.json of a set (version, sizes, colours, classes, atlas). */
nlohmann::json toJson(const TileSet& set);

/**
 * Strict parse of tileset.json: unknown fields, wrong types, out-of-range values, colour ids that do not
 * exist, tile counts that disagree with the atlas grid → one-line sylva::Error `<where>: <field>: <reason>`.
 */
TileSetDescription tileSetFromJson(const nlohmann::json& json, const std::string& where);

/** An extra picture written into a tile set's directory (e.g. a preview of a tiling). */
struct ExtraImage {
  std::string fileName; ///< plain file name, .png or .exr
  Image image;          ///< the picture
};

/**
 * Writes `dir` with tileset.json, color.png and (with normals) normal.png (8-bit; normals c = (n + 1) / 2
 * with green along rows, +v), plus `extras`. Atomic: everything is written into a temporary sibling
 * directory, which then replaces `dir`; on error nothing is left. Throws sylva::Error naming the path.
 */
void saveTileSet(const std::filesystem::path& dir, const TileSet& set,
                 const std::vector<ExtraImage>& extras = {});

/**
 * Reads a directory written by saveTileSet. Errors (one line, naming the file and field): missing files,
 * bad JSON, atlas sizes that disagree with tileset.json.
 */
TileSet loadTileSet(const std::filesystem::path& dir);

/**
 * Checks, before a tile set is built, that saveTileSet may write `dir`: throws sylva::Error naming --out when
 * it is a file, or a non-empty directory without a tileset.json (which would be replaced).
 */
void checkTileSetOutput(const std::filesystem::path& dir);

/** "wrote DIR: N tiles of SxS texels in C classes, E edge colours, atlas CxR tiles (color.png…) in T s\n". */
std::string describeTileSet(const TileSet& set, const std::filesystem::path& dir, double seconds);

} // namespace sylva::texsynth
