#include <sylva/texsynth/TileSet.hpp>

#include "internal/Candidates.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/texsynth/MinCut.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace sylva::texsynth {

int TileSet::firstTile(int classIndex) const {
  if (classIndex < 0 || classIndex >= static_cast<int>(classes.size())) {
    fail("tile set: class {} does not exist ({} classes)", classIndex, classes.size());
  }
  int first = 0;
  for (int c = 0; c < classIndex; ++c) {
    first += classes[static_cast<std::size_t>(c)].tileCount;
  }
  return first;
}

int TileSet::classOf(int tile) const {
  int first = 0;
  for (std::size_t c = 0; c < classes.size(); ++c) {
    if (tile >= first && tile < first + classes[c].tileCount) {
      return static_cast<int>(c);
    }
    first += classes[c].tileCount;
  }
  fail("tile set: tile {} does not exist ({} tiles)", tile, first);
}

int TileSettings::effectiveBand() const {
  return band > 0 ? band : std::max(1, tileSize / 8);
}
int TileSettings::effectiveOverlap() const {
  return overlap > 0 ? overlap : std::max(1, tileSize / 6);
}

void validate(const TileSettings& settings, const std::vector<Texture>& photos) {
  if (settings.tileSize < 8 || settings.tileSize > 1024) {
    fail("tileSize: {} is out of range [8, 1024]", settings.tileSize);
  }
  if (settings.band < 0 || settings.band > settings.tileSize / 2) {
    fail("band: {} is out of range [0, {}]", settings.band, settings.tileSize / 2);
  }
  if (settings.overlap < 0 || settings.overlap > settings.tileSize / 2) {
    fail("overlap: {} is out of range [0, {}]", settings.overlap, settings.tileSize / 2);
  }
  if (2 * (settings.effectiveBand() + settings.effectiveOverlap()) > settings.tileSize) {
    fail("band: band {} + overlap {} must be at most half the tile size {}", settings.effectiveBand(),
         settings.effectiveOverlap(), settings.tileSize);
  }
  if (!std::isfinite(settings.tolerance) || settings.tolerance < 0.0 || settings.tolerance > 10.0) {
    fail("tolerance: {} is not a finite number in [0, 10]", settings.tolerance);
  }
  if (settings.maxCandidates < 16 || settings.maxCandidates > 1000000) {
    fail("maxCandidates: {} is out of range [16, 1000000]", settings.maxCandidates);
  }
  if (photos.empty() || photos.size() > 16) {
    fail("photos: expected 1..16 photos, got {}", photos.size());
  }
  for (const Texture& photo : photos) {
    if (photo.empty()) {
      fail("{}: the photo is empty", photo.name);
    }
    if (photo.width < settings.tileSize || photo.height < settings.tileSize) {
      fail("{}: the photo is {}x{}, smaller than the {}x{} tile", photo.name, photo.width, photo.height,
           settings.tileSize, settings.tileSize);
    }
    if (photo.channels != photos.front().channels) {
      fail("{}: the photo has {} channels but {} has {} (give every photo a normal map or none)", photo.name,
           photo.channels, photos.front().name, photos.front().channels);
    }
  }
}

namespace {

using detail::colourError;
using detail::Position;

/** Sizes of the tile construction: tile T, band b, overlap ring o, band depth read from sources D = b + o. */
struct Geometry {
  int tile = 0;
  int band = 0;
  int overlap = 0;
  int depth = 0;
  int channels = 3;
};

inline void copyTexel(float* to, const float* from, int channels) {
  std::memcpy(to, from, sizeof(float) * static_cast<std::size_t>(channels));
}

/**
 * What one edge colour contributes to a tile. Oriented: two unrotated source strips, so anisotropic
 * textures (bark grooves) keep their direction: `texels` of T × (2D − 1) texels for edges 0/2, whose row
 * D − 1 is the line (the tile above the edge takes rows D−1..2D−2, the tile below rows 0..D−1), and
 * `vertical` of (2D − 1) × T texels for edges 1/3, whose column D − 1 is the line (the tile right of the edge
 * takes columns D−1..2D−2, the tile left of it columns 0..D−1). Symmetric: `texels` is a band of T × D texels
 * (x along, y = distance inward from the line), mirrored along x and placed on all four edges, rotated.
 */
struct ColourMaterial {
  bool symmetric = false;
  Texture texels;
  Texture vertical;
};

/** Copies a w × h source region at (sx, sy). */
Texture region(const Texture& source, int sx, int sy, int w, int h) {
  Texture out = Texture::blank(w, h, source.channels, source.name);
  for (int y = 0; y < h; ++y) {
    std::memcpy(out.at(0, y), source.at(sx, sy + y),
                sizeof(float) * static_cast<std::size_t>(w) * source.channels);
  }
  return out;
}

ColourMaterial orientedStrips(const Texture& source, const Geometry& g, Rng& rng, const float* corner) {
  const int across = 2 * g.depth - 1;
  const auto below = [&](int span) { return static_cast<int>(rng.below(static_cast<std::uint32_t>(span))); };
  ColourMaterial m;
  const int hx = below(source.width - g.tile + 1);
  const int hy = below(source.height - across + 1);
  m.texels = region(source, hx, hy, g.tile, across);
  const int vx = below(source.width - across + 1);
  const int vy = below(source.height - g.tile + 1);
  m.vertical = region(source, vx, vy, across, g.tile);
  copyTexel(m.texels.at(0, g.depth - 1), corner, g.channels);
  copyTexel(m.texels.at(g.tile - 1, g.depth - 1), corner, g.channels);
  copyTexel(m.vertical.at(g.depth - 1, 0), corner, g.channels);
  copyTexel(m.vertical.at(g.depth - 1, g.tile - 1), corner, g.channels);
  return m;
}

/** Scales a texel's normal to unit length (a flat normal when it is zero). */
void normalise(float* texel) {
  const float length = std::sqrt(texel[3] * texel[3] + texel[4] * texel[4] + texel[5] * texel[5]);
  if (length > 0.0f) {
    texel[3] /= length, texel[4] /= length, texel[5] /= length;
  } else {
    texel[3] = 0.0f, texel[4] = 0.0f, texel[5] = 1.0f;
  }
}

/** A minimum-error monotone path through a d × d corner square and what it implies. */
struct CornerCut {
  /** lowest[q]: the smallest p of the path in row q; texels with p < lowest[q] take the vertical edge's band.
   */
  std::vector<int> lowest;
  double cost = 0.0;
};

/**
 * The corner cut between a horizontal edge's band and a vertical edge's band in local (p, q) = (distance from
 * the vertical edge's line, distance from the horizontal edge's line): a path of steps (1, 0), (0, 1), (1, 1)
 * from (0, 0) to (d−1, d−1) that touches neither line after its first texel, minimising Σ errors[q·d + p].
 */
CornerCut cornerCut(const std::vector<double>& errors, int d) {
  const double inf = std::numeric_limits<double>::infinity();
  const auto index = [d](int p, int q) { return static_cast<std::size_t>(q) * d + p; };
  std::vector<double> cost(static_cast<std::size_t>(d) * d, inf);
  for (int q = 0; q < d; ++q) {
    for (int p = 0; p < d; ++p) {
      if (p == 0 && q == 0) {
        cost[index(p, q)] = errors[index(p, q)];
      } else if (p > 0 && q > 0) {
        cost[index(p, q)] = errors[index(p, q)] + std::min({cost[index(p - 1, q - 1)], cost[index(p - 1, q)],
                                                            cost[index(p, q - 1)]});
      }
    }
  }
  CornerCut cut;
  cut.cost = cost[index(d - 1, d - 1)];
  cut.lowest.assign(static_cast<std::size_t>(d), d);
  int p = d - 1;
  int q = d - 1;
  while (true) {
    cut.lowest[static_cast<std::size_t>(q)] = std::min(cut.lowest[static_cast<std::size_t>(q)], p);
    if (p == 0 || q == 0) {
      break; // only (0, 0) is reachable on the lines
    }
    const double diagonal = cost[index(p - 1, q - 1)];
    const double left = cost[index(p - 1, q)];
    const double down = cost[index(p, q - 1)];
    if (diagonal <= left && diagonal <= down) {
      --p, --q;
    } else if (left <= down) {
      --p;
    } else {
      --q;
    }
  }
  cut.lowest[0] = 0;
  return cut;
}

/** The symmetric band whose half comes from source texels at (sx, sy). */
ColourMaterial symmetricBandAt(const Texture& source, const Geometry& g, int sx, int sy,
                               const float* corner) {
  const int half = (g.tile + 1) / 2;
  ColourMaterial m{true, Texture::blank(g.tile, g.depth, g.channels, source.name), {}};
  for (int d = 0; d < g.depth; ++d) {
    for (int i = 0; i < half; ++i) {
      float* texel = m.texels.at(i, d);
      copyTexel(texel, source.at(sx + i, sy + d), g.channels);
      if (g.channels == 6) {
        if (i == g.tile - 1 - i) {
          texel[3] = 0.0f; // the centre of an odd line is its own mirror image
        }
        if (d == 0) {
          texel[4] = 0.0f; // on the line the texture continues across as a reflection: no slope across it
        }
        normalise(texel);
      }
      float* mirror = m.texels.at(g.tile - 1 - i, d);
      copyTexel(mirror, texel, g.channels);
      if (g.channels == 6) {
        mirror[3] = -texel[3];
      }
    }
  }
  copyTexel(m.texels.at(0, 0), corner, g.channels);
  copyTexel(m.texels.at(g.tile - 1, 0), corner, g.channels);
  return m;
}

/** Mean and standard deviation of luminance over a w × h region (every 2nd texel). */
std::pair<double, double> luminanceStats(const Texture& t, int x0, int y0, int w, int h) {
  double sum = 0.0;
  double squares = 0.0;
  int n = 0;
  for (int y = y0; y < y0 + h; y += 2) {
    for (int x = x0; x < x0 + w; x += 2) {
      const float* c = t.at(x, y);
      const double l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
      sum += l;
      squares += l * l;
      ++n;
    }
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, squares / n - mean * mean))};
}

/**
 * The symmetric band, from `tries` seeded source positions: the quarter whose luminance mean is closest to
 * the photo's and whose contrast is closest to half the photo's (a generic, calm border), and
 * among those the one whose corners join best. All four corners of a tile are the same join up to rotation
 * and mirroring: edge 0's band(p, q) against edge 3's, which reads band(q, p) there; the cost is that
 * corner's minimum cut.
 */
ColourMaterial symmetricBand(const Texture& source, const Geometry& g, Rng& rng, const float* corner,
                             int tries) {
  // Half the photo's contrast: mirrored and rotated copies of a busy band read as a kaleidoscope around
  // every tile, a calmer one as bark.
  constexpr double kBandContrast = 0.5;
  const int half = (g.tile + 1) / 2;
  const int d = g.depth;
  const auto [photoMean, photoContrast] = luminanceStats(source, 0, 0, source.width, source.height);
  struct Try {
    int x = 0;
    int y = 0;
    double distance = 0.0;
  };
  std::vector<Try> positions;
  for (int k = 0; k < tries; ++k) {
    Try t;
    t.x = static_cast<int>(rng.below(static_cast<std::uint32_t>(source.width - half + 1)));
    t.y = static_cast<int>(rng.below(static_cast<std::uint32_t>(source.height - d + 1)));
    const auto [mean, contrast] = luminanceStats(source, t.x, t.y, half, d);
    t.distance = std::hypot(mean - photoMean, contrast - kBandContrast * photoContrast);
    positions.push_back(t);
  }
  std::stable_sort(positions.begin(), positions.end(),
                   [](const Try& a, const Try& b) { return a.distance < b.distance; });
  positions.resize(std::max<std::size_t>(1, positions.size() / 4));
  ColourMaterial best;
  double bestCost = std::numeric_limits<double>::infinity();
  std::vector<double> errors(static_cast<std::size_t>(d) * d);
  for (const Try& t : positions) {
    ColourMaterial m = symmetricBandAt(source, g, t.x, t.y, corner);
    for (int q = 0; q < d; ++q) {
      for (int p = 0; p < d; ++p) {
        errors[static_cast<std::size_t>(q) * d + p] = colourError(m.texels.at(p, q), m.texels.at(q, p));
      }
    }
    const double cost = cornerCut(errors, d).cost;
    if (cost < bestCost) {
      bestCost = cost;
      best = std::move(m);
    }
  }
  return best;
}

/** The texel that the band of `edge` (colour material m) puts at tile texel (x, y), within depth D of it. */
void sampleBand(const ColourMaterial& m, const Geometry& g, int edge, int x, int y, float* out) {
  const int t = g.tile;
  const int d = g.depth;
  int sx = 0;
  int sy = 0;
  int turns = 0;
  if (!m.symmetric) {
    switch (edge) {
    case kEdgeBottom:
      copyTexel(out, m.texels.at(x, y + d - 1), g.channels);
      return;
    case kEdgeTop:
      copyTexel(out, m.texels.at(x, y - (t - d)), g.channels);
      return;
    case kEdgeRight:
      copyTexel(out, m.vertical.at(x - (t - d), y), g.channels);
      return;
    default:
      copyTexel(out, m.vertical.at(x + d - 1, y), g.channels);
      return;
    }
  } else {
    switch (edge) {
    case kEdgeBottom:
      sx = x, sy = y;
      break;
    case kEdgeRight:
      sx = y, sy = t - 1 - x, turns = 1;
      break;
    case kEdgeTop:
      sx = t - 1 - x, sy = t - 1 - y, turns = 2;
      break;
    default:
      sx = t - 1 - y, sy = x, turns = 3;
      break;
    }
  }
  copyTexel(out, m.texels.at(sx, sy), g.channels);
  if (g.channels == 6 && turns != 0) {
    rotateNormal(out, turns);
  }
}

/**
 * The frame of a tile with the given edge materials: every texel within D of an edge, from that edge's band;
 * in each D × D corner square the two bands are joined by cornerCut, which never touches either edge line
 * after the corner texel, so lines stay pure.
 */
Texture buildFrame(const std::array<const ColourMaterial*, 4>& materials, const Geometry& g) {
  const int t = g.tile;
  const int d = g.depth;
  Texture frame = Texture::blank(t, t, g.channels, "frame");
  for (int y = 0; y < t; ++y) {
    for (int x = 0; x < t; ++x) {
      const bool bands[4] = {y < d, x >= t - d, y >= t - d, x < d};
      const int count = bands[0] + bands[1] + bands[2] + bands[3];
      if (count == 1) {
        for (int e = 0; e < 4; ++e) {
          if (bands[e]) {
            sampleBand(*materials[static_cast<std::size_t>(e)], g, e, x, y, frame.at(x, y));
          }
        }
      }
    }
  }
  // Corners: (horizontal edge, vertical edge); local (p, q) = (distance from the vertical edge's line,
  // distance from the horizontal edge's line).
  const int corners[4][2] = {
      {kEdgeBottom, kEdgeLeft}, {kEdgeBottom, kEdgeRight}, {kEdgeTop, kEdgeRight}, {kEdgeTop, kEdgeLeft}};
  std::vector<float> a(static_cast<std::size_t>(d) * d * g.channels);
  std::vector<float> b(a.size());
  std::vector<double> errors(static_cast<std::size_t>(d) * d);
  for (int k = 0; k < 4; ++k) {
    const int horizontal = corners[k][0];
    const int vertical = corners[k][1];
    const auto tileX = [&](int p) { return vertical == kEdgeRight ? t - 1 - p : p; };
    const auto tileY = [&](int q) { return horizontal == kEdgeTop ? t - 1 - q : q; };
    const auto index = [&](int p, int q) { return static_cast<std::size_t>(q) * d + p; };
    for (int q = 0; q < d; ++q) {
      for (int p = 0; p < d; ++p) {
        float* ta = a.data() + index(p, q) * g.channels;
        float* tb = b.data() + index(p, q) * g.channels;
        sampleBand(*materials[static_cast<std::size_t>(horizontal)], g, horizontal, tileX(p), tileY(q), ta);
        sampleBand(*materials[static_cast<std::size_t>(vertical)], g, vertical, tileX(p), tileY(q), tb);
      }
    }
    for (int q = 0; q < d; ++q) {
      for (int p = 0; p < d; ++p) {
        errors[index(p, q)] =
            colourError(a.data() + index(p, q) * g.channels, b.data() + index(p, q) * g.channels);
      }
    }
    const std::vector<int> lowest = cornerCut(errors, d).lowest;
    for (int qq = 0; qq < d; ++qq) {
      for (int pp = 0; pp < d; ++pp) {
        const bool fromVertical = pp < lowest[static_cast<std::size_t>(qq)];
        const float* texel = (fromVertical ? b.data() : a.data()) + index(pp, qq) * g.channels;
        copyTexel(frame.at(tileX(pp), tileY(qq)), texel, g.channels);
      }
    }
  }
  return frame;
}

/** Distance of texel (x, y) from the nearest tile edge, texels. */
inline int edgeDistance(int x, int y, int t) {
  return std::min({x, y, t - 1 - x, t - 1 - y});
}

/**
 * A tile: the frame within b of the edges, the interior block (source texels at `from`) beyond D, and in the
 * ring between them, per side, a minimum-error cut along the side (union of the four sides' frame parts).
 */
Texture composeTile(const Texture& frame, const Texture& source, Position from, const Geometry& g) {
  const int t = g.tile;
  std::vector<std::uint8_t> keepFrame(static_cast<std::size_t>(t) * t, 0);
  for (int y = 0; y < t; ++y) {
    for (int x = 0; x < t; ++x) {
      keepFrame[static_cast<std::size_t>(y) * t + x] = edgeDistance(x, y, t) < g.band ? 1 : 0;
    }
  }
  const auto sideTexel = [t](int side, int along, int depth) -> Position {
    switch (side) {
    case kEdgeBottom:
      return {along, depth};
    case kEdgeRight:
      return {t - 1 - depth, along};
    case kEdgeTop:
      return {along, t - 1 - depth};
    default:
      return {depth, along};
    }
  };
  for (int side = 0; side < 4; ++side) {
    ErrorSurface surface{t, g.overlap, std::vector<double>(static_cast<std::size_t>(t) * g.overlap)};
    for (int along = 0; along < t; ++along) {
      for (int k = 0; k < g.overlap; ++k) {
        const Position p = sideTexel(side, along, g.band + k);
        surface.values[static_cast<std::size_t>(along) * g.overlap + k] =
            colourError(frame.at(p.x, p.y), source.at(from.x + p.x, from.y + p.y));
      }
    }
    const Cut cut = verticalCut(surface);
    for (int along = 0; along < t; ++along) {
      for (int k = 0; k < cut.path[static_cast<std::size_t>(along)]; ++k) {
        const Position p = sideTexel(side, along, g.band + k);
        keepFrame[static_cast<std::size_t>(p.y) * t + p.x] = 1;
      }
    }
  }
  Texture tile = Texture::blank(t, t, g.channels, "tile");
  for (int y = 0; y < t; ++y) {
    for (int x = 0; x < t; ++x) {
      copyTexel(tile.at(x, y),
                keepFrame[static_cast<std::size_t>(y) * t + x] != 0 ? frame.at(x, y)
                                                                    : source.at(from.x + x, from.y + y),
                g.channels);
    }
  }
  return tile;
}

/** An interior candidate: a T × T block of one of the photos. */
struct Candidate {
  int photo = 0;
  Position at;
  double roughness = 0.0; ///< variance of luminance over the block (sampled every 4th texel)
};

std::vector<Candidate> interiorCandidates(const std::vector<Texture>& photos, const TileSettings& settings) {
  const int t = settings.tileSize;
  std::vector<Candidate> candidates;
  const int perPhoto = std::max(1, settings.maxCandidates / static_cast<int>(photos.size()));
  for (std::size_t i = 0; i < photos.size(); ++i) {
    for (const Position p : detail::candidateGrid(photos[i].width, photos[i].height, t, t, perPhoto)) {
      candidates.push_back({static_cast<int>(i), p, 0.0});
    }
  }
  parallelFor(
      candidates.size(),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          const Texture& photo = photos[static_cast<std::size_t>(candidates[i].photo)];
          double sum = 0.0;
          double sumSquares = 0.0;
          int n = 0;
          for (int y = 0; y < t; y += 4) {
            for (int x = 0; x < t; x += 4) {
              const float* c = photo.at(candidates[i].at.x + x, candidates[i].at.y + y);
              const double luminance = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
              sum += luminance;
              sumSquares += luminance * luminance;
              ++n;
            }
          }
          const double mean = sum / n;
          candidates[i].roughness = std::max(0.0, sumSquares / n - mean * mean);
        }
      },
      8);
  return candidates;
}

/** A class to build: its four edge materials, the candidates its interiors may come from, its rng stream. */
struct ClassPlan {
  TileClass info;
  std::vector<std::size_t> allowed; ///< indices into the candidate list
};

/**
 * Builds every class's tiles: one frame per class, the SSD of each allowed candidate over the overlap ring,
 * then per variant the tolerance rule among the candidates no tile of the set uses yet (so tiles differ
 * inside).
 */
TileSet buildTiles(const std::vector<Texture>& photos, const std::vector<EdgeColour>& colours,
                   const std::vector<ColourMaterial>& materials, const std::vector<ClassPlan>& plans,
                   const std::vector<Candidate>& candidates, int variants, const TileSettings& settings,
                   const Geometry& g, Progress* progress) {
  TileSet set;
  set.tileSize = g.tile;
  set.band = g.band;
  set.overlap = g.overlap;
  set.channels = g.channels;
  set.colours = colours;
  std::vector<Position> ring;
  for (int y = 0; y < g.tile; ++y) {
    for (int x = 0; x < g.tile; ++x) {
      const int distance = edgeDistance(x, y, g.tile);
      if (distance >= g.band && distance < g.depth) {
        ring.push_back({x, y});
      }
    }
  }
  std::vector<bool> used(candidates.size(), false);
  for (std::size_t c = 0; c < plans.size(); ++c) {
    const ClassPlan& plan = plans[c];
    std::array<const ColourMaterial*, 4> edgeMaterials{};
    for (std::size_t e = 0; e < 4; ++e) {
      edgeMaterials[e] = &materials[static_cast<std::size_t>(plan.info.edges[e])];
    }
    const Texture frame = buildFrame(edgeMaterials, g);
    std::vector<double> errors(plan.allowed.size());
    parallelFor(
        plan.allowed.size(),
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) {
            const Candidate& candidate = candidates[plan.allowed[i]];
            const Texture& photo = photos[static_cast<std::size_t>(candidate.photo)];
            double sum = 0.0;
            for (const Position p : ring) {
              sum += colourError(frame.at(p.x, p.y), photo.at(candidate.at.x + p.x, candidate.at.y + p.y));
            }
            errors[i] = sum;
          }
        },
        4);
    Rng rng(hash64(settings.seed ^ hash64(0x7469ULL + c)), 0x696e746572ULL + c);
    // Interiors not used yet by any tile of the set, so that variants and classes differ inside.
    const auto unusedAllowed = [&] {
      std::vector<std::size_t> unused;
      for (std::size_t i = 0; i < plan.allowed.size(); ++i) {
        if (!used[plan.allowed[i]]) {
          unused.push_back(i);
        }
      }
      return unused;
    };
    std::vector<std::size_t> unused = unusedAllowed();
    TileClass info = plan.info;
    info.tileCount = variants;
    set.classes.push_back(info);
    for (int v = 0; v < variants; ++v) {
      if (progress != nullptr && progress->cancelled()) {
        fail("tile synthesis cancelled");
      }
      if (unused.empty()) {
        // More tiles than candidates: start over (tiles may then repeat an interior).
        unused.resize(plan.allowed.size());
        std::iota(unused.begin(), unused.end(), std::size_t{0});
      }
      std::vector<double> remaining(unused.size());
      for (std::size_t i = 0; i < unused.size(); ++i) {
        remaining[i] = errors[unused[i]];
      }
      const std::size_t pick = chooseCandidate(remaining, settings.tolerance, rng);
      const Candidate& chosen = candidates[plan.allowed[unused[pick]]];
      used[plan.allowed[unused[pick]]] = true;
      unused.erase(unused.begin() + static_cast<std::ptrdiff_t>(pick));
      set.tiles.push_back(composeTile(frame, photos[static_cast<std::size_t>(chosen.photo)], chosen.at, g));
      set.tiles.back().name = fmt::format("{}[{}]", info.name, v);
      if (progress != nullptr) {
        progress->advance();
      }
    }
  }
  return set;
}

Geometry geometryOf(const TileSettings& settings, int channels) {
  Geometry g;
  g.tile = settings.tileSize;
  g.band = settings.effectiveBand();
  g.overlap = settings.effectiveOverlap();
  g.depth = g.band + g.overlap;
  g.channels = channels;
  return g;
}

/** The corner texel shared by every line: a seeded source colour with a flat normal. */
std::vector<float> cornerTexel(const Texture& source, Rng& rng) {
  const int x = static_cast<int>(rng.below(static_cast<std::uint32_t>(source.width)));
  const int y = static_cast<int>(rng.below(static_cast<std::uint32_t>(source.height)));
  std::vector<float> texel(source.at(x, y), source.at(x, y) + source.channels);
  if (source.channels == 6) {
    texel[3] = 0.0f;
    texel[4] = 0.0f;
    texel[5] = 1.0f;
  }
  return texel;
}

void checkVariants(int variantsPerClass) {
  if (variantsPerClass < 1 || variantsPerClass > 64) {
    fail("variants: {} is out of range [1, 64]", variantsPerClass);
  }
}

} // namespace

TileSet wangTileSet(const Texture& source, int colourCount, int variantsPerClass,
                    const TileSettings& settings, Progress* progress) {
  const std::vector<Texture> photos{source};
  validate(settings, photos);
  if (colourCount < 1 || colourCount > 3) {
    fail("colours: {} is out of range [1, 3]", colourCount);
  }
  checkVariants(variantsPerClass);
  const Geometry g = geometryOf(settings, source.channels);
  Rng rng(settings.seed, 0x77616e67ULL);
  const std::vector<float> corner = cornerTexel(source, rng);
  std::vector<EdgeColour> colours;
  std::vector<ColourMaterial> materials;
  for (int k = 0; k < colourCount; ++k) {
    colours.push_back({fmt::format("wang{}", k), false});
    materials.push_back(orientedStrips(source, g, rng, corner.data()));
  }
  const std::vector<Candidate> candidates = interiorCandidates(photos, settings);
  std::vector<std::size_t> all(candidates.size());
  std::iota(all.begin(), all.end(), std::size_t{0});
  std::vector<ClassPlan> plans;
  const int k = colourCount;
  for (int index = 0; index < k * k * k * k; ++index) {
    ClassPlan plan;
    plan.info.edges = {index % k, (index / k) % k, (index / (k * k)) % k, (index / (k * k * k)) % k};
    plan.info.name = fmt::format("wang-{}{}{}{}", plan.info.edges[0], plan.info.edges[1], plan.info.edges[2],
                                 plan.info.edges[3]);
    plan.info.interior = "any";
    plan.allowed = all;
    plans.push_back(std::move(plan));
  }
  return buildTiles(photos, colours, materials, plans, candidates, variantsPerClass, settings, g, progress);
}

TileSet barkTileSet(const std::vector<Texture>& photos, int variantsPerClass, const TileSettings& settings,
                    Progress* progress, int edgeColours) {
  validate(settings, photos);
  checkVariants(variantsPerClass);
  if (edgeColours < 1 || edgeColours > 3) {
    fail("bark tile set: {} edge colours is out of range (1..3)", edgeColours);
  }
  const Texture& edgeSource = photos.front();
  const Geometry g = geometryOf(settings, edgeSource.channels);
  Rng rng(settings.seed, 0x6261726bULL);
  const std::vector<float> corner = cornerTexel(edgeSource, rng);
  std::vector<EdgeColour> colours;
  std::vector<ColourMaterial> materials;
  for (int k = 0; k < edgeColours; ++k) {
    colours.push_back({k == 0 ? std::string("bark") : fmt::format("bark{}", k), true});
    materials.push_back(symmetricBand(edgeSource, g, rng, corner.data(), 64));
  }
  const std::vector<Candidate> candidates = interiorCandidates(photos, settings);
  // Rougher classes draw from the rougher candidates: sort by roughness and keep the top fraction.
  std::vector<std::size_t> byRoughness(candidates.size());
  std::iota(byRoughness.begin(), byRoughness.end(), std::size_t{0});
  std::stable_sort(byRoughness.begin(), byRoughness.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].roughness > candidates[b].roughness;
  });
  const auto roughest = [&](std::size_t divisor) {
    const std::size_t count =
        std::max<std::size_t>(static_cast<std::size_t>(variantsPerClass), byRoughness.size() / divisor);
    std::vector<std::size_t> chosen(byRoughness.begin(),
                                    byRoughness.begin() +
                                        static_cast<std::ptrdiff_t>(std::min(count, byRoughness.size())));
    std::sort(chosen.begin(), chosen.end());
    return chosen;
  };
  // Per bark class, one class of tiles for every assignment of the colours to the four edges (combination
  // e0 + K·e1 + K²·e2 + K³·e3), so any colouring of a mesh's edges finds its tile.
  const int k = edgeColours;
  const int combos = k * k * k * k;
  std::vector<ClassPlan> plans;
  const std::array<std::pair<const char*, const char*>, 3> kinds{
      {{"plain", "any"}, {"fork", "rougher half"}, {"crotch", "roughest quarter"}}};
  for (int b = 0; b < 3; ++b) {
    const std::vector<std::size_t> allowed = roughest(std::size_t{1} << b);
    for (int combo = 0; combo < combos; ++combo) {
      ClassPlan plan;
      const std::array<int, 4> edges{combo % k, combo / k % k, combo / (k * k) % k, combo / (k * k * k) % k};
      plan.info = {combos == 1 ? std::string(kinds[static_cast<std::size_t>(b)].first)
                               : fmt::format("{} {}{}{}{}", kinds[static_cast<std::size_t>(b)].first,
                                             edges[0], edges[1], edges[2], edges[3]),
                   edges, kinds[static_cast<std::size_t>(b)].second, 0};
      plan.allowed = allowed;
      plans.push_back(std::move(plan));
    }
  }
  return buildTiles(photos, colours, materials, plans, candidates, variantsPerClass, settings, g, progress);
}

namespace {

void checkTileCount(const TileSet& set, const char* what, int w, int h) {
  if (set.tiles.empty() || set.classes.empty()) {
    fail("{}: the tile set is empty", what);
  }
  if (w < 1 || h < 1 || w > 4096 || h > 4096) {
    fail("{}: {}x{} tiles is out of range (1..4096 per side)", what, w, h);
  }
}

/** A random tile of a class whose edges satisfy `fits`, or -1 when none does. */
template <typename Fits> int drawTile(const TileSet& set, Rng& rng, Fits fits) {
  int total = 0;
  for (const TileClass& c : set.classes) {
    total += fits(c) ? c.tileCount : 0;
  }
  if (total == 0) {
    return -1;
  }
  int pick = static_cast<int>(rng.below(static_cast<std::uint32_t>(total)));
  int first = 0;
  for (const TileClass& c : set.classes) {
    if (fits(c)) {
      if (pick < c.tileCount) {
        return first + pick;
      }
      pick -= c.tileCount;
    }
    first += c.tileCount;
  }
  return -1;
}

} // namespace

std::vector<int> tileGrid(const TileSet& set, int w, int h, std::uint64_t seed) {
  checkTileCount(set, "tile grid", w, h);
  Rng rng(seed, 0x67726964ULL);
  std::vector<int> grid(static_cast<std::size_t>(w) * h, -1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const int left = x > 0 ? set.edgeColour(grid[static_cast<std::size_t>(y) * w + x - 1], kEdgeRight) : -1;
      const int below = y > 0 ? set.edgeColour(grid[static_cast<std::size_t>(y - 1) * w + x], kEdgeTop) : -1;
      const int tile = drawTile(set, rng, [&](const TileClass& c) {
        return (left < 0 || c.edges[kEdgeLeft] == left) && (below < 0 || c.edges[kEdgeBottom] == below);
      });
      if (tile < 0) {
        fail("tile grid: no tile fits at ({}, {}) (left colour {}, bottom colour {}); the set is incomplete",
             x, y, left, below);
      }
      grid[static_cast<std::size_t>(y) * w + x] = tile;
    }
  }
  return grid;
}

std::vector<int> tileRing(const TileSet& set, int n, std::uint64_t seed) {
  checkTileCount(set, "tile ring", n, 1);
  Rng rng(seed, 0x72696e67ULL);
  const auto colourCount = static_cast<std::uint32_t>(set.colours.size());
  // Seam colours first (seam j is between tile j − 1 and tile j, seam 0 closes the ring), then the tiles;
  // a few draws so that sets without every combination still close when some seam sequence allows it.
  for (int attempt = 0; attempt < 256; ++attempt) {
    std::vector<int> seams(static_cast<std::size_t>(n));
    for (int& seam : seams) {
      seam = static_cast<int>(rng.below(colourCount));
    }
    std::vector<int> ring(static_cast<std::size_t>(n));
    bool closed = true;
    for (int j = 0; j < n && closed; ++j) {
      const int leftSeam = seams[static_cast<std::size_t>(j)];
      const int rightSeam = seams[static_cast<std::size_t>((j + 1) % n)];
      ring[static_cast<std::size_t>(j)] = drawTile(set, rng, [&](const TileClass& c) {
        return c.edges[kEdgeLeft] == leftSeam && c.edges[kEdgeRight] == rightSeam;
      });
      closed = ring[static_cast<std::size_t>(j)] >= 0;
    }
    if (closed) {
      return ring;
    }
  }
  fail("tile ring: no ring of {} tiles closes with this tile set", n);
}

std::vector<float> edgeLine(const Texture& tile, int edge) {
  std::vector<float> line;
  const int t = tile.width;
  line.reserve(static_cast<std::size_t>(t) * tile.channels);
  for (int i = 0; i < t; ++i) {
    int x = i;
    int y = i;
    switch (edge) {
    case kEdgeBottom:
      y = 0;
      break;
    case kEdgeRight:
      x = t - 1;
      break;
    case kEdgeTop:
      y = t - 1;
      break;
    default:
      x = 0;
      break;
    }
    line.insert(line.end(), tile.at(x, y), tile.at(x, y) + tile.channels);
  }
  return line;
}

Texture tilingPreview(const TileSet& set, const std::vector<int>& grid, int w, int h) {
  checkTileCount(set, "tiling preview", w, h);
  if (grid.size() != static_cast<std::size_t>(w) * h) {
    fail("tiling preview: {} tiles given for a {}x{} grid", grid.size(), w, h);
  }
  const int t = set.tileSize;
  Texture out = Texture::blank(w * t, h * t, set.channels, "preview");
  for (int gy = 0; gy < h; ++gy) {
    for (int gx = 0; gx < w; ++gx) {
      const Texture& tile =
          set.tiles.at(static_cast<std::size_t>(grid[static_cast<std::size_t>(gy) * w + gx]));
      for (int y = 0; y < t; ++y) {
        std::memcpy(out.at(gx * t, gy * t + y), tile.at(0, y),
                    sizeof(float) * static_cast<std::size_t>(t) * set.channels);
      }
    }
  }
  return out;
}

} // namespace sylva::texsynth
