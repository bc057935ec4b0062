#pragma once

// The generated benchmark case of the folding targets (docs/folding.md, "Benchmarks"), shared by the Google
// Benchmark cases (bench/folding/FoldingBench.cpp) and `sylva bench fold`: one 1024×1024 image, one zone
// covering it, N seeded point anchors, and a 64-vertex star polygon for the thresholds. Header-only so both
// the benchmark executable and the CLI include it without a library.

#include <sylva/core/Image.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/folding/Field.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Synthesis.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace sylva::folding::bench {

/** Side of the benchmark image in pixels (1 MP). */
inline constexpr int kCaseSide = 1024;

/** A deterministic RGBA8 test picture (smooth colour waves, so bilinear reads do real work). */
inline Image benchPicture(int side = kCaseSide) {
  Image image(side, side, 4, PixelType::U8);
  const auto v = image.values<std::uint8_t>();
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * side + x) * 4;
      v[i + 0] = static_cast<std::uint8_t>(127.5 + 127.0 * std::sin(x * 0.031 + y * 0.017));
      v[i + 1] = static_cast<std::uint8_t>(127.5 + 127.0 * std::sin(y * 0.023 - x * 0.011));
      v[i + 2] = static_cast<std::uint8_t>((x ^ y) & 0xff);
      v[i + 3] = 255;
    }
  }
  return image;
}

/** A 64-vertex star around the image centre (radii 0.30 and 0.36 of the side), simple and non-convex. */
inline std::vector<Vec2> benchStar(int side = kCaseSide) {
  std::vector<Vec2> star;
  const double c = 0.5 * side;
  for (int i = 0; i < 64; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 64.0;
    const double r = (i % 2 == 0 ? 0.36 : 0.30) * side;
    star.emplace_back(c + r * std::cos(a), c + r * std::sin(a));
  }
  return star;
}

/**
 * The project: image "bench" (the canvas, uncropped), profile "wave" (2 s, piecewise up-and-back), one zone
 * covering the image with `anchors` seeded point anchors (forward motions up to 12 px) interpolated by
 * `interp`. `foldPolygon` adds the 64-vertex star as the zone's folding polygon.
 */
inline Project benchProject(int anchors, const Interpolation& interp, bool foldPolygon = false,
                            int side = kCaseSide) {
  Project p;
  p.seed = 7;
  p.canvas = "bench";
  p.images.push_back(ImageEntry{"bench", "bench.png", false});
  Profile profile;
  profile.id = "wave";
  profile.periodS = 2.0;
  profile.fn.type = PositionFunction::Type::Piecewise;
  profile.fn.knots = {{0.0, 0.0}, {0.5, 1.0}, {1.0, 0.0}};
  p.profiles.push_back(profile);
  Zone zone;
  zone.id = "all";
  zone.image = "bench";
  zone.shape.type = Shape::Type::Rect;
  zone.shape.min = Vec2(0.0);
  zone.shape.max = Vec2(side);
  zone.profile = "wave";
  zone.interp = interp;
  PointsTool points;
  Rng rng(1234);
  for (int i = 0; i < anchors; ++i) {
    const Vec2 to(rng.uniform(1.0f, side - 1.0f), rng.uniform(1.0f, side - 1.0f));
    const Vec2 motion(rng.uniform(-12.0f, 12.0f), rng.uniform(-12.0f, 12.0f));
    points.pairs.push_back({to - motion, to});
  }
  zone.tools.push_back(points);
  if (foldPolygon) {
    zone.folding.type = Folding::Type::Polygons;
    zone.folding.polygons.push_back(benchStar(side));
  }
  p.zones.push_back(zone);
  return p;
}

/** The loaded images of benchProject (the picture, no masks). */
inline ProjectImages benchImages(int side = kCaseSide) {
  ProjectImages images;
  images.images.push_back(benchPicture(side));
  images.freezeMasks.emplace_back();
  images.foldMasks.emplace_back();
  return images;
}

/** The backward jump the threshold benchmark gives pixel (x, y): up to 40 px, varying smoothly. */
inline Vec2 benchJump(int x, int y) {
  return {40.0 * std::sin(y * 0.02), 30.0 * std::cos(x * 0.015)};
}

/**
 * Moves point anchor `pair` of the case's points tool by `delta` pixels (its destination b) and returns the
 * moved project and, in `region`, the atlas rectangle (pixels) the move can change (anchorMoveAtlasRect: the
 * R-boxes around the old and the new position for modified Shepard, the zone for Shepard).
 */
inline Project movedAnchor(const Project& p, int pair, Vec2 delta, const Atlas& atlas, Rect& region) {
  Project moved = p;
  auto& points = std::get<PointsTool>(moved.zones[0].tools[0]);
  const Vec2 before = points.pairs[static_cast<std::size_t>(pair)][1];
  const Vec2 after = before + delta;
  points.pairs[static_cast<std::size_t>(pair)][1] = after;
  region = anchorMoveAtlasRect(moved, atlas, 0, before, after);
  return moved;
}

} // namespace sylva::folding::bench
