// Rims and edges are watertight, proven by rendering. Trees of four species (every piece type: I, Y, Psi,
// Branch, Cap, Foot) in random poses and random wind bends are drawn from seeded close-up views of random
// rims at every tessellation level 1 … 64 (and with the distance rule). A closed surface seen from outside
// shows only front faces. Each frame draws the front faces over a black background, then the back faces with
// depth test LESS in pure magenta: a back-face pixel is the inside (or, beyond it, the background) showing
// through a crack. The footprint is defined robustly: only pixels whose 3 x 3 neighbourhood holds no
// background and whose front surface around them is continuous in depth (within 5 %) count, so silhouettes
// (where a grazing back face may win a pixel by rasterisation alone, against the background or a farther
// branch) are out and every crack inside the surface is in. Zero such pixels in every frame = watertight.
// With the rims broken by 3 % the same check must find cracks, so it is known to work.
#include <sylva/core/Random.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include "GlTest.hpp"
#include "TempDir.hpp"

#include <glm/geometric.hpp>

#include <fmt/format.h>

#include <algorithm>

#include <memory>

namespace sylva::trees {
namespace {

constexpr int kWidth = 160;
constexpr int kHeight = 120;
// Each test case takes 8 levels and kViews seeded views of its own, each drawn at those 8 levels. CI: 8 views
// for levels 1..32 and 4 for levels 33..64 (whose frames cost up to 4x as much on llvmpipe: 48 views, 384
// frames); SYLVA_FULL=1: 8 x 128 = 1,024 views, 8,192 frames.
const int kViews = test::fullMode() ? 128 : 8;
int viewsForLevels(int firstLevel) {
  return test::fullMode() || firstLevel <= 32 ? kViews : kViews / 2;
}

std::shared_ptr<Forest> testForest() {
  return std::make_shared<Forest>(
      gridForest({"almond", "california-black-oak", "weeping-willow", "apple"}, 2, 9.0f, 11));
}

/** Segments (rim centre to rim centre) with the radius of the surface around them, world metres. */
struct Bone {
  glm::vec3 a;
  glm::vec3 b;
  float radius;
};

std::vector<Bone> bones(const Forest& forest, const std::vector<gpu::JointFrame>& frames) {
  std::vector<Bone> out;
  auto origin = [](const gpu::JointFrame& f) { return glm::vec3(f.x.w, f.y.w, f.z.w); };
  auto scale = [](const gpu::JointFrame& f) { return glm::length(glm::vec3(f.x.x, f.y.x, f.z.x)); };
  for (std::size_t t = 0; t < forest.trees.size(); ++t) {
    const TreeTopology& topo = forest.trees[t].topology;
    const std::uint32_t offset = forest.jointOffset[t];
    for (const TreeNode& n : topo.nodes) {
      const gpu::JointFrame& root = frames[offset + n.rootJoint];
      const Piece& piece = forest.pieces[static_cast<std::size_t>(n.piece)];
      const float r = scale(root);
      if (piece.leafRims() == 0) {
        const glm::vec3 up = glm::normalize(glm::vec3(root.x.y, root.y.y, root.z.y));
        out.push_back({origin(root), origin(root) + up * (2.0f * r), r});
      }
      for (std::size_t k = 1; k <= piece.leafRims(); ++k) {
        out.push_back({origin(root), origin(frames[offset + n.jointBase + k - 1]), r});
      }
    }
  }
  return out;
}

float distanceToSegment(glm::vec3 p, const Bone& b) {
  const glm::vec3 ab = b.b - b.a;
  const float t = std::clamp(glm::dot(p - b.a, ab) / std::max(glm::dot(ab, ab), 1e-12f), 0.0f, 1.0f);
  return glm::length(p - (b.a + ab * t));
}

class WatertightRig {
public:
  explicit WatertightRig(const shader::Library& library)
      : mForest(testForest()), mTarget(kWidth, kHeight), mRenderer(library, mForest) {}

  /** Pose `index`: wind bends, frames uploaded; returns a camera looking at a random rim from outside. */
  render::Camera pose(int index) {
    Rng rng(hash64(0x7ee5ULL + static_cast<std::uint64_t>(index)));
    std::vector<glm::vec2> bends(mForest->jointCount);
    for (glm::vec2& b : bends) {
      b = glm::vec2(rng.uniform(-0.12f, 0.12f), rng.uniform(-0.12f, 0.12f));
    }
    forestFrames(*mForest, bends, mFrames);
    mRenderer.setFrames(mFrames);
    const std::vector<Bone> all = bones(*mForest, mFrames);
    for (;;) {
      const Bone& at = all[rng.below(static_cast<std::uint32_t>(all.size()))];
      const glm::vec3 target = at.a;
      glm::vec3 dir(rng.uniform(-1.0f, 1.0f), rng.uniform(-0.6f, 1.0f), rng.uniform(-1.0f, 1.0f));
      if (glm::length(dir) < 0.1f) {
        continue;
      }
      const float distance = at.radius * rng.uniform(3.0f, 30.0f);
      render::Camera camera;
      camera.position = target + glm::normalize(dir) * distance;
      camera.target = target;
      camera.fovY = glm::radians(rng.uniform(25.0f, 60.0f));
      camera.nearPlane = 0.02f * at.radius;
      // Pieces well behind the rim in view are culled by the far plane (they cost the most at high levels and
      // prove the least). Unlike a draw distance, a far plane never opens the surface towards the camera: a
      // ray's first hit before the far plane is still a front face.
      camera.farPlane = 2.5f * distance;
      bool outside = true;
      for (const Bone& b : all) {
        if (distanceToSegment(camera.position, b) < 1.6f * b.radius + camera.nearPlane * 4.0f) {
          outside = false;
          break;
        }
      }
      if (outside) {
        return camera;
      }
    }
  }

  /** Inside pixels visible through the surface for `camera` at `level` (0: the distance rule). */
  std::int64_t cracks(const render::Camera& camera, float level, bool breakRims) {
    TreeLod lod;
    lod.fixedLevel = level;
    lod.maxLevel = 64.0f;
    lod.pixelsPerSegment = 2.0f;
    mRenderer.cull(camera, mTarget.aspect(), lod);
    mTarget.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    glDepthFunc(GL_LESS);
    TreeDrawOptions options;
    options.view = TreeView::PieceTypes; // front faces: lit type colours; back faces: pure magenta
    options.breakRims = breakRims;
    options.faces = TreeFaces::Front;
    mRenderer.draw(camera, kWidth, kHeight, 0.0, lod, nullptr, options);
    glDepthMask(GL_FALSE);
    // Where two branches interpenetrate, one's back face crosses the other's front face: a depth tie along
    // the intersection curve. Push back faces back a little; a crack shows the inside far behind the surface.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 8.0f);
    options.faces = TreeFaces::Back;
    mRenderer.draw(camera, kWidth, kHeight, 0.0, lod, nullptr, options);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthMask(GL_TRUE);
    mImage = mTarget.readColor();
    // The front surface's depth (the back faces did not write it), as eye-space distance.
    const Image window = mTarget.readDepth();
    const float n = camera.nearPlane;
    const float f = camera.farPlane;
    const auto eye = [&](int x, int y) { return n * f / (f - window.get(x, y, 0) * (f - n)); };
    const auto is = [&](int x, int y, float r, float g, float b) {
      return mImage.get(x, y, 0) == r && mImage.get(x, y, 1) == g && mImage.get(x, y, 2) == b;
    };
    std::int64_t count = 0;
    for (int y = 1; y + 1 < kHeight; ++y) {
      for (int x = 1; x + 1 < kWidth; ++x) {
        if (!is(x, y, 1.0f, 0.0f, 1.0f)) {
          continue;
        }
        // Inside the footprint: no background around it, and the front surface around it continuous (a
        // silhouette against a farther branch is an edge of the footprint too, not a crack).
        bool inside = true;
        float nearest = 1e30f;
        float farthest = 0.0f;
        for (int dy = -1; dy <= 1 && inside; ++dy) {
          for (int dx = -1; dx <= 1 && inside; ++dx) {
            inside = !is(x + dx, y + dy, 0.0f, 0.0f, 0.0f);
            if (dx != 0 || dy != 0) {
              nearest = std::min(nearest, eye(x + dx, y + dy));
              farthest = std::max(farthest, eye(x + dx, y + dy));
            }
          }
        }
        inside = inside && farthest - nearest < 0.05f * nearest;
        count += inside ? 1 : 0;
      }
    }
    return count;
  }

  const Image& image() const { return mImage; }
  std::size_t visiblePieces() const {
    std::size_t n = 0;
    for (std::uint32_t c : mRenderer.readVisibleCounts()) {
      n += c;
    }
    return n;
  }

private:
  std::shared_ptr<Forest> mForest;
  render::RenderTarget mTarget;
  TreeRenderer mRenderer;
  std::vector<gpu::JointFrame> mFrames;
  Image mImage;
};

class TreeWatertight : public test::GlTest, public ::testing::WithParamInterface<int> {};

TEST_P(TreeWatertight, NoInsideVisibleThroughTheSurface) {
  WatertightRig rig(shaders());
  const int firstLevel = GetParam() * 8 + 1;
  std::size_t pieces = 0;
  int frames = 0;
  for (int view = 0; view < viewsForLevels(firstLevel); ++view) {
    const render::Camera camera = rig.pose(view * 64 + GetParam());
    for (int level = firstLevel; level < firstLevel + 8; ++level) {
      const std::int64_t cracks = rig.cracks(camera, static_cast<float>(level), false);
      pieces += rig.visiblePieces();
      ++frames;
      if (cracks != 0) {
        saveImage(std::filesystem::path(SYLVA_BINARY_DIR) / "golden-out" /
                      fmt::format("tree_crack_l{}_view{}.png", level, view),
                  rig.image());
      }
      ASSERT_EQ(cracks, 0) << "view " << view << ", level " << level << ": " << cracks
                           << " inside pixels through the surface (magenta; image in golden-out/)";
    }
  }
  // The views must actually show pieces (and so rims).
  EXPECT_GT(pieces, static_cast<std::size_t>(frames) * 3);
  RecordProperty("frames", std::to_string(frames));
}

INSTANTIATE_TEST_SUITE_P(Levels, TreeWatertight, ::testing::Range(0, 8),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return fmt::format("levels_{:02}_{:02}", info.param * 8 + 1, info.param * 8 + 8);
                         });

class TreeWatertightChecks : public test::GlTest {};

TEST_F(TreeWatertightChecks, DistanceRuleIsWatertight) {
  // Edge levels from the edges' own midpoints: neighbouring quads (and pieces) differ in level, each shared
  // edge does not.
  WatertightRig rig(shaders());
  for (int view = 0; view < kViews * 8; ++view) {
    const render::Camera camera = rig.pose(100000 + view);
    const std::int64_t cracks = rig.cracks(camera, 0.0f, false);
    ASSERT_EQ(cracks, 0) << "view " << view << ": " << cracks << " inside pixels through the surface";
  }
}

TEST_F(TreeWatertightChecks, BrokenRimsAreCaught) {
  WatertightRig rig(shaders());
  int caught = 0;
  const int views = 16;
  for (int view = 0; view < views; ++view) {
    const render::Camera camera = rig.pose(200000 + view);
    caught += rig.cracks(camera, 8.0f, true) > 0 ? 1 : 0;
  }
  // Many close-ups of a rim show the gap (some look along it, see it hidden behind a branch, or frame a twig
  // too thin for the check's robust footprint); intact rims show none in hundreds of views.
  EXPECT_GE(caught, views / 4) << caught << " of " << views << " views caught the broken rims";
}

} // namespace
} // namespace sylva::trees
