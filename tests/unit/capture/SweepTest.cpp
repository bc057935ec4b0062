// The capture sweep (issue 30): random clusters of every class new users brought (fans, a blade inside its
// neighbour's outline, crossing fans, dense fans of 11+ blades over 60°) under camera roll and pitch and edge
// dropouts, captured from depth alone and measured against their truth. The targets are an exact
// count on ≥ 95 % of clusters and a width error ≤ 10 % on ≥ 95 % of blades. Depth layers separate blades in
// front of their neighbours, notches and depth splits some of the crossing and dense fans; those are not met
// yet: this test holds what the extractor reaches today (docs/capture.md, "Overlapping, crossing and dense
// blades") so that it can only go up, and plain fans must stay exact.
#include <sylva/capture/Depth.hpp>
#include <sylva/capture/Extract.hpp>
#include <sylva/capture/Synthetic.hpp>
#include <sylva/core/Error.hpp>

#include "TempDir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SYLVA_SWEEP_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define SYLVA_SWEEP_SANITIZED 1
#endif
#endif

namespace sylva::capture {
namespace {

void print(const char* name, const SweepTally& t) {
  std::printf("%s\n", sweepLine(name, t).c_str());
}

TEST(CaptureSweep, RandomClustersOfEveryClass) {
#ifdef SYLVA_SWEEP_SANITIZED
  // Under the sanitizers the point is the memory and thread checks of every class, not the shares.
  const int clusters = 24;
#else
  const int clusters = test::fullMode() ? 1000 : 200;
#endif
  const SweepReport report = captureSweep(clusters);
  for (std::size_t i = 0; i < report.byLayout.size(); ++i) {
    print(clusterLayoutName(kClusterLayouts[i]), report.byLayout[i]);
    EXPECT_GT(report.byLayout[i].clusters, 0) << "every class is drawn";
  }
  print("all", report.all);
  RecordProperty("tips_free", std::to_string(report.all.tipsFreeShare()));
  RecordProperty("tips_free_exact", std::to_string(report.all.tipsFreeExactShare()));
  EXPECT_EQ(report.all.clusters, clusters);
  RecordProperty("count_exact", std::to_string(report.all.exactShare()));
  RecordProperty("width_within_10", std::to_string(report.all.widthShare()));
  const SweepTally& fans = report.byLayout[0];
  EXPECT_GE(fans.exactShare(), 0.97) << "a plain fan, rolled and pitched, is counted exactly";
  EXPECT_GE(fans.widthShare(), 0.97);
#ifndef SYLVA_SWEEP_SANITIZED
  // Measured with depth layers (a 5 mm / 0.7 % step), the split of blades much wider than their cluster's
  // narrow blades (1.4x the lower quartile of its widths), junctions at notches between tips and the split of
  // blades whose outer halves part in depth, short pointed tips as blades, blades broken in two by a nearer
  // one joined, widths where a nearer blade hides an edge taken from where both show, a 4 % coverage margin
  // for partitions with fewer blades, the depth split's second look over a blade's outer 35 %, elongation
  // judged beyond a blade's lowest tenth, and blades found by the surface (or the branch of one) their free
  // tip ends on over the cluster's outer quarter (captured as the PNG holds the depth), hidden widths also
  // where a nearer blade hides the axis itself, widths of blades found on a medial axis over their own depth
  // surface, and each blade's widths smoothed along it: 200 clusters 91.5 % exact (occluded 95.6 %, crossing
  // 87.7 %, dense 82.6 %), widths within 10 % on 93.4 % of 1,460 blades (crossing 89.9 %, dense 93.0 %);
  // 1,000 clusters (SYLVA_FULL=1) 89.9 % (fan 100 %, occluded 97.6 %, crossing 82.6 %, dense 79.2 %) and
  // 93.4 % of 7,224 (occluded 95.8 %, crossing 87.2 %, dense 92.8 %). Unsmoothed: 200 clusters 92.7 % of
  // widths, 1,000 92.6 %. Without the surface widths as well: 200 clusters 91.6 %, 1,000 92.1 % (dense
  // 90.3 %). Hidden widths only where the axis shows as well: 200 clusters 90.3 % of widths, 1,000 91.1 %
  // (crossing 82.0 %). Without the tip surfaces as well: 200 clusters 87.5 % and 89.1 %, 1,000 86.7 % and
  // 90.3 %. Elongation by the widest point: 200 clusters 85.5 % and 89.0 %, 1,000 85.3 % and 90.4 %. Without
  // the second look as well: 200 clusters 83.5 % and 88.6 %, 1,000 83.8 % and 90.1 %. With the 2 % margin as
  // well: 83.3 %. Without the join and the occluded widths as well (1,000): 82.3 % and 89.4 %. Without
  // pointed tips as well: 81.8 % and 88.8 %. Without notches and the depth split: 80.0 % and 84.3 %;
  // 1,000: 79.0 % and 85.6 %. With 1.6x the median as the split's reference: 78.5 % and 83.1 %. Without the
  // split: 75.5 % (dense 43.5 %) and 80.5 %. Before the depth layers: 49.5 % (occluded 0 %) and 78.3 %.
  const SweepTally& occluded = report.byLayout[1];
  EXPECT_GE(occluded.exactShare(), 0.93) << "a blade in front of its neighbour is its own depth layer";
  EXPECT_GE(occluded.widthShare(), 0.92);
  const SweepTally& crossing = report.byLayout[2];
  EXPECT_GE(crossing.exactShare(), 0.81)
      << "blades of two fans merged up to tips that part in depth are split, broken ones joined";
  EXPECT_GE(crossing.widthShare(), 0.86) << "a blade passing behind a crossing one keeps its width there";
  const SweepTally& dense = report.byLayout[3];
  EXPECT_GE(dense.exactShare(), 0.76) << "neighbouring tips part at notches, or in depth";
  EXPECT_GE(dense.widthShare(), 0.92) << "a blade in front of its neighbour is as wide as its own surface";
  EXPECT_GE(report.all.exactShare(), 0.89);
  EXPECT_GE(report.all.widthShare(), 0.93);
  // The targets are within reach of one frame: nearly every cluster shows each blade's tip on its own (in the
  // picture, or by a depth step of 5 mm); 200 clusters 94.5 %, 1,000 96.1 %. On those the count is exact on
  // 94.7 % (1,000: 91.7 %): what is missing is the extractor's, not the frame's.
  EXPECT_GE(report.all.tipsFreeShare(), 0.92);
  EXPECT_GE(report.all.tipsFreeExactShare(), 0.91);
#endif
}

TEST(CaptureSweep, TipsStandFreeUnlessHiddenOrTouchingAtTheSameDepth) {
  const auto freeTips = [](const SyntheticScene& scene) {
    const SyntheticFrame frame = renderScene(scene);
    const std::vector<bool> free = tipsStandFree(frame.truth, scene.width, scene.height);
    EXPECT_EQ(free.size(), scene.blades.size());
    return static_cast<int>(std::count(free.begin(), free.end(), true));
  };
  // A plain fan: every tip on its own.
  SyntheticScene fan = makeCluster(BladeShape::SlimGrass, 5, 0.3f, 0.0f, 1);
  fan.noise = false;
  EXPECT_EQ(freeTips(fan), 5);
  // A blade inside its neighbour's outline, 3 cm nearer: its tip stands free by depth.
  SyntheticScene occluded =
      makeLayoutCluster(ClusterLayout::Occluded, BladeShape::SlenderLeaf, 5, 0.2f, 0.0f, 7);
  occluded.noise = false;
  EXPECT_EQ(freeTips(occluded), 5);
  // The same blade drawn at its neighbour's depth: its tip lies in the neighbour's outline on the same
  // surface.
  for (SyntheticBlade& b : occluded.blades) {
    b.nearerMetres = 0.0f;
  }
  EXPECT_EQ(freeTips(occluded), 4);
  // Fourteen broad leaves over 60°: tips touch their neighbours'.
  SyntheticScene dense =
      makeLayoutCluster(ClusterLayout::Dense, BladeShape::QuadraticLeaf, 14, 0.0f, 0.0f, 3);
  dense.noise = false;
  EXPECT_LT(freeTips(dense), 14);
  // A narrower, shorter blade wholly behind another: no tip of its own.
  SyntheticScene twin = makeCluster(BladeShape::SlenderLeaf, 1, 0.0f, 0.0f, 1);
  twin.noise = false;
  twin.blades.push_back(twin.blades[0]);
  twin.blades[1].nearerMetres = -0.02f;
  twin.blades[1].widthMetres *= 0.5f;
  twin.blades[1].lengthMetres *= 0.8f;
  EXPECT_EQ(freeTips(twin), 1);
}

TEST(CaptureSweep, ClassesAreWhatTheyClaim) {
  // Occluded: the extra blade is nearer than its neighbour and, from the camera, inside its outline.
  SyntheticScene occluded =
      makeLayoutCluster(ClusterLayout::Occluded, BladeShape::SlenderLeaf, 5, 0.2f, 0.0f, 7);
  occluded.noise = false;
  ASSERT_EQ(occluded.blades.size(), 5u);
  const SyntheticFrame frame = renderScene(occluded);
  std::size_t front = 0;
  for (std::size_t b = 0; b < occluded.blades.size(); ++b) {
    if (occluded.blades[b].nearerMetres > 0.0f) {
      front = b;
    }
  }
  ASSERT_GT(front, 0u);
  // Drawn without it, its pixels belong to the rest of the cluster (mostly its neighbour; near the root, the
  // blades beside it): the silhouette does not change, only depth tells it is there.
  SyntheticScene without = occluded;
  without.blades.erase(without.blades.begin() + static_cast<std::ptrdiff_t>(front));
  const SyntheticFrame behind = renderScene(without);
  const std::vector<int>& label = frame.truth.label;
  int visible = 0;
  int covered = 0;
  int neighbour = 0;
  for (std::size_t i = 0; i < label.size(); ++i) {
    if (label[i] == static_cast<int>(front)) {
      ++visible;
      covered += behind.truth.label[i] >= 0 ? 1 : 0;
      neighbour += behind.truth.label[i] == static_cast<int>(front) - 1 ? 1 : 0;
    }
  }
  EXPECT_GT(visible, 100);
  EXPECT_GE(covered, visible * 99 / 100) << covered << " of " << visible << " pixels inside the rest";
  EXPECT_GE(neighbour, visible * 80 / 100) << neighbour << " of " << visible << " pixels over the neighbour";
  EXPECT_EQ(behind.truth.mask, frame.truth.mask);

  // Crossing: two roots; some blade of one fan covers pixels another blade of the other fan also covers.
  const SyntheticScene crossing =
      makeLayoutCluster(ClusterLayout::Crossing, BladeShape::SlimGrass, 6, 0.2f, 0.0f, 3);
  ASSERT_EQ(crossing.blades.size(), 6u);
  EXPECT_NE(crossing.blades[0].rootOffsetMetres, crossing.blades[5].rootOffsetMetres);
  // Dense: 12 blades within 60° of lean.
  const SyntheticScene dense =
      makeLayoutCluster(ClusterLayout::Dense, BladeShape::SlimGrass, 12, 0.0f, 0.0f, 3);
  EXPECT_NEAR(dense.blades.back().leanRadians - dense.blades.front().leanRadians, 1.0472f, 1e-3f);
  EXPECT_THROW((void)makeLayoutCluster(ClusterLayout::Occluded, BladeShape::SlimGrass, 1, 0.0f, 0.0f, 1),
               Error);

  // Roll turns the picture: a single upright blade rolled by +0.4 rad leans right in the image by 0.4 rad.
  SyntheticScene one = makeCluster(BladeShape::SlimGrass, 1, 0.0f, 0.0f, 1);
  one.blades[0].tiltRadians = 0.0f;
  one.noise = false;
  one.rollRadians = 0.4f;
  const SyntheticFrame rolled = renderScene(one);
  const glm::vec2 d = rolled.truth.centrelinePx[0].back() - rolled.truth.centrelinePx[0].front();
  EXPECT_NEAR(std::atan2(d.x, -d.y), 0.4f, 0.02f);
  // Pitch brings an upright blade's tip towards the camera.
  one.rollRadians = 0.0f;
  one.pitchRadians = 0.3f;
  const SyntheticFrame pitched = renderScene(one);
  EXPECT_LT(pitched.truth.centrelineMetres[0].back().z, pitched.truth.centrelineMetres[0].front().z - 0.05f);
}

TEST(CaptureLayers, ABladeInsideItsNeighboursOutlineIsPartitionedOnItsOwnDepthLayer) {
  // The class: one blade 3 cm in front of its neighbour and inside its outline, for every shape, several
  // clusters each, with the sensor's noise. Only depth shows the front blade; it must come out as a blade of
  // its own, at its own depth, as wide as it is (not as its neighbour).
  int clusters = 0;
  for (const BladeShape shape : kBladeShapes) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SyntheticScene scene = makeLayoutCluster(ClusterLayout::Occluded, shape, 5, 0.2f, 0.1f, seed);
      scene.colour = false;
      const SyntheticFrame frame = renderScene(scene);
      const ExtractResult result = extractBlades(frame.frame);
      const AccuracyReport accuracy = evaluateCapture(frame.truth, result);
      SCOPED_TRACE(std::string(bladeShapeName(shape)) + " seed " + std::to_string(seed));
      EXPECT_EQ(accuracy.bladesFound, 5);
      ++clusters;
      // The nearest layer holds one blade, at the front blade's depth (its root 3 cm before the others').
      const auto front = std::find_if(result.clusters.begin(), result.clusters.end(),
                                      [](const Cluster& c) { return c.layer == 0; });
      ASSERT_NE(front, result.clusters.end()) << "no depth layer found";
      EXPECT_EQ(front->layerCount, 2);
      ASSERT_EQ(front->blades.size(), 1u);
      const CapturedBlade& blade = result.blades[static_cast<std::size_t>(front->blades.front())];
      std::size_t truthIndex = 0;
      for (std::size_t b = 0; b < scene.blades.size(); ++b) {
        truthIndex = scene.blades[b].nearerMetres > 0.0f ? b : truthIndex;
      }
      const float trueRootZ = frame.truth.centrelineMetres[truthIndex].front().z;
      const float trueMidZ =
          frame.truth.centrelineMetres[truthIndex][frame.truth.centrelineMetres[truthIndex].size() / 2].z;
      EXPECT_NEAR(blade.knots[blade.knots.size() / 2].z, trueMidZ, 0.01f) << "root at " << trueRootZ << " m";
      const float maxWidth = *std::max_element(blade.widths.begin(), blade.widths.end());
      const float trueWidth = *std::max_element(frame.truth.widthsMetres[truthIndex].begin(),
                                                frame.truth.widthsMetres[truthIndex].end());
      EXPECT_NEAR(maxWidth, trueWidth, 0.25f * trueWidth)
          << "the front blade's own width, not its neighbour's";
    }
  }
  EXPECT_EQ(clusters, 15);

  // A plain fan is one depth layer: nothing changes for it.
  const SyntheticFrame fan = renderScene(makeCluster(BladeShape::SlimGrass, 5, 0.3f, 0.0f, 4));
  for (const Cluster& c : extractBlades(fan.frame).clusters) {
    EXPECT_EQ(c.layer, -1);
    EXPECT_EQ(c.layerCount, 1);
  }
}

TEST(CaptureLayers, ABladeCrossedByANearerOneIsFollowedBehindIt) {
  // Two blades in an X from roots 5 cm apart, the left one 3 cm nearer: the right blade shows in two pieces,
  // below and above the crossing, joined behind the nearer blade into one layer and one blade of its full
  // length.
  for (const float lean : {0.3f, 0.45f}) {
    SyntheticScene scene;
    scene.seed = 11;
    scene.colour = false;
    SyntheticBlade left;
    left.shape = BladeShape::SlimGrass;
    left.lengthMetres = 0.28f;
    left.widthMetres = 0.012f;
    left.leanRadians = lean;
    left.rootOffsetMetres = {-0.025f, 0.0f, -0.015f};
    SyntheticBlade right = left;
    right.leanRadians = -lean;
    right.rootOffsetMetres = {0.025f, 0.0f, 0.015f};
    scene.blades = {left, right};
    const SyntheticFrame frame = renderScene(scene);
    const ExtractResult result = extractBlades(frame.frame);
    const AccuracyReport accuracy = evaluateCapture(frame.truth, result);
    SCOPED_TRACE("lean " + std::to_string(lean));
    EXPECT_EQ(accuracy.bladesFound, 2);
    EXPECT_EQ(result.blades.size(), 2u);
    EXPECT_GT(accuracy.lengthRatio, 0.9);
    EXPECT_LT(accuracy.lengthRatio, 1.1);
    ASSERT_EQ(result.clusters.size(), 2u);
    EXPECT_EQ(result.clusters[0].layerCount, 2);
  }
}

/** A sweep cluster captured from depth alone with `options`, and how many blades its truth has. */
std::pair<ExtractResult, int> captureSweepCluster(std::uint64_t seed, const ExtractOptions& options) {
  SyntheticScene scene = makeSweepCluster(seed);
  scene.colour = false;
  SyntheticFrame frame = renderScene(scene);
  roundToDepthPng(frame.frame); // as the sweep captures it
  return {extractBlades(frame.frame, options), static_cast<int>(frame.truth.centrelinePx.size())};
}

/** How many of the messages in `list` (Cluster::split, rejected, joined) of `result`'s clusters hold
 * `phrase`. */
std::size_t countMessages(const ExtractResult& result, std::vector<std::string> Cluster::*list,
                          const std::string& phrase) {
  std::size_t count = 0;
  for (const Cluster& c : result.clusters) {
    const std::vector<std::string>& messages = c.*list;
    count +=
        static_cast<std::size_t>(std::count_if(messages.begin(), messages.end(), [&](const std::string& m) {
          return m.find(phrase) != std::string::npos;
        }));
  }
  return count;
}

TEST(CaptureDepthSplit, BladesMergedInTheOutlineWhoseTipsPartInDepthAreSplit) {
  // Sweep clusters (a crossing one and dense fans) where blades of different depths merge in the outline up
  // to their tips: the merged blade's outer half holds a surface for each, and each becomes a blade. Without
  // the split each cluster comes out short.
  ExtractOptions without;
  without.depthSplit = false;
  for (const std::uint64_t seed : {240u, 84u, 121u, 180u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    EXPECT_GE(countMessages(result, &Cluster::split, "parts in depth towards its tip"), 1u);
    EXPECT_LT(static_cast<int>(captureSweepCluster(seed, without).first.blades.size()), expected);
  }
  // A plain fan, its blades tilted towards and away from the camera, holds one surface per blade: no split.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SyntheticScene fan = makeCluster(BladeShape::SlenderLeaf, 5, 0.3f, 0.0f, seed);
    fan.colour = false;
    fan.pitchRadians = 0.3f;
    const ExtractResult result = extractBlades(renderScene(fan).frame);
    EXPECT_EQ(result.blades.size(), 5u);
    for (const Cluster& c : result.clusters) {
      EXPECT_TRUE(c.split.empty()) << c.split.front();
    }
  }
}

TEST(CaptureDepthSplit, BladesWhoseNeighboursHideAllButTheirEndsPartInDepthOverTheirOuterThird) {
  // Dense fans (and crossing ones) whose neighbouring blades overlap up to near their tips: beyond its
  // junctions a merged blade shows only its last 10–20 px, too few pixels for two surfaces, but the blades
  // part in depth over the outer third of their length. The second look finds them; without it (share 0)
  // each cluster comes out short.
  ExtractOptions without;
  without.depthSplitOuterShare = 0.0;
  without.tipSurfacesOuterShare = 0.0; // which would find them by their surfaces instead
  for (const std::uint64_t seed : {89u, 191u, 461u, 102u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    EXPECT_GE(countMessages(result, &Cluster::split, "over the outer 35 % of its length"), 1u);
    const ExtractResult short_ = captureSweepCluster(seed, without).first;
    EXPECT_LT(static_cast<int>(short_.blades.size()), expected);
    EXPECT_EQ(countMessages(short_, &Cluster::split, "over the outer"), 0u);
  }
}

TEST(CaptureElongation, ABladeWhoseBaseWidensWhereItMeetsItsNeighboursIsStillABlade) {
  // A plain fan (399) and crossing fans (130, 178, 566) where a blade's segment, closed across its base
  // between junctions far apart, is wide only at that base: judged by its widest point it was "not
  // elongated" (167 px long, 72 px wide in 399) and the blade was lost. Judged beyond its lowest tenth,
  // every cluster counts exactly, and no segment of them is rejected for its elongation.
  for (const std::uint64_t seed : {399u, 130u, 178u, 566u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    EXPECT_EQ(countMessages(result, &Cluster::rejected, "not elongated"), 0u);
  }
  // The test still rejects: asked for an elongation of 40, more than any of the fan's blades has beyond its
  // base, it rejects all five as not elongated.
  ExtractOptions strict;
  strict.minElongation = 40.0;
  const ExtractResult none = captureSweepCluster(399, strict).first;
  EXPECT_TRUE(none.blades.empty());
  EXPECT_GE(countMessages(none, &Cluster::rejected, "not elongated"), 5u);
}

TEST(CaptureTipSurfaces, BladesWhoseNeighboursHideAllButTheirEndsAreFoundByTheSurfaceTheyEndOn) {
  // Dense fans (and a crossing one) where a blade's neighbours hide all of it but its outer end, and the
  // outline shows no junction for it: over the cluster's outer quarter its end is a depth surface of its own
  // that ends in a free tip where no captured blade ends. Without the pass (share 0) each comes out short.
  ExtractOptions without;
  without.tipSurfacesOuterShare = 0.0;
  for (const std::uint64_t seed : {124u, 299u, 493u, 612u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    EXPECT_GE(countMessages(result, &Cluster::split, "where no blade ends: one blade more"), 1u);
    const ExtractResult short_ = captureSweepCluster(seed, without).first;
    EXPECT_LT(static_cast<int>(short_.blades.size()), expected);
    EXPECT_EQ(countMessages(short_, &Cluster::split, "where no blade ends"), 0u);
  }
  // Plain clusters of every shape whose edges jitter by 1.5 px (three times the sensor model's default) and
  // lose 40 % of their pixels to dropouts: a jag of an edge, or the end of a piece cut off by a break in a
  // thin blade's depth, is no free tip (without the outline's turn at the tip, 7 of these 50 gain a blade).
  for (const BladeShape shape : kBladeShapes) {
#ifdef SYLVA_SWEEP_SANITIZED
    const std::uint64_t seeds = 2; // under the sanitizers the point is the memory checks, not the count
#else
    const std::uint64_t seeds = 10;
#endif
    for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
      SCOPED_TRACE(std::string(bladeShapeName(shape)) + " cluster " + std::to_string(seed));
      SyntheticScene scene = makeCluster(shape, 3 + static_cast<int>(seed % 5), 0.3f, 0.0f, seed);
      scene.lateralNoisePx = 1.5f;
      scene.edgeDropout = 0.4f;
      const SyntheticFrame frame = renderScene(scene);
      const ExtractResult result = extractBlades(frame.frame);
      EXPECT_EQ(result.blades.size(), frame.truth.centrelinePx.size());
      EXPECT_EQ(countMessages(result, &Cluster::split, "where no blade ends"), 0u);
    }
  }
  // Plain fans, occluded ones, crossing and dense ones whose every tip is captured gain nothing from it.
  for (const std::uint64_t seed : {1u, 2u, 3u, 4u, 6u, 8u, 12u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(countMessages(result, &Cluster::split, "where no blade ends"), 0u);
  }
}

TEST(CaptureDepthLayers, DroppedPartsNameThePixelsTheyHold) {
  // Crossing fans whose nearer layer leaves single pixels beside the farther one: each dropped part is named
  // with the pixels it holds (a part one pixel thin encloses no area within its outline, and was once
  // reported as "a part of 0 px").
  const ExtractResult result = captureSweepCluster(629, ExtractOptions{}).first;
  ASSERT_FALSE(result.droppedParts.empty());
  for (const std::string& dropped : result.droppedParts) {
    EXPECT_THAT(dropped, testing::ContainsRegex("a part of [1-9][0-9]* pixels? at")) << dropped;
    EXPECT_THAT(dropped, testing::HasSubstr("px² a part needs")) << dropped;
  }
}

TEST(CapturePointedTips, ShortPointedTipsBeyondOverlappingNeighboursAreBlades) {
  // Dense fans (and an occluded one) where a blade's neighbours overlap it up to near its end: its tip stands
  // only 9–15 px above its junctions, short of a blade's minimum length, but it is pointed, and it is a
  // blade. Without the exception (fraction 1) each cluster comes out one short.
  ExtractOptions without;
  without.pointedTipFraction = 1.0;
  without.tipSurfacesOuterShare = 0.0; // which would find some of them by their surfaces instead
  for (const std::uint64_t seed : {488u, 772u, 821u, 849u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    const auto [short_, same] = captureSweepCluster(seed, without);
    EXPECT_EQ(static_cast<int>(short_.blades.size()), expected - 1);
    EXPECT_GE(countMessages(short_, &Cluster::rejected, "too short"), 1u)
        << "without the exception the tip is rejected as too short";
  }
}

TEST(CaptureNotches, TipsThatPartOnlyNearTheirEndsAreJunctions) {
  // Dense fans whose neighbouring tips part only over their last few centimetres: the valleys between them
  // are too shallow for the prominence test beside the longest blade, but they are notches. Without notches
  // each cluster comes out short.
  ExtractOptions without;
  without.notchProminence = 0.0;
  without.tipSurfacesOuterShare = 0.0; // which would find them by their surfaces instead
  for (const std::uint64_t seed : {68u, 373u, 526u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    std::size_t shallow = 0;
    for (const Cluster& c : result.clusters) {
      for (const Junction& j : c.junctions) {
        shallow += j.prominence < ExtractOptions{}.prominence ? 1 : 0;
      }
    }
    EXPECT_GE(shallow, 1u) << "a notch below the prominence test is a junction";
    EXPECT_LT(static_cast<int>(captureSweepCluster(seed, without).first.blades.size()), expected);
  }
}

/** How many of a sweep cluster's blades, captured from depth alone with `options`, are within 10 % in width.
 */
int widthsWithin10(std::uint64_t seed, const ExtractOptions& options) {
  SyntheticScene scene = makeSweepCluster(seed);
  scene.colour = false;
  SyntheticFrame frame = renderScene(scene);
  roundToDepthPng(frame.frame);
  const AccuracyReport report = evaluateCapture(frame.truth, extractBlades(frame.frame, options));
  return static_cast<int>(std::count_if(report.bladeWidthErrors.begin(), report.bladeWidthErrors.end(),
                                        [](double e) { return e <= 0.10; }));
}

/** Sweep cluster `seed` is counted exactly with every blade within 10 % of its width, and with `without` at
 * least `fewer` blades are not. */
void expectEveryWidthWithin10(std::uint64_t seed, const ExtractOptions& without, int fewer) {
  const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
  EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
  EXPECT_EQ(widthsWithin10(seed, ExtractOptions{}), expected) << "every blade within 10 %";
  EXPECT_LE(widthsWithin10(seed, without), expected - fewer);
}

TEST(CaptureOccludedWidths, ABladeWhoseEdgeANearerBladeHidesIsAsWideAsWhereBothEdgesShow) {
  // Occluded sweep clusters: the narrow blade in front hides one edge of its neighbour along most of its
  // length, so the part of the neighbour that shows is narrower than the neighbour. Taking the width there
  // from where both its edges show brings the neighbour within 10 %; measured on what shows, it is not.
  ExtractOptions without;
  without.occludedWidths = false;
  for (const std::uint64_t seed : {12u, 93u, 223u, 231u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    EXPECT_EQ(widthsWithin10(seed, ExtractOptions{}), expected) << "every blade within 10 %";
    EXPECT_EQ(widthsWithin10(seed, without), expected - 1);
  }
  // Crossing sweep clusters: a blade of the back fan passes behind one of the front fan, which hides it
  // whole across its width, so no depth of its own lies on its axis there. The depth of its nearest seen
  // samples tells that the edges there are a nearer blade's: the stretch takes its width from both sides
  // (measured on what shows, 1-2 px of blades 15-20 px wide).
  for (const std::uint64_t seed : {36u, 82u, 218u}) {
    SCOPED_TRACE("crossing sweep cluster " + std::to_string(seed));
    expectEveryWidthWithin10(seed, without, 2);
  }
  // Where nothing nearer borders a blade the widths are what shows, to the bit.
  SyntheticScene fan = makeCluster(BladeShape::SlenderLeaf, 5, 0.3f, 0.0f, 7);
  fan.colour = false;
  const SyntheticFrame frame = renderScene(fan);
  const ExtractResult a = extractBlades(frame.frame);
  const ExtractResult b = extractBlades(frame.frame, without);
  ASSERT_EQ(a.blades.size(), b.blades.size());
  for (std::size_t i = 0; i < a.blades.size(); ++i) {
    EXPECT_EQ(a.blades[i].widthsPx, b.blades[i].widthsPx) << "blade " << i;
  }
}

TEST(CaptureSurfaceWidths, ABladeInFrontOfItsNeighbourIsAsWideAsItsOwnSurface) {
  // Dense sweep clusters whose blades overlap at nearly the same place: the blades found on a medial axis
  // (split from merged ones, depth parts) measured across the region they share come out as wide as two.
  // Over their own depth surface, up to where the farther neighbour begins, every blade is within 10 %.
  ExtractOptions without;
  without.surfaceWidths = false;
  for (const std::uint64_t seed : {116u, 667u, 787u}) {
    SCOPED_TRACE("dense sweep cluster " + std::to_string(seed));
    expectEveryWidthWithin10(seed, without, 2);
    const ExtractResult result = captureSweepCluster(seed, ExtractOptions{}).first;
    // Only narrower, and only blades found on a medial axis.
    const ExtractResult plain = captureSweepCluster(seed, without).first;
    ASSERT_EQ(plain.blades.size(), result.blades.size());
    for (std::size_t i = 0; i < result.blades.size(); ++i) {
      for (std::size_t k = 0; k < result.blades[i].widthsPx.size(); ++k) {
        EXPECT_LE(result.blades[i].widthsPx[k], plain.blades[i].widthsPx[k])
            << "blade " << i << " knot " << k;
      }
      if (!result.blades[i].medialAxis) {
        EXPECT_EQ(result.blades[i].widthsPx, plain.blades[i].widthsPx) << "blade " << i;
      }
    }
  }
}

TEST(CaptureWidthSmoothing, TheSensorsEdgeJitterIsSmoothedAndABladesShapeKept) {
  // Sweep clusters (dense, occluded, crossing) whose widths jitter from knot to knot with the sensor's edges:
  // smoothed along each blade, every blade is within 10 %; unsmoothed, not.
  ExtractOptions off;
  off.widthSmoothKnots = 0.0;
  for (const auto& [seed, fewer] :
       std::vector<std::pair<std::uint64_t, int>>{{180, 2}, {802, 2}, {352, 1}, {707, 1}}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    expectEveryWidthWithin10(seed, off, fewer);
  }
  // Without sensor noise the smoothing changes next to nothing; with it, the widths come closer to the truth.
  for (const bool noise : {false, true}) {
    SCOPED_TRACE(noise ? "with noise" : "noise-free");
    SyntheticScene fan = makeCluster(BladeShape::SlenderLeaf, 5, 0.3f, 0.0f, 7);
    fan.colour = false;
    fan.noise = noise;
    const SyntheticFrame frame = renderScene(fan);
    const ExtractResult smoothed = extractBlades(frame.frame);
    const ExtractResult raw = extractBlades(frame.frame, off);
    ASSERT_EQ(smoothed.blades.size(), raw.blades.size());
    const double errSmoothed = evaluateCapture(frame.truth, smoothed).widthError;
    const double errRaw = evaluateCapture(frame.truth, raw).widthError;
    if (noise) {
      EXPECT_LT(errSmoothed, errRaw - 0.002);
    } else {
      for (std::size_t i = 0; i < raw.blades.size(); ++i) {
        for (std::size_t k = 0; k < raw.blades[i].widthsPx.size(); ++k) {
          EXPECT_NEAR(smoothed.blades[i].widthsPx[k], raw.blades[i].widthsPx[k], 0.25f)
              << "blade " << i << " knot " << k;
        }
      }
    }
  }
  // A lobed leaf's width rises and falls within a fifth of its length: the median keeps it.
  SyntheticScene lobed = makeCluster(BladeShape::SlenderLeaf, 3, 0.3f, 0.0f, 43);
  for (SyntheticBlade& blade : lobed.blades) {
    blade.lobe = 3.0f;
  }
  const SyntheticFrame frame = renderScene(lobed);
  EXPECT_LE(evaluateCapture(frame.truth, extractBlades(frame.frame)).widthError,
            evaluateCapture(frame.truth, extractBlades(frame.frame, off)).widthError + 0.005);
}

TEST(CaptureJoin, ABladeBrokenInTwoByANearerOneCrossingItIsOneBlade) {
  // Crossing fans where a blade of the front fan crosses one of the back fan at a shallow angle: the straight
  // runs across it do not reach the far side, so the back blade's outer part becomes a depth layer of its
  // own. Joined to the blade whose tip points at it, the count is exact; kept apart, one too many.
  ExtractOptions without;
  without.joinBroken = false;
  for (const std::uint64_t seed : {74u, 201u, 331u, 909u}) {
    SCOPED_TRACE("sweep cluster " + std::to_string(seed));
    const auto [result, expected] = captureSweepCluster(seed, ExtractOptions{});
    EXPECT_EQ(static_cast<int>(result.blades.size()), expected);
    EXPECT_EQ(countMessages(result, &Cluster::joined, "broke off where a nearer blade crosses it"), 1u);
    for (const Cluster& c : result.clusters) {
      for (const int b : c.blades) {
        ASSERT_GE(b, 0);
        ASSERT_LT(static_cast<std::size_t>(b), result.blades.size()) << "the clusters name kept blades only";
      }
    }
    EXPECT_EQ(static_cast<int>(captureSweepCluster(seed, without).first.blades.size()), expected + 1);
  }
}

} // namespace
} // namespace sylva::capture
