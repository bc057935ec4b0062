#include <sylva/texsynth/TileSetIo.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/JsonNode.hpp>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <system_error>

namespace sylva::texsynth {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxTiles = 8192;
constexpr int kMaxAtlasSide = 65536;
constexpr const char* kJsonName = "tileset.json";

} // namespace

int TileSetDescription::tileTotal() const {
  int total = 0;
  for (const TileClass& c : set.classes) {
    total += c.tileCount;
  }
  return total;
}

AtlasLayout atlasLayout(int tileCount, bool normals) {
  AtlasLayout layout;
  layout.columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(tileCount)))));
  while (layout.columns * layout.columns < tileCount) {
    ++layout.columns; // guards against a floating-point sqrt just below the integer
  }
  layout.rows = std::max(1, (tileCount + layout.columns - 1) / layout.columns);
  layout.normal = normals ? "normal.png" : "";
  return layout;
}

nlohmann::json toJson(const TileSet& set) {
  const AtlasLayout layout = atlasLayout(static_cast<int>(set.tiles.size()), set.channels == 6);
  nlohmann::json colours = nlohmann::json::array();
  for (const EdgeColour& colour : set.colours) {
    colours.push_back({{"name", colour.name}, {"symmetric", colour.symmetric}});
  }
  nlohmann::json classes = nlohmann::json::array();
  for (const TileClass& c : set.classes) {
    classes.push_back({{"name", c.name},
                       {"edges", {c.edges[0], c.edges[1], c.edges[2], c.edges[3]}},
                       {"interior", c.interior},
                       {"tiles", c.tileCount}});
  }
  nlohmann::json atlas = {{"columns", layout.columns}, {"rows", layout.rows}, {"color", layout.colour}};
  if (!layout.normal.empty()) {
    atlas["normal"] = layout.normal;
  }
  return {{"version", kTileSetVersion}, {"tileSize", set.tileSize},
          {"band", set.band},           {"overlap", set.overlap},
          {"channels", set.channels},   {"colours", colours},
          {"classes", classes},         {"atlas", atlas}};
}

namespace {

/** A plain PNG file name inside the set's directory (no directories, not hidden). */
std::string atlasFileName(const JsonNode& node) {
  const std::string name = node.string();
  if (name.find('/') != std::string::npos || name.find('\\') != std::string::npos || name.front() == '.' ||
      name.size() < 5 || name.substr(name.size() - 4) != ".png") {
    node.error(fmt::format("'{}' must be a plain .png file name in the tile set's directory", name));
  }
  return name;
}

} // namespace

TileSetDescription tileSetFromJson(const nlohmann::json& json, const std::string& where) {
  requireJsonVersion(json, kTileSetVersion, where);
  const JsonNode root(json, where, "");
  root.object({"version", "tileSize", "band", "overlap", "channels", "colours", "classes", "atlas"});
  TileSetDescription d;
  TileSet& set = d.set;
  set.tileSize = root["tileSize"].integer(8, 1024);
  set.band = root["band"].integer(1, set.tileSize / 2);
  set.overlap = root["overlap"].integer(1, set.tileSize / 2);
  if (2 * (set.band + set.overlap) > set.tileSize) {
    root["overlap"].error(fmt::format("band {} + overlap {} must be at most half the tile size {}", set.band,
                                      set.overlap, set.tileSize));
  }
  set.channels = root["channels"].integer(3, 6);
  if (set.channels != 3 && set.channels != 6) {
    root["channels"].error(fmt::format("must be 3 (colour) or 6 (colour and normal), got {}", set.channels));
  }
  const JsonNode colours = root["colours"];
  const std::size_t colourCount = colours.array(1, 64);
  for (std::size_t i = 0; i < colourCount; ++i) {
    const JsonNode colour = colours[i];
    colour.object({"name", "symmetric"});
    set.colours.push_back({colour["name"].string(), colour["symmetric"].boolean()});
  }
  const JsonNode classes = root["classes"];
  const std::size_t classCount = classes.array(1, kMaxTiles);
  int total = 0;
  for (std::size_t i = 0; i < classCount; ++i) {
    const JsonNode node = classes[i];
    node.object({"name", "edges", "interior", "tiles"});
    TileClass c;
    c.name = node["name"].string();
    const JsonNode edges = node["edges"];
    edges.arrayOf(4, "edges 0..3: bottom, right, top, left");
    for (std::size_t e = 0; e < 4; ++e) {
      c.edges[e] = edges[e].integer(0, static_cast<int>(colourCount) - 1);
    }
    c.interior = node["interior"].string(true);
    c.tileCount = node["tiles"].integer(1, kMaxTiles);
    total += c.tileCount;
    if (total > kMaxTiles) {
      node["tiles"].error(fmt::format("the set has more than {} tiles", kMaxTiles));
    }
    set.classes.push_back(std::move(c));
  }
  const JsonNode atlas = root["atlas"];
  atlas.object({"columns", "rows", "color", "normal"});
  d.atlas.columns = atlas["columns"].integer(1, kMaxAtlasSide / set.tileSize);
  d.atlas.rows = atlas["rows"].integer(1, kMaxAtlasSide / set.tileSize);
  d.atlas.colour = atlasFileName(atlas["color"]);
  if (atlas.has("normal")) {
    d.atlas.normal = atlasFileName(atlas["normal"]);
    if (d.atlas.normal == d.atlas.colour) {
      atlas["normal"].error("must differ from 'color'");
    }
  }
  if ((set.channels == 6) != !d.atlas.normal.empty()) {
    atlas.error(set.channels == 6 ? "missing field 'normal' (channels is 6)"
                                  : "field 'normal' given but channels is 3");
  }
  if (d.atlas.columns * d.atlas.rows < total || d.atlas.columns * (d.atlas.rows - 1) >= total) {
    atlas["rows"].error(fmt::format("a {}x{} atlas grid does not hold exactly the {} tiles of the classes "
                                    "(expected {} rows)",
                                    d.atlas.columns, d.atlas.rows, total,
                                    (total + d.atlas.columns - 1) / d.atlas.columns));
  }
  return d;
}

namespace {

/** Copies the tiles into one atlas texture (tile i at column i % columns, row i / columns). */
Texture atlasTexture(const TileSet& set, const AtlasLayout& layout) {
  const int t = set.tileSize;
  Texture atlas = Texture::blank(layout.columns * t, layout.rows * t, set.channels, "atlas");
  for (std::size_t i = 0; i < set.tiles.size(); ++i) {
    const int cx = static_cast<int>(i) % layout.columns;
    const int cy = static_cast<int>(i) / layout.columns;
    for (int y = 0; y < t; ++y) {
      std::memcpy(atlas.at(cx * t, cy * t + y), set.tiles[i].at(0, y),
                  sizeof(float) * static_cast<std::size_t>(t) * set.channels);
    }
  }
  return atlas;
}

void checkSet(const TileSet& set) {
  int total = 0;
  for (const TileClass& c : set.classes) {
    total += c.tileCount;
  }
  if (set.tiles.empty() || static_cast<int>(set.tiles.size()) != total) {
    fail("tile set: {} tiles but the classes count {}", set.tiles.size(), total);
  }
  for (const Texture& tile : set.tiles) {
    if (tile.width != set.tileSize || tile.height != set.tileSize || tile.channels != set.channels) {
      fail("tile set: tile {} is {}x{}x{}, expected {}x{}x{}", tile.name, tile.width, tile.height,
           tile.channels, set.tileSize, set.tileSize, set.channels);
    }
  }
}

} // namespace

void saveTileSet(const fs::path& dir, const TileSet& set, const std::vector<ExtraImage>& extras) {
  checkSet(set);
  for (const ExtraImage& extra : extras) {
    if (extra.fileName.empty() || extra.fileName.find('/') != std::string::npos ||
        extra.fileName.front() == '.' || extra.fileName == kJsonName || extra.fileName == "color.png" ||
        extra.fileName == "normal.png") {
      fail("{}: '{}' is not a plain file name of its own", dir.string(), extra.fileName);
    }
  }
  const nlohmann::json json = toJson(set);
  const AtlasLayout layout = atlasLayout(static_cast<int>(set.tiles.size()), set.channels == 6);
  const Texture atlas = atlasTexture(set, layout);
  const Image colour = colourImage(atlas);
  const Image normal = set.channels == 6 ? normalImage(atlas, NormalGreen::AlongRows) : Image();

  // Everything goes into a temporary sibling directory, which then replaces `dir` in two renames.
  const fs::path target =
      dir.lexically_normal().has_filename() ? dir.lexically_normal() : dir.lexically_normal().parent_path();
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string stem = target.filename().string();
  const fs::path temporary = parent / fmt::format(".{}.tmp.{}", stem, ::getpid());
  const fs::path previous = parent / fmt::format(".{}.old.{}", stem, ::getpid());
  std::error_code ec;
  fs::create_directories(parent, ec);
  fs::remove_all(temporary, ec);
  try {
    if (!fs::create_directory(temporary, ec) || ec) {
      fail("{}: cannot create the directory ({})", temporary.string(), ec.message());
    }
    saveJsonFile(temporary / kJsonName, json);
    saveImage(temporary / layout.colour, colour);
    if (!layout.normal.empty()) {
      saveImage(temporary / layout.normal, normal);
    }
    for (const ExtraImage& extra : extras) {
      saveImage(temporary / extra.fileName, extra.image);
    }
    if (fs::exists(target, ec)) {
      if (!fs::is_directory(target, ec)) {
        fail("{}: exists and is not a directory", target.string());
      }
      fs::rename(target, previous, ec);
      if (ec) {
        fail("{}: cannot replace the directory ({})", target.string(), ec.message());
      }
    }
    fs::rename(temporary, target, ec);
    if (ec) {
      fs::rename(previous, target, ec);
      fail("{}: cannot write the tile set ({})", target.string(), ec.message());
    }
    fs::remove_all(previous, ec);
  } catch (...) {
    fs::remove_all(temporary, ec);
    throw;
  }
}

TileSet loadTileSet(const fs::path& dir) {
  const fs::path jsonPath = dir / kJsonName;
  const TileSetDescription d = tileSetFromJson(loadJsonFile(jsonPath), jsonPath.string());
  TileSet set = d.set;
  const int t = set.tileSize;
  const auto loadAtlas = [&](const std::string& name) {
    const fs::path path = dir / name;
    const Image image = loadImage(path);
    if (image.width() != d.atlas.columns * t || image.height() != d.atlas.rows * t) {
      fail("{}: the atlas is {}x{} but {} (atlas, tileSize) says {}x{}", path.string(), image.width(),
           image.height(), jsonPath.string(), d.atlas.columns * t, d.atlas.rows * t);
    }
    if (image.channels() < 3) {
      fail("{}: the atlas needs 3 channels, it has {}", path.string(), image.channels());
    }
    return image;
  };
  const Image colour = loadAtlas(d.atlas.colour);
  Image normal;
  if (!d.atlas.normal.empty()) {
    normal = loadAtlas(d.atlas.normal);
  }
  const Texture atlas =
      textureFromImages(colour, (dir / d.atlas.colour).string(), normal.empty() ? nullptr : &normal,
                        (dir / d.atlas.normal).string(), NormalGreen::AlongRows);
  const int total = d.tileTotal();
  for (int i = 0; i < total; ++i) {
    Texture tile =
        Texture::blank(t, t, set.channels, fmt::format("{}[{}]", (dir / d.atlas.colour).string(), i));
    const int cx = i % d.atlas.columns;
    const int cy = i / d.atlas.columns;
    for (int y = 0; y < t; ++y) {
      std::memcpy(tile.at(0, y), atlas.at(cx * t, cy * t + y),
                  sizeof(float) * static_cast<std::size_t>(t) * set.channels);
    }
    set.tiles.push_back(std::move(tile));
  }
  return set;
}

void checkTileSetOutput(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    fail("--out: {} exists and is not a directory", dir.string());
  }
  if (std::filesystem::exists(dir, ec) && !std::filesystem::exists(dir / "tileset.json", ec) &&
      !std::filesystem::is_empty(dir, ec)) {
    fail("--out: {} is a directory that holds no tile set; refusing to replace it", dir.string());
  }
}

std::string describeTileSet(const TileSet& set, const std::filesystem::path& dir, double seconds) {
  const AtlasLayout layout = atlasLayout(static_cast<int>(set.tiles.size()), set.channels == 6);
  return fmt::format("wrote {}: {} tiles of {}x{} texels in {} classes, {} edge colour{}, atlas {}x{} tiles "
                     "(color.png{}) in {:.1f} s\n",
                     dir.string(), set.tiles.size(), set.tileSize, set.tileSize, set.classes.size(),
                     set.colours.size(), set.colours.size() == 1 ? "" : "s", layout.columns, layout.rows,
                     set.channels == 6 ? ", normal.png" : "", seconds);
}

} // namespace sylva::texsynth
