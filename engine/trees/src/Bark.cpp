#include <sylva/trees/Bark.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/texsynth/Procedural.hpp>
#include <sylva/texsynth/TileSetIo.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

namespace sylva::trees {

std::vector<std::uint8_t> quadTileRotations(const Piece& piece) {
  // Graph distance of every vertex from the root rim over quad edges (breadth first).
  const std::size_t n = piece.vertices.size();
  std::vector<std::vector<std::uint32_t>> neighbours(n);
  for (const auto& q : piece.quads) {
    for (std::size_t e = 0; e < 4; ++e) {
      neighbours[q[e]].push_back(q[(e + 1) % 4]);
      neighbours[q[(e + 1) % 4]].push_back(q[e]);
    }
  }
  constexpr int kFar = std::numeric_limits<int>::max() / 4;
  std::vector<int> distance(n, kFar);
  std::queue<std::uint32_t> open;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (piece.vertices[v].rim == 0) {
      distance[v] = 0;
      open.push(v);
    }
  }
  while (!open.empty()) {
    const std::uint32_t v = open.front();
    open.pop();
    for (std::uint32_t w : neighbours[v]) {
      if (distance[w] == kFar) {
        distance[w] = distance[v] + 1;
        open.push(w);
      }
    }
  }
  // Ties (quads whose sides climb equally) go to the rotation whose y axis climbs most in model space along
  // the piece axis, then to the smallest rotation, so the choice is deterministic.
  std::vector<std::uint8_t> out;
  out.reserve(piece.quads.size());
  for (const auto& q : piece.quads) {
    int best = 0;
    float bestScore = -std::numeric_limits<float>::infinity();
    for (int r = 0; r < 4; ++r) {
      const auto c0 = q[static_cast<std::size_t>(r)];
      const auto c1 = q[static_cast<std::size_t>((r + 1) % 4)];
      const auto c2 = q[static_cast<std::size_t>((r + 2) % 4)];
      const auto c3 = q[static_cast<std::size_t>((r + 3) % 4)];
      // y runs c0 → c3 and c1 → c2.
      const float climb = static_cast<float>((distance[c3] - distance[c0]) + (distance[c2] - distance[c1]));
      const float rise = (piece.vertices[c3].position.y - piece.vertices[c0].position.y) +
                         (piece.vertices[c2].position.y - piece.vertices[c1].position.y);
      const float score = climb * 1000.0f + rise;
      if (score > bestScore) {
        bestScore = score;
        best = r;
      }
    }
    out.push_back(static_cast<std::uint8_t>(best));
  }
  return out;
}

glm::vec2 tileCoord(glm::vec2 uv, int rotation) {
  switch (rotation & 3) {
  case 0:
    return uv;
  case 1:
    return {uv.y, 1.0f - uv.x};
  case 2:
    return {1.0f - uv.x, 1.0f - uv.y};
  default:
    return {1.0f - uv.y, uv.x};
  }
}

std::uint32_t instanceTileSeed(std::uint32_t rootJoint) {
  return lowbias32(rootJoint * 0x9e3779b9u + 0x7f4a7c15u);
}

std::uint32_t chooseTile(std::uint32_t seed, std::uint32_t quad, std::uint32_t first, std::uint32_t count) {
  return first + lowbias32(seed ^ (quad * 0x85ebca6bu + 0x27d4eb2fu)) % count;
}

glm::ivec2 tileTexel(glm::vec2 xy, int tileSize) {
  const float last = static_cast<float>(tileSize - 1);
  return {static_cast<int>(std::lround(std::clamp(xy.x, 0.0f, 1.0f) * last)),
          static_cast<int>(std::lround(std::clamp(xy.y, 0.0f, 1.0f) * last))};
}

void validate(const BarkSet& set, const std::string& where) {
  if (set.tileSize < 4 || set.tileSize > 4096) {
    fail("{}: tile size {} (4 … 4096)", where, set.tileSize);
  }
  if (set.colour.empty()) {
    fail("{}: no tiles", where);
  }
  if (!set.normal.empty() && set.normal.size() != set.colour.size()) {
    fail("{}: {} normal maps for {} tiles", where, set.normal.size(), set.colour.size());
  }
  for (std::size_t c = 0; c < set.classCount.size(); ++c) {
    if (set.classCount[c] == 0) {
      continue;
    }
    if (set.classFirst[c] + set.classCount[c] > set.colour.size()) {
      fail("{}: class {} tiles {} … {} beyond the {} tiles", where, c, set.classFirst[c],
           set.classFirst[c] + set.classCount[c] - 1, set.colour.size());
    }
  }
  if (set.classCount[0] == 0) {
    fail("{}: class 0 (plain bark) has no tiles", where);
  }
  if (set.edgeColours < 1 || set.edgeColours > 3) {
    fail("{}: {} edge colours (1 … 3)", where, set.edgeColours);
  }
  for (std::size_t c = 0; c < set.classCount.size(); ++c) {
    if (set.classCount[c] % colourings(set.edgeColours) != 0) {
      fail("{}: class {} has {} tiles, not a multiple of the {} edge colourings", where, c, set.classCount[c],
           colourings(set.edgeColours));
    }
  }
  auto check = [&](const Image& image, std::size_t i, const char* kind) {
    if (image.width() != set.tileSize || image.height() != set.tileSize) {
      fail("{}: {} tile {} is {}x{}, not {}x{}", where, kind, i, image.width(), image.height(), set.tileSize,
           set.tileSize);
    }
    if (image.type() != PixelType::U8 || image.channels() < 3) {
      fail("{}: {} tile {} must be 8-bit RGB or RGBA", where, kind, i);
    }
  };
  for (std::size_t i = 0; i < set.colour.size(); ++i) {
    check(set.colour[i], i, "colour");
  }
  for (std::size_t i = 0; i < set.normal.size(); ++i) {
    check(set.normal[i], i, "normal");
  }
}

namespace {

/** How far vertex `v` moves along the model y axis per unit of stretch − 1 (leafBind: leaf joints' binds move
 * up by their height × (stretch − 1); linear blend skinning carries the vertex with its weights). */
float stretchRate(const Piece& piece, const PieceVertex& v) {
  float rate = 0.0f;
  for (std::size_t k = 0; k < 4; ++k) {
    const std::size_t j = v.joints[k];
    if (j < piece.joints.size()) {
      rate += v.weights[static_cast<int>(k)] * piece.joints[j].bind[3].y;
    }
  }
  return rate;
}

/** PieceTiling::repeat: groups of quads joined over side edges (union-find), each group's mean ratio and
 * growth, or one tile where a side edge of the group is a rim or not a side of its other quad. */
std::vector<std::array<std::uint8_t, 2>> quadRepeats(const Piece& piece, const PieceTiling& tiling) {
  const std::size_t count = piece.quads.size();
  std::vector<std::size_t> parent(count);
  for (std::size_t q = 0; q < count; ++q) {
    parent[q] = q;
  }
  auto find = [&](std::size_t q) {
    while (parent[q] != q) {
      parent[q] = parent[parent[q]];
      q = parent[q];
    }
    return q;
  };
  auto key = [](std::uint32_t a, std::uint32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  // Tile side k of quad q is quad edge (rotation + k) mod 4; sides 1 and 3 run along the grain.
  auto side = [&](std::size_t q, std::size_t e) { return ((e + 4 - tiling.rotation[q]) % 4) % 2 == 1; };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::pair<std::size_t, std::size_t>>> owners;
  for (std::size_t q = 0; q < count; ++q) {
    for (std::size_t e = 0; e < 4; ++e) {
      owners[key(piece.quads[q][e], piece.quads[q][(e + 1) % 4])].push_back({q, e});
    }
  }
  // An edge along the grain of both its quads joins their groups (they split it alike). One along the grain
  // of one quad only, or on a rim, keeps that quad's group to one tile: the other side sees one tile's line.
  std::vector<bool> single(count, false);
  for (const auto& [edge, list] : owners) {
    const bool both =
        list.size() == 2 && side(list[0].first, list[0].second) && side(list[1].first, list[1].second);
    if (both) {
      parent[find(list[0].first)] = find(list[1].first);
      continue;
    }
    for (const auto& o : list) {
      if (side(o.first, o.second)) {
        single[o.first] = true;
      }
    }
  }
  // Per group: summed side-edge lengths and growth rates, and summed widths (the tile-x edges).
  struct Sums {
    double length = 0.0, growth = 0.0, width = 0.0;
    int sides = 0, widths = 0;
    bool single = false;
  };
  std::vector<Sums> groups(count);
  for (std::size_t q = 0; q < count; ++q) {
    Sums& g = groups[find(q)];
    g.single = g.single || single[q];
    const int r = tiling.rotation[q];
    auto corner = [&](int c) -> const PieceVertex& {
      return piece.vertices[piece.quads[q][static_cast<std::size_t>((r + c) % 4)]];
    };
    // The tile's y runs corner r → r + 3 and r + 1 → r + 2; its x runs r → r + 1 and r + 3 → r + 2.
    for (const auto& [from, to] : {std::pair{0, 3}, std::pair{1, 2}}) {
      const glm::vec3 d = corner(to).position - corner(from).position;
      const float length = glm::length(d);
      g.length += length;
      if (length > 0.0f) {
        g.growth += (stretchRate(piece, corner(to)) - stretchRate(piece, corner(from))) * d.y / length;
      }
      ++g.sides;
    }
    for (const auto& [from, to] : {std::pair{0, 1}, std::pair{3, 2}}) {
      g.width += glm::length(corner(to).position - corner(from).position);
      ++g.widths;
    }
  }
  std::vector<std::array<std::uint8_t, 2>> out(count, {16, 0});
  for (std::size_t q = 0; q < count; ++q) {
    const Sums& g = groups[find(q)];
    const double width = g.width / std::max(g.widths, 1);
    if (g.single || !(width > 1e-4)) {
      continue;
    }
    auto fixed = [](double x) {
      return static_cast<std::uint8_t>(std::clamp(std::lround(x * 16.0), 0L, 255L));
    };
    out[q] = {fixed(g.length / g.sides / width), fixed(std::max(g.growth / g.sides, 0.0) / width)};
  }
  return out;
}

} // namespace

PieceTiling pieceTiling(const Piece& piece) {
  PieceTiling tiling;
  tiling.rotation = quadTileRotations(piece);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  auto key = [](std::uint32_t a, std::uint32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  for (const auto& q : piece.quads) {
    for (std::size_t e = 0; e < 4; ++e) {
      ++uses[key(q[e], q[(e + 1) % 4])];
    }
  }
  // Interior edges (shared by two quads) numbered in order of their vertex pairs: a stable id per piece.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint8_t> ids;
  for (const auto& [edge, n] : uses) {
    if (n >= 2) {
      if (ids.size() >= kRimEdge) {
        fail("piece '{}': more than {} interior edges for bark tiles", piece.name, int{kRimEdge});
      }
      ids.emplace(edge, static_cast<std::uint8_t>(ids.size()));
    }
  }
  for (const auto& q : piece.quads) {
    std::array<std::uint8_t, 4> e{};
    for (std::size_t k = 0; k < 4; ++k) {
      const auto it = ids.find(key(q[k], q[(k + 1) % 4]));
      e[k] = it == ids.end() ? kRimEdge : it->second;
    }
    tiling.edges.push_back(e);
  }
  tiling.repeat = quadRepeats(piece, tiling);
  for (std::size_t q = 0; q < piece.quads.size(); ++q) {
    const auto& quad = piece.quads[q];
    const std::size_t r = tiling.rotation[q];
    // Side 1 runs corner r + 1 → r + 2 along the tile's y, side 3 corner r → r + 3.
    const bool flip1 = quad[(r + 1) % 4] > quad[(r + 2) % 4];
    const bool flip3 = quad[r] > quad[(r + 3) % 4];
    tiling.sideFlip.push_back(static_cast<std::uint8_t>((flip1 ? 1 : 0) | (flip3 ? 2 : 0)));
  }
  return tiling;
}

std::uint32_t tileStretch(float stretch) {
  return static_cast<std::uint32_t>(std::clamp(std::lround(stretch * 16.0f), 1L, 255L));
}

std::uint32_t tileRepeat(const PieceTiling& tiling, std::size_t quad, std::uint32_t stretch) {
  if (quad >= tiling.repeat.size()) {
    return 1;
  }
  const int ratio = tiling.repeat[quad][0];
  const int growth = tiling.repeat[quad][1];
  // (ratio + (stretch / 16 − 1) · growth) / 16, rounded, in integers: both sides compute the same bits.
  const int scaled = ratio * 16 + (static_cast<int>(stretch) - 16) * growth + 128;
  const int n = scaled <= 0 ? 1 : scaled / 256;
  return static_cast<std::uint32_t>(std::clamp(n, 1, static_cast<int>(kMaxTileRepeat)));
}

std::pair<std::uint32_t, float> subTile(float y, std::uint32_t repeat) {
  const float along = y * static_cast<float>(repeat);
  const auto sub =
      std::min(static_cast<std::uint32_t>(std::max(std::floor(along), 0.0f)), std::max(repeat, 1u) - 1u);
  return {sub, along - static_cast<float>(sub)};
}

std::uint32_t sideEdgeColour(std::uint32_t seed, std::uint8_t edge, std::uint32_t part,
                             std::uint32_t colours) {
  if (edge == kRimEdge || colours <= 1) {
    return 0;
  }
  return lowbias32(seed ^ (std::uint32_t{edge} * 0x9e3779b9u + 0x165667b1u + part * 0x68e31da4u)) % colours;
}

std::uint32_t innerEdgeColour(std::uint32_t seed, std::uint32_t quad, std::uint32_t sub,
                              std::uint32_t colours) {
  if (colours <= 1) {
    return 0;
  }
  return lowbias32(seed ^ (quad * 0x2c1b3c6du + sub * 0x297a2d39u + 0x1b873593u)) % colours;
}

std::uint32_t edgeColour(std::uint32_t seed, std::uint8_t edge, std::uint32_t colours) {
  if (edge == kRimEdge || colours <= 1) {
    return 0;
  }
  return lowbias32(seed ^ (std::uint32_t{edge} * 0x9e3779b9u + 0x165667b1u)) % colours;
}

std::uint32_t quadColouring(const PieceTiling& tiling, std::size_t quad, std::uint32_t seed,
                            std::uint32_t colours, std::uint32_t sub, std::uint32_t repeat) {
  const auto q = static_cast<std::uint32_t>(quad);
  std::uint32_t index = 0;
  std::uint32_t weight = 1;
  for (std::size_t k = 0; k < 4; ++k) {
    const std::size_t e = (tiling.rotation[quad] + k) % 4;
    std::uint32_t colour = 0;
    if (k == 0 && sub > 0) {
      colour = innerEdgeColour(seed, q, sub, colours);
    } else if (k == 2 && sub + 1 < repeat) {
      colour = innerEdgeColour(seed, q, sub + 1, colours);
    } else if (k % 2 == 1) {
      const bool flip = quad < tiling.sideFlip.size() && ((tiling.sideFlip[quad] >> (k / 2)) & 1u) != 0;
      colour = sideEdgeColour(seed, tiling.edges[quad][e], flip ? repeat - 1 - sub : sub, colours);
    } else {
      colour = edgeColour(seed, tiling.edges[quad][e], colours);
    }
    index += colour * weight;
    weight *= colours;
  }
  return index;
}

std::uint32_t colourings(int edgeColours) {
  const auto k = static_cast<std::uint32_t>(std::max(edgeColours, 1));
  return k * k * k * k;
}

std::uint32_t barkTile(const BarkSet& set, const Piece& piece, const PieceTiling& tiling,
                       std::uint32_t rootJoint, std::uint32_t quad, std::uint32_t sub, std::uint32_t repeat) {
  const std::uint32_t cls = quad < piece.tileClass.size() ? piece.tileClass[quad] : 0u;
  std::size_t c = std::min<std::size_t>(cls, SYLVA_TREE_MAX_TILE_CLASSES - 1);
  if (set.classCount[c] == 0) {
    c = 0;
  }
  const std::uint32_t seed = instanceTileSeed(rootJoint);
  const std::uint32_t variants = std::max(set.classCount[c] / colourings(set.edgeColours), 1u);
  const std::uint32_t block = quadColouring(
      tiling, quad, seed, static_cast<std::uint32_t>(std::max(set.edgeColours, 1)), sub, repeat);
  return chooseTile(seed, quad + 256u * sub, set.classFirst[c] + block * variants, variants);
}

BarkSet barkSetFromTiles(const texsynth::TileSet& tiles, const std::string& name) {
  // Classes come in blocks of K⁴ edge colourings per bark kind (texsynth::barkTileSet).
  const int k = static_cast<int>(tiles.colours.size());
  const std::size_t block = colourings(k);
  if (k < 1 || k > 3 || tiles.classes.empty() || tiles.classes.size() % block != 0 ||
      tiles.classes.size() / block > SYLVA_TREE_MAX_TILE_CLASSES) {
    fail("bark set '{}': {} tile classes for {} edge colours (1 … {} kinds of {} colourings)", name,
         tiles.classes.size(), k, SYLVA_TREE_MAX_TILE_CLASSES, block);
  }
  for (std::size_t c = 0; c < tiles.classes.size(); ++c) {
    const std::array<int, 4>& e = tiles.classes[c].edges;
    const auto combo = static_cast<int>(c % block);
    if (e != std::array<int, 4>{combo % k, combo / k % k, combo / (k * k) % k, combo / (k * k * k) % k} ||
        tiles.classes[c].tileCount != tiles.classes[c - c % block].tileCount ||
        std::any_of(tiles.colours.begin(), tiles.colours.end(),
                    [](const texsynth::EdgeColour& colour) { return !colour.symmetric; })) {
      fail("bark set '{}': class {} is not the edge colouring {} of symmetric colours with as many tiles as "
           "its kind's others",
           name, c, combo);
    }
  }
  BarkSet set;
  set.name = name;
  set.tileSize = tiles.tileSize;
  set.edgeColours = k;
  for (const texsynth::Texture& tile : tiles.tiles) {
    set.colour.push_back(texsynth::colourImage(tile));
    if (tile.hasNormals()) {
      set.normal.push_back(texsynth::normalImage(tile, texsynth::NormalGreen::AlongRows));
    }
  }
  if (set.normal.size() != set.colour.size()) {
    set.normal.clear();
  }
  for (std::size_t kind = 0; kind < tiles.classes.size() / block; ++kind) {
    set.classFirst[kind] = static_cast<std::uint32_t>(tiles.firstTile(static_cast<int>(kind * block)));
    set.classCount[kind] = static_cast<std::uint32_t>(block) *
                           static_cast<std::uint32_t>(tiles.tileCount(static_cast<int>(kind * block)));
  }
  validate(set, "bark set '" + name + "'");
  return set;
}

texsynth::TileSettings BarkSources::defaultBarkTiles() {
  texsynth::TileSettings s;
  s.tileSize = 128;
  s.seed = 1;
  s.maxCandidates = 512;
  return s;
}

namespace {

/** Halves a texture (2 × 2 box filter) until its larger side is at most `side`. */
texsynth::Texture shrink(texsynth::Texture t, int side) {
  while (std::max(t.width, t.height) > side && std::min(t.width, t.height) >= 2) {
    texsynth::Texture half = texsynth::Texture::blank(t.width / 2, t.height / 2, t.channels, t.name);
    for (int y = 0; y < half.height; ++y) {
      for (int x = 0; x < half.width; ++x) {
        float* out = half.at(x, y);
        for (int c = 0; c < t.channels; ++c) {
          out[c] = 0.25f * (t.at(2 * x, 2 * y)[c] + t.at(2 * x + 1, 2 * y)[c] + t.at(2 * x, 2 * y + 1)[c] +
                            t.at(2 * x + 1, 2 * y + 1)[c]);
        }
      }
    }
    t = std::move(half);
  }
  return t;
}

std::string cacheKey(const std::string& source, const BarkSources& s) {
  return fmt::format("{}-t{}-v{}-k{}-s{}-p{}-c{}-b{}-o{}", source, s.tiles.tileSize, s.variants,
                     s.edgeColours, s.tiles.seed, s.photoSide, s.tiles.maxCandidates, s.tiles.band,
                     s.tiles.overlap);
}

} // namespace

std::string barkSource(const std::string& photo, const BarkSources& sources) {
  if (sources.mode != "auto" && sources.mode != "procedural") {
    return sources.mode;
  }
  if (sources.mode == "auto" && photo != "procedural" &&
      std::filesystem::exists(sources.photoDir / (photo + "_color_1k.jpg"))) {
    return photo;
  }
  return "procedural";
}

BarkSet barkSetFromSource(const std::string& source, const BarkSources& sources) {
  const bool fromDir = sources.mode != "auto" && sources.mode != "procedural";
  texsynth::TileSet tiles;
  const std::filesystem::path cached = sources.cacheDir.empty() || fromDir
                                           ? std::filesystem::path{}
                                           : sources.cacheDir / cacheKey(source, sources);
  if (fromDir) {
    tiles = texsynth::loadTileSet(source);
    log::info("bark: tile set {}", source);
  } else if (!cached.empty() && std::filesystem::exists(cached / "tileset.json")) {
    tiles = texsynth::loadTileSet(cached);
    log::info("bark '{}': cached tile set {}", source, cached.string());
  } else {
    const std::filesystem::path colour = sources.photoDir / (source + "_color_1k.jpg");
    const std::filesystem::path normal = sources.photoDir / (source + "_normal_1k.jpg");
    texsynth::Texture photoTexture =
        source == "procedural"
            ? texsynth::proceduralBark(sources.photoSide, sources.tiles.seed)
            : texsynth::loadPhotoTexture(colour,
                                         std::filesystem::exists(normal) ? normal : std::filesystem::path{});
    photoTexture = shrink(std::move(photoTexture), sources.photoSide);
    const std::vector<texsynth::Texture> photos{std::move(photoTexture)};
    // A narrow frame (the only part all tiles share) and a wide ring where the interior is cut in: the
    // shared border is what shows as a pattern, so it is kept to a few texels.
    texsynth::TileSettings settings = sources.tiles;
    if (settings.band == 0) {
      settings.band = std::max(2, settings.tileSize / 40);
    }
    if (settings.overlap == 0) {
      settings.overlap = std::max(2, settings.tileSize / 8);
    }
    tiles = texsynth::barkTileSet(photos, sources.variants, settings, nullptr, sources.edgeColours);
    log::info("bark '{}': synthesised {} tiles of {}²", source, tiles.tiles.size(), tiles.tileSize);
    if (!cached.empty()) {
      try {
        texsynth::saveTileSet(cached, tiles);
      } catch (const Error& e) {
        log::warn("bark cache not written: {}", e.what());
      }
    }
  }
  return barkSetFromTiles(tiles, source);
}

std::vector<BarkSet> barkSetsFor(const Forest& forest, const BarkSources& sources,
                                 std::vector<int>& speciesSet) {
  std::vector<BarkSet> sets;
  speciesSet.clear();
  auto setFor = [&](const std::string& photo) -> int {
    const std::string source = barkSource(photo, sources);
    const auto known =
        std::find_if(sets.begin(), sets.end(), [&](const BarkSet& s) { return s.name == source; });
    if (known != sets.end()) {
      return static_cast<int>(known - sets.begin());
    }
    sets.push_back(barkSetFromSource(source, sources));
    return static_cast<int>(sets.size() - 1);
  };
  for (const Species& species : forest.species) {
    speciesSet.push_back(setFor(species.bark));
  }
  if (sets.empty()) {
    speciesSet.push_back(setFor("procedural"));
  }
  return sets;
}

BarkAtlas barkAtlas(const BarkSet& set) {
  BarkAtlas atlas;
  const int n = static_cast<int>(set.colour.size());
  atlas.tileSize = set.tileSize;
  atlas.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  atlas.rows = (n + atlas.columns - 1) / atlas.columns;
  atlas.image = Image(atlas.columns * set.tileSize, atlas.rows * set.tileSize, 3, PixelType::U8);
  for (int i = 0; i < n; ++i) {
    const Image& tile = set.colour[static_cast<std::size_t>(i)];
    const int x0 = (i % atlas.columns) * set.tileSize;
    const int y0 = (i / atlas.columns) * set.tileSize;
    for (int y = 0; y < set.tileSize; ++y) {
      for (int x = 0; x < set.tileSize; ++x) {
        for (int c = 0; c < 3; ++c) {
          atlas.image.set(x0 + x, y0 + y, c, tile.get(x, y, c));
        }
      }
    }
  }
  return atlas;
}

std::array<glm::vec2, 4> barkAtlasUv(const BarkAtlas& atlas, std::uint32_t tile, int rotation) {
  const std::array<glm::vec2, 4> corners{glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)};
  const auto size = static_cast<float>(atlas.tileSize);
  const glm::vec2 cell(static_cast<float>(static_cast<int>(tile) % atlas.columns) * size,
                       static_cast<float>(static_cast<int>(tile) / atlas.columns) * size);
  const glm::vec2 extent(static_cast<float>(atlas.image.width()), static_cast<float>(atlas.image.height()));
  std::array<glm::vec2, 4> out{};
  for (std::size_t c = 0; c < 4; ++c) {
    // Texel centres of the tile's outermost rows and columns on the quad's edges, as the renderer samples.
    out[c] = (cell + 0.5f + tileCoord(corners[c], rotation) * (size - 1.0f)) / extent;
  }
  return out;
}

std::vector<glm::uvec2> quadTileTable(const Piece& piece) {
  const PieceTiling tiling = pieceTiling(piece);
  std::vector<glm::uvec2> out(piece.quads.size());
  for (std::size_t q = 0; q < out.size(); ++q) {
    const std::uint32_t cls = q < piece.tileClass.size() ? piece.tileClass[q] : 0u;
    out[q].x = std::min<std::uint32_t>(cls, SYLVA_TREE_MAX_TILE_CLASSES - 1) |
               (std::uint32_t{tiling.rotation[q]} << 8) | (std::uint32_t{tiling.sideFlip[q]} << 10) |
               (std::uint32_t{tiling.repeat[q][0]} << 16) | (std::uint32_t{tiling.repeat[q][1]} << 24);
    for (std::size_t e = 0; e < 4; ++e) {
      out[q].y |= std::uint32_t{tiling.edges[q][e]} << (8 * e);
    }
  }
  return out;
}

} // namespace sylva::trees
