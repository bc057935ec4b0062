// The region an anchor drag can change (anchorMoveAtlasRect): re-synthesising just that region after moving
// an anchor gives exactly the textures of a full synthesis, for every interpolation type.
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Synthesis.hpp>

#include "Patterns.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace sylva::folding {
namespace {

using nlohmann::json;

/** A zone over a 96×64 image with every kind of anchor source: points, a curve, a lasso, zero anchors. */
json zone(const json& interp, const std::string& id = "z", int layer = 0) {
  return {
      {"id", id},
      {"image", "img"},
      {"shape", {{"type", "polygon"}, {"pts", {{4, 4}, {92, 6}, {90, 60}, {6, 58}}}}},
      {"profile", "p"},
      {"layer", layer},
      {"interp", interp},
      {"zero_anchors", "zone_boundary"},
      {"feather_px", 3},
      {"tools",
       {{{"type", "points"}, {"pairs", {{{40, 20}, {46, 28}}, {{60, 40}, {55, 44}}, {{24, 30}, {20, 36}}}}},
        {{"type", "curve"},
         {"source", {{20, 50}, {30, 40}, {50, 40}, {70, 50}}},
         {"vectors", {{0, {0, -4}}, {1, {2, -6}}}}},
        {{"type", "lasso"},
         {"from", {{70, 10}, {85, 12}, {80, 25}}},
         {"to", {{72, 14}, {86, 16}, {82, 28}}}}}},
      {"folding", {{"type", "polygon"}, {"pts", {{30, 24}, {60, 22}, {62, 40}, {45, 30}, {28, 40}}}}}};
}

json project(const std::vector<json>& zones, bool twoLayers = false) {
  json j = {{"format", "sylva-fold"},
            {"version", 1},
            {"seed", 11},
            {"atlas", {{"gutter_px", 4}, {"images", {{{"id", "img"}, {"file", "img.png"}}}}}},
            {"profiles", {{{"id", "p"}, {"period_s", 2.0}, {"fn", {{"type", "linear"}, {"slope", 1.0}}}}}},
            {"zones", json(zones)}};
  if (twoLayers) {
    j["jump_layers"] = {0.0, 0.5, 1.0};
  }
  return j;
}

struct Case {
  Project project;
  ProjectImages images;
};

Case make(const json& j) {
  Case c;
  c.project = parseProject(j, "region.json");
  c.images.images.push_back(test::patternImage(96, 64));
  validateAgainstImages(c.project, {{96, 64}}, "region.json");
  c.images.freezeMasks.resize(c.project.zones.size());
  c.images.foldMasks.resize(c.project.zones.size());
  return c;
}

const json kShepard = {{"type", "shepard"}, {"power", 2.0}};
const json kModified = {{"type", "modified_shepard"}, {"R", 14}};
const json kRandom = {{"type", "modified_shepard_random"}, {"R", 14}, {"ring", 5}};

Vec2 anchorTo(const Project& p, int zone, int pair) {
  return std::get<PointsTool>(p.zones[static_cast<std::size_t>(zone)].tools[0])
      .pairs[static_cast<std::size_t>(pair)][1];
}

void expectSameTextures(const Textures& a, const Textures& b) {
  EXPECT_EQ(a.atlas.entries, b.atlas.entries) << "the move must keep the atlas layout";
  EXPECT_EQ(a.init, b.init);
  EXPECT_EQ(a.jump, b.jump);
  EXPECT_EQ(a.fold, b.fold);
}

TEST(FoldingRegion, OneAnchorMoveEqualsAFullSynthesisForEveryInterpolation) {
  for (const json& interp : {kShepard, kModified, kRandom}) {
    SCOPED_TRACE(interp.dump());
    Case c = make(project({zone(interp)}));
    Textures tex = synthesize(c.project, c.images);
    EditHistory history(c.project);
    const Vec2 before = anchorTo(c.project, 0, 0);
    const Vec2 after = before + Vec2(4.0, 2.5);
    movePointAnchor(history, 0, 0, 0, 1, after);
    const Rect region = anchorMoveAtlasRect(history.project(), tex.atlas, 0, before, after);
    const Rect whole = zoneAtlasRect(history.project(), tex.atlas, 0);
    if (interp == kShepard) {
      EXPECT_EQ(region, whole) << "global weights: the whole zone";
    } else {
      // Half-side R around both positions, one texel of margin, in atlas pixels.
      const glm::ivec2 o = tex.atlas.entries[0].origin();
      const Rect expected{o + glm::ivec2(46 - 14 - 1, 28 - 14 - 1), o + glm::ivec2(50 + 14 + 1, 31 + 14 + 1)};
      EXPECT_EQ(region, expected);
      EXPECT_LT(region.width() * region.height(), whole.width() * whole.height() / 2);
    }
    // The region is not a formality: the full synthesis differs from the old textures.
    const Textures full = synthesize(history.project(), c.images);
    EXPECT_NE(tex.jump, full.jump);
    resynthesize(history.project(), c.images, tex, region);
    expectSameTextures(tex, full);
  }
}

TEST(FoldingRegion, ADragOfManyStepsStaysExactWithOverlappingZones) {
  // A drag as the editor does it: one edit and one region re-synthesis per mouse event, the anchor walking a
  // circle, with a second zone on another jump layer overlapping the first.
  for (const json& interp : {kShepard, kModified, kRandom}) {
    SCOPED_TRACE(interp.dump());
    json z2 = zone(kRandom, "z2", 1);
    z2["shape"] = {{"type", "rect"}, {"min", {30, 10}}, {"max", {80, 50}}};
    Case c = make(project({zone(interp), z2}, true));
    Textures tex = synthesize(c.project, c.images);
    EditHistory history(c.project);
    const Vec2 centre = anchorTo(c.project, 0, 1);
    Vec2 position = centre;
    for (int step = 1; step <= 12; ++step) {
      const double a = 2.0 * std::numbers::pi * step / 12.0;
      const Vec2 next = centre + 5.0 * Vec2(std::cos(a), std::sin(a));
      movePointAnchor(history, 0, 0, 1, 1, next);
      resynthesize(history.project(), c.images, tex,
                   anchorMoveAtlasRect(history.project(), tex.atlas, 0, position, next));
      position = next;
    }
    expectSameTextures(tex, synthesize(history.project(), c.images));
  }
}

TEST(FoldingRegion, MovingAnOutermostAnchorRedoesTheWholeZone) {
  // Without zero anchors on the border, anchor 0 of this zone is the leftmost: moving it moves the anchor
  // grid, which reorders the sums of far-away texels, so the whole zone is redone.
  for (const json& interp : {kModified, kRandom}) {
    SCOPED_TRACE(interp.dump());
    json z = zone(interp);
    z["zero_anchors"] = "none";
    z["tools"] = {
        {{"type", "points"}, {"pairs", {{{10, 30}, {8, 31}}, {{50, 33}, {52, 35}}, {{70, 50}, {72, 48}}}}}};
    Case c = make(project({z}));
    Textures tex = synthesize(c.project, c.images);
    EditHistory history(c.project);
    const Vec2 before = anchorTo(c.project, 0, 0);
    const Vec2 after = before + Vec2(3.0, -2.0);
    movePointAnchor(history, 0, 0, 0, 1, after);
    const Rect region = anchorMoveAtlasRect(history.project(), tex.atlas, 0, before, after);
    EXPECT_EQ(region, zoneAtlasRect(history.project(), tex.atlas, 0));
    resynthesize(history.project(), c.images, tex, region);
    expectSameTextures(tex, synthesize(history.project(), c.images));
    // The middle anchor is strictly inside: just its neighbourhood.
    const Vec2 mid = anchorTo(history.project(), 0, 1);
    const Rect small = anchorMoveAtlasRect(history.project(), tex.atlas, 0, mid, mid + Vec2(1.0, 1.0));
    EXPECT_LT(small.width(), zoneAtlasRect(history.project(), tex.atlas, 0).width());
  }
}

TEST(FoldingRegion, AMoveOutsideTheZoneChangesNothing) {
  // Anchors may lie outside their zone: R-boxes that miss the zone give an empty region, and indeed the
  // textures do not change.
  json z = zone(kModified);
  z["zero_anchors"] = "none";
  z["shape"] = {{"type", "rect"}, {"min", {0, 0}}, {"max", {40, 64}}};
  z["tools"] = {
      {{"type", "points"}, {"pairs", {{{10, 10}, {12, 12}}, {{70, 30}, {72, 30}}, {{94, 62}, {90, 60}}}}}};
  z.erase("folding");
  Case c = make(project({z}));
  Textures tex = synthesize(c.project, c.images);
  EditHistory history(c.project);
  const Vec2 before = anchorTo(c.project, 0, 1);
  const Vec2 after = before + Vec2(2.0, 1.0);
  movePointAnchor(history, 0, 0, 1, 1, after);
  const Rect region = anchorMoveAtlasRect(history.project(), tex.atlas, 0, before, after);
  EXPECT_TRUE(region.empty());
  EXPECT_EQ(region, Rect{});
  resynthesize(history.project(), c.images, tex, region);
  expectSameTextures(tex, synthesize(history.project(), c.images));
}

} // namespace
} // namespace sylva::folding
