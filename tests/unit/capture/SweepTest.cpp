// The capture sweep (issue 30): random clusters of every class new users brought (fans, a blade inside its
// neighbour's outline, crossing fans, dense fans of 11+ blades over 60°) under camera roll and pitch and edge
// dropouts, captured from depth alone and measured against their truth. The targets are an exact
// count on ≥ 95 % of clusters and a width error ≤ 10 % on ≥ 95 % of blades. They are not met yet: this test
// holds what the extractor reaches today (docs/capture.md, "Overlapping, crossing and dense blades") so that
// it can only go up, and plain fans must stay exact.
#include <sylva/capture/Synthetic.hpp>
#include <sylva/core/Error.hpp>

#include "TempDir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

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
  std::printf("%-9s %4d clusters: count exact %5.1f %% (%d too few), width within 10 %% on %5.1f %% of %d "
              "blades\n",
              name, t.clusters, 100.0 * t.exactShare(), t.fewer, 100.0 * t.widthShare(), t.blades);
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
  EXPECT_EQ(report.all.clusters, clusters);
  RecordProperty("count_exact", std::to_string(report.all.exactShare()));
  RecordProperty("width_within_10", std::to_string(report.all.widthShare()));
  const SweepTally& fans = report.byLayout[0];
  EXPECT_GE(fans.exactShare(), 0.97) << "a plain fan, rolled and pitched, is counted exactly";
  EXPECT_GE(fans.widthShare(), 0.97);
#ifndef SYLVA_SWEEP_SANITIZED
  // Measured: 200 clusters 49.5 % exact, widths within 10 % on 78.3 % of 1,460 blades; 1,000 clusters
  // (SYLVA_FULL=1) 47.0 % and 79.3 % of 7,224. Raise these when the extractor separates depth layers.
  EXPECT_GE(report.all.exactShare(), 0.45);
  EXPECT_GE(report.all.widthShare(), 0.76);
#endif
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

} // namespace
} // namespace sylva::capture
