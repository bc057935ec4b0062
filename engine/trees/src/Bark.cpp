#include <sylva/trees/Bark.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
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

std::uint32_t barkTile(const BarkSet& set, std::uint32_t rootJoint, std::uint32_t quad,
                       std::uint32_t tileClass) {
  std::size_t c = std::min<std::size_t>(tileClass, SYLVA_TREE_MAX_TILE_CLASSES - 1);
  if (set.classCount[c] == 0) {
    c = 0;
  }
  return chooseTile(instanceTileSeed(rootJoint), quad, set.classFirst[c], std::max(set.classCount[c], 1u));
}

std::vector<std::uint32_t> quadTileTable(const Piece& piece) {
  const std::vector<std::uint8_t> rotations = quadTileRotations(piece);
  std::vector<std::uint32_t> out(piece.quads.size());
  for (std::size_t q = 0; q < out.size(); ++q) {
    const std::uint32_t cls = q < piece.tileClass.size() ? piece.tileClass[q] : 0u;
    out[q] =
        std::min<std::uint32_t>(cls, SYLVA_TREE_MAX_TILE_CLASSES - 1) | (std::uint32_t{rotations[q]} << 8);
  }
  return out;
}

} // namespace sylva::trees
