// Blade extraction on real data: the Middlebury 2006 Aloe disparity map (data/external/aloeGT.png, fetched by
// scripts/fetch-sample-data.sh). There is no ground truth for the leaves, so the checks are plausibility
// bounds that the rosette's leaves meet and clearly wrong captures (the pot as a blade, leaves cut into
// short fragments, one giant blob, skeletons off the leaves) do not. The options are the ones docs/capture.md
// uses: the region above the pot (y < 760) and the rosette's core as the centre.
#include <sylva/capture/Depth.hpp>
#include <sylva/capture/Extract.hpp>
#include <sylva/core/Image.hpp>

#include "ExternalData.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace sylva::capture {
namespace {

/** True when pixel (x, y) or one of its 8 neighbours is in the mask. */
bool nearMask(const ExtractResult& r, glm::vec2 p) {
  const int cx = static_cast<int>(std::lround(p.x));
  const int cy = static_cast<int>(std::lround(p.y));
  for (int y = cy - 1; y <= cy + 1; ++y) {
    for (int x = cx - 1; x <= cx + 1; ++x) {
      if (x >= 0 && y >= 0 && x < r.width && y < r.height &&
          r.mask[static_cast<std::size_t>(y) * r.width + x] != 0) {
        return true;
      }
    }
  }
  return false;
}

TEST(Aloe, RosetteLeavesAreBlades) {
  const std::filesystem::path path = test::externalData("aloeGT.png");
  SYLVA_REQUIRE_EXTERNAL_DATA(path);
  const DepthFrame frame = loadMiddlebury(path);
  EXPECT_TRUE(frame.relativeDepth) << "uncalibrated Middlebury depth is nominal";
  EXPECT_EQ(frame.kind, DepthSourceKind::Middlebury);

  ExtractOptions options;
  options.roi = {0, 0, 1282, 760};
  options.centre = CentreMode::Manual;
  options.centrePx = {770.0f, 640.0f};
  const ExtractResult result = extractBlades(frame, options);

  std::printf("aloe: %dx%d, %zu blades in %zu clusters, depth %.3f-%.3f m (nominal)\n", frame.width,
              frame.height, result.blades.size(), result.clusters.size(), result.nearMetres,
              result.farMetres);
  for (const std::string& w : result.warnings) {
    std::printf("  warning: %s\n", w.c_str());
  }
  for (std::size_t b = 0; b < result.blades.size(); ++b) {
    const CapturedBlade& blade = result.blades[b];
    const float maxWidth = *std::max_element(blade.widthsPx.begin(), blade.widthsPx.end());
    std::printf(
        "  blade %zu: cluster %d, length %.0f px, max width %.1f px, elongation %.1f, side ratio %.2f, "
        "%s%s\n",
        b, blade.cluster, blade.lengthPx, maxWidth, blade.lengthPx / maxWidth, blade.sideRatio,
        blade.medialAxis ? "medial axis" : "symmetric matching",
        blade.touchesBorder ? ", cut by the border" : "");
  }

  EXPECT_GE(result.blades.size(), 5u);
  EXPECT_LE(result.blades.size(), 14u);
  ASSERT_FALSE(result.clusters.empty());

  // The rosette's leaves. Leaves in front of others are depth layers of their own (clusters of their own), so
  // the checks run over every blade: the six long leaves that radiate from the core, none a fragment.
  int leaves = 0;
  for (std::size_t b = 0; b < result.blades.size(); ++b) {
    const CapturedBlade& blade = result.blades[b];
    ASSERT_FALSE(blade.widthsPx.empty());
    const float maxWidth = *std::max_element(blade.widthsPx.begin(), blade.widthsPx.end());
    leaves += blade.lengthPx >= 400.0f ? 1 : 0;
    EXPECT_GE(blade.lengthPx, 150.0f) << "blade " << b;
    EXPECT_LE(blade.lengthPx, 1300.0f) << "blade " << b;
    EXPECT_GE(maxWidth, 15.0f) << "blade " << b;
    EXPECT_LE(maxWidth, 220.0f) << "blade " << b;
    EXPECT_GE(blade.lengthPx / maxWidth, 3.0f) << "blade " << b;
  }
  EXPECT_GE(leaves, 6);
  const auto layered = std::count_if(result.clusters.begin(), result.clusters.end(),
                                     [](const Cluster& c) { return c.layer >= 0 && !c.blades.empty(); });
  EXPECT_GE(layered, 2) << "the rosette's leaves lie at several depths";

  int symmetric = 0;
  for (std::size_t b = 0; b < result.blades.size(); ++b) {
    const CapturedBlade& blade = result.blades[b];
    symmetric += blade.medialAxis ? 0 : 1;
    ASSERT_FALSE(blade.outline.empty());
    ASSERT_GE(blade.tip, 0);
    ASSERT_LT(static_cast<std::size_t>(blade.tip), blade.outline.size());
    const glm::vec2 tip = blade.outline[static_cast<std::size_t>(blade.tip)];
    EXPECT_TRUE(nearMask(result, tip)) << "blade " << b << " tip (" << tip.x << ", " << tip.y << ")";
    ASSERT_FALSE(blade.skeletonPx.empty());
    const glm::vec2 end = blade.skeletonPx.back();
    EXPECT_TRUE(nearMask(result, end)) << "blade " << b << " skeleton tip (" << end.x << ", " << end.y << ")";
    // Nothing below the region of interest (the pot and the floor).
    EXPECT_LT(tip.y, 760.0f) << "blade " << b;
  }
  EXPECT_GE(symmetric, 3);

  const Image overlay = overlayImage(frame, result);
  EXPECT_EQ(overlay.width(), frame.width);
  EXPECT_EQ(overlay.height(), frame.height);
}

// Without a region or a centre the pot and the floor are in the mask too: the capture is worse but must still
// find leaves and not throw.
TEST(Aloe, DefaultOptionsFindLeaves) {
  const std::filesystem::path path = test::externalData("aloeGT.png");
  SYLVA_REQUIRE_EXTERNAL_DATA(path);
  const DepthFrame frame = loadMiddlebury(path);
  ExtractResult result;
  ASSERT_NO_THROW(result = extractBlades(frame));
  std::printf("aloe, default options: %zu blades in %zu clusters\n", result.blades.size(),
              result.clusters.size());
  EXPECT_GE(result.blades.size(), 1u);
}

} // namespace
} // namespace sylva::capture
