// The tree renderer against its CPU references: the culling compute pass gives exactly the instances
// cullInstances() keeps, for every piece type, with and without size culling; the draw is deterministic; one
// multi-draw and the per-piece baseline draw the same image, and so do commands of any chunk size; size
// culling drops many pieces of a distant forest and leaves its picture; the depth-only view (shadow casters)
// writes the shaded view's depth.
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/Tessellation.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include "GlTest.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace sylva::trees {
namespace {

using TreeRendererTest = test::GlTest;

render::Camera lookingAt(glm::vec3 from, glm::vec3 to) {
  render::Camera camera;
  camera.position = from;
  camera.target = to;
  camera.fovY = glm::radians(45.0f);
  camera.nearPlane = 0.1f;
  camera.farPlane = 500.0f;
  return camera;
}

TEST_F(TreeRendererTest, CullingPassMatchesTheCpuReference) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "apple", "weeping-willow"}, 6, 6.0f, 2));
  TreeRenderer renderer(shaders(), forest);
  std::vector<gpu::JointFrame> frames;
  forestFrames(*forest, {}, frames);
  std::vector<gpu::TreePieceGpu> table;
  for (const Piece& p : forest->pieces.pieces) {
    table.push_back(pieceTableEntry(p));
  }
  const float aspect = 16.0f / 9.0f;
  int partial = 0;
  for (const auto& [camera, distance] : {std::pair{lookingAt({-20, 6, 20}, {0, 2, 0}), 0.0f},
                                         std::pair{lookingAt({0, 3, 0}, {15, 2, 3}), 0.0f},
                                         std::pair{lookingAt({-30, 10, -30}, {0, 0, 0}), 30.0f},
                                         std::pair{lookingAt({5, 40, 5}, {5, 0, 4}), 0.0f}}) {
    TreeLod lod;
    lod.drawDistance = distance;
    renderer.cull(camera, aspect, lod);
    const Frustum frustum = camera.frustum(aspect);
    const auto expected = cullInstances(renderer.instances(), table, frames, frustum.planes(),
                                        camera.position, distance, 1.25f);
    std::size_t kept = 0;
    for (std::size_t t = 0; t < table.size(); ++t) {
      std::vector<std::uint32_t> gpu = renderer.readVisible(t);
      std::sort(gpu.begin(), gpu.end());
      EXPECT_EQ(gpu, expected[t]) << "piece type " << t;
      kept += expected[t].size();
    }
    partial += kept > 0 && kept < renderer.instances().instances.size() ? 1 : 0;
  }
  // The cameras must cull something and keep something, or equality would prove little.
  EXPECT_GE(partial, 3);
}

TEST_F(TreeRendererTest, DrawIsDeterministicAndTheBaselineDrawsTheSameImage) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "california-black-oak"}, 2, 6.0f, 5));
  TreeRenderer renderer(shaders(), forest);
  const render::Camera camera = lookingAt({-8, 4, 10}, {0, 2, 0});
  render::RenderTarget target(200, 150);
  TreeLod lod;
  auto draw = [&](bool perPiece) {
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    if (perPiece) {
      renderer.drawPerPiece(camera, 200, 150, 0.0, lod);
    } else {
      renderer.cull(camera, target.aspect(), lod);
      renderer.draw(camera, 200, 150, 0.0, lod);
    }
    return target.readColor();
  };
  const Image a = draw(false);
  const Image b = draw(false);
  const Image c = draw(true);
  EXPECT_TRUE(a == b);
  EXPECT_TRUE(a == c);
  // Something was drawn.
  int covered = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      covered += a.get(x, y, 0) + a.get(x, y, 1) + a.get(x, y, 2) > 0.0f ? 1 : 0;
    }
  }
  EXPECT_GT(covered, 500);
}

TEST_F(TreeRendererTest, ChunkSizeDoesNotChangeTheImage) {
  // The cull picks the quads per command from the largest level (15 at 16, 1 at 64). With segments long
  // enough that no edge reaches level 16, both largest levels tessellate alike: the images, patch ids
  // included (the tiles view shows them), must be identical, and so must the visible counts.
  ASSERT_NE(quadsPerCommand(16.0f), quadsPerCommand(64.0f));
  auto forest = std::make_shared<Forest>(gridForest({"almond", "california-black-oak"}, 2, 6.0f, 5));
  TreeRenderer renderer(shaders(), forest);
  const render::Camera camera = lookingAt({-8, 4, 10}, {0, 2, 0});
  render::RenderTarget target(200, 150);
  auto draw = [&](float maxLevel, TreeView view) {
    TreeLod lod;
    lod.maxLevel = maxLevel;
    lod.pixelsPerSegment = 40.0f;
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 0.0f));
    renderer.cull(camera, target.aspect(), lod);
    TreeDrawOptions options;
    options.view = view;
    renderer.draw(camera, 200, 150, 0.0, lod, nullptr, options);
    return std::pair{target.readColor(), renderer.readVisibleCounts()};
  };
  for (TreeView view : {TreeView::Tiles, TreeView::Shaded}) {
    const auto [coarse, coarseCounts] = draw(16.0f, view);
    const auto [fine, fineCounts] = draw(64.0f, view);
    EXPECT_TRUE(coarse == fine) << "view " << static_cast<int>(view);
    EXPECT_EQ(coarseCounts, fineCounts);
  }
  // Patch ids differ across each piece's quads (the green channel of the tiles view): more than one chunk's
  // worth of quads is on screen, so a wrong chunk base would have shown.
  const Image tiles = draw(64.0f, TreeView::Tiles).first;
  std::vector<bool> seen(256, false);
  int patches = 0;
  for (int y = 0; y < tiles.height(); ++y) {
    for (int x = 0; x < tiles.width(); ++x) {
      const auto id = static_cast<std::size_t>(std::lround(tiles.get(x, y, 1) * 255.0f));
      if (tiles.get(x, y, 3) > 0.0f && !seen[id]) {
        seen[id] = true;
        ++patches;
      }
    }
  }
  EXPECT_GT(patches, static_cast<int>(kMaxQuadsPerCommand));
}

TEST_F(TreeRendererTest, SizeCullingMatchesTheCpuReferenceAndKeepsThePicture) {
  // A forest seen from afar (perspective) and from above as a shadow cascade sees it (orthographic): the
  // GPU's lists equal the CPU reference with the same terms, size culling drops much of what the frustum
  // keeps, and the picture hardly changes (the dropped pieces span under a pixel).
  auto forest = std::make_shared<Forest>(gridForest({"almond", "california-black-oak"}, 3, 6.0f, 5));
  TreeRenderer renderer(shaders(), forest);
  std::vector<gpu::JointFrame> frames;
  forestFrames(*forest, {}, frames);
  std::vector<gpu::TreePieceGpu> table;
  for (const Piece& p : forest->pieces.pieces) {
    table.push_back(pieceTableEntry(p));
  }
  const int width = 320;
  const int height = 180;
  render::RenderTarget target(width, height);
  render::Camera sun = lookingAt({6, 80, 6.5f}, {6, 0, 6});
  sun.orthoHeight = 12.0f;
  sun.farPlane = 200.0f;
  for (const render::Camera& camera : {lookingAt({-20, 8, 30}, {6, 3, 6}), sun}) {
    auto drawn = [&](float minPixels) {
      TreeLod lod;
      lod.minPixels = minPixels;
      target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 0.0f));
      renderer.cull(camera, width, height, lod);
      renderer.draw(camera, width, height, 0.0, lod);
      std::size_t kept = 0;
      const auto expected = cullInstances(
          renderer.instances(), table, frames, camera.frustum(target.aspect()).planes(), camera.position,
          0.0f, 1.25f, sizeCullTerms(camera.fovY, camera.orthoHeight, height, minPixels));
      for (std::size_t t = 0; t < table.size(); ++t) {
        std::vector<std::uint32_t> gpu = renderer.readVisible(t);
        std::sort(gpu.begin(), gpu.end());
        EXPECT_EQ(gpu, expected[t]) << "piece type " << t << ", " << minPixels << " pixels";
        kept += expected[t].size();
      }
      return std::pair{target.readColor(), kept};
    };
    const auto [all, allKept] = drawn(0.0f);
    const auto [sized, sizedKept] = drawn(1.0f);
    const auto [coarse, coarseKept] = drawn(30.0f);
    // Size culling drops pieces the frustum keeps; a coarser threshold drops more.
    EXPECT_LT(sizedKept, allKept * 3 / 4) << "ortho " << camera.orthoHeight;
    EXPECT_LT(coarseKept, sizedKept);
    // Coverage: the background is cleared to black.
    auto on = [](const Image& image, int x, int y) {
      return image.get(x, y, 0) + image.get(x, y, 1) + image.get(x, y, 2) > 0.0f;
    };
    int covered = 0;
    int changed = 0;
    int coarseChanged = 0;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        covered += on(all, x, y) ? 1 : 0;
        changed += on(all, x, y) != on(sized, x, y) ? 1 : 0;
        coarseChanged += on(all, x, y) != on(coarse, x, y) ? 1 : 0;
      }
    }
    EXPECT_GT(covered, 200);
    // Bare twigs under a pixel each hit a pixel's sample now and then: dropping them changes a few per cent
    // of the coverage (under 10 %; in a scene with foliage, 25 pixels of 921,600). The control shows the
    // comparison can fail: pieces under 30 pixels are most of the picture.
    EXPECT_LE(changed, covered / 10) << "ortho " << camera.orthoHeight;
    EXPECT_GT(coarseChanged, covered / 2) << "ortho " << camera.orthoHeight;
  }
}

TEST_F(TreeRendererTest, DepthViewWritesTheShadedDepth) {
  auto forest = std::make_shared<Forest>(gridForest({"almond", "california-black-oak"}, 2, 6.0f, 5));
  TreeRenderer renderer(shaders(), forest);
  const render::Camera camera = lookingAt({-8, 4, 10}, {0, 2, 0});
  render::RenderTarget target(200, 150);
  auto depth = [&](TreeView view) {
    TreeLod lod;
    target.begin(glm::vec4(0.0f));
    renderer.cull(camera, 200, 150, lod);
    TreeDrawOptions options;
    options.view = view;
    renderer.draw(camera, 200, 150, 0.0, lod, nullptr, options);
    return std::pair{target.readDepth(), target.readColor()};
  };
  const auto [shadedDepth, shaded] = depth(TreeView::Shaded);
  const auto [depthOnly, colour] = depth(TreeView::Depth);
  EXPECT_TRUE(shadedDepth == depthOnly);
  int covered = 0;
  int coloured = 0;
  for (int y = 0; y < shaded.height(); ++y) {
    for (int x = 0; x < shaded.width(); ++x) {
      covered += shadedDepth.get(x, y, 0) < 1.0f ? 1 : 0;
      coloured += colour.get(x, y, 0) + colour.get(x, y, 1) + colour.get(x, y, 2) > 0.0f ? 1 : 0;
    }
  }
  EXPECT_GT(covered, 500);
  EXPECT_EQ(coloured, 0); // no shading: the depth program writes no colour of its own
}

} // namespace
} // namespace sylva::trees
