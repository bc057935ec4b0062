// Foliage impostors on the GPU with known geometry: a cloud of two leaf cards, one in front of the sphere's
// centre (red) and one behind it (blue), baked along the view and drawn as billboards. The front card wins
// where they overlap; the depth buffer holds the CPU fragment rule's depth; an opaque quad through the centre
// hides the back card only; a billboard behind another is hidden exactly where the first has leaves. The bake
// runs again only for a new view direction, and the far-field dissolve drops foliage like its tree's pieces.
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/gpu/FoliageRenderer.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>

#include "ExternalData.hpp"
#include "GlTest.hpp"

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>

namespace sylva::trees {
namespace {

using FoliageRendererTest = test::GlTest;

constexpr int kSize = 128;
const glm::vec4 kBackground(0.0f, 0.0f, 0.0f, 0.0f);

/** Trees that are a foot with a cap on it (one foliage anchor each) at `positions`, white leaves. */
std::shared_ptr<Forest> capForest(const std::vector<glm::vec3>& positions) {
  auto forest = std::make_shared<Forest>();
  forest->pieces = standardPieces();
  Species species;
  species.leafColour = glm::vec3(1.0f);
  forest->species.push_back(species);
  const int foot = forest->pieces.find("Foot");
  const int cap = forest->pieces.find("Cap");
  for (const glm::vec3& p : positions) {
    ForestTree tree;
    TreeNode root;
    root.piece = foot;
    TreeNode tip;
    tip.piece = cap;
    tip.parent = 0;
    tip.parentRim = 1;
    tip.depth = 1;
    tree.topology.nodes = {root, tip};
    indexJoints(forest->pieces, tree.topology);
    tree.base = baseFrame(p, 0.0f, 0.2f);
    tree.pose.assign(tree.topology.jointCount(), glm::vec2(0.0f));
    forest->trees.push_back(std::move(tree));
  }
  forest->index();
  return forest;
}

/** Spheres of exactly 1 m, no variation, centred on the tip joint. */
FoliageSettings unitSettings() {
  FoliageSettings s;
  s.textureSize = 128;
  s.minRadius = 1.0f;
  s.maxRadius = 1.0f;
  s.sizeVariation = 0.0f;
  s.rotationVariation = 0.0f;
  s.lift = 0.0f;
  return s;
}

/** Front card: red, at cloud z = +0.45 (t = 0.275); back card: blue, at z = −0.45 (t = 0.725); seen along −z
 * they overlap for x in [−0.25, 0.25]. */
LeafCloud twoCards() {
  LeafCard front;
  front.centre = glm::vec3(-0.15f, 0.0f, 0.45f);
  front.size = glm::vec2(0.8f);
  front.tint = glm::vec3(1.0f, 0.0f, 0.0f);
  LeafCard back = front;
  back.centre = glm::vec3(0.15f, 0.0f, -0.45f);
  back.tint = glm::vec3(0.0f, 0.0f, 1.0f);
  const LeafCard cards[] = {front, back};
  return leafCloudFromCards(cards);
}

Image whiteLeaf() {
  Image image(4, 4, 4, PixelType::U8);
  for (auto& v : image.values<std::uint8_t>()) {
    v = 255;
  }
  return image;
}

render::Camera lookingAlongMinusZ(glm::vec3 centre, float distance) {
  render::Camera camera;
  camera.position = centre + glm::vec3(0.0f, 0.0f, distance);
  camera.target = centre;
  camera.fovY = glm::radians(45.0f);
  camera.nearPlane = 1.0f;
  camera.farPlane = 20.0f;
  return camera;
}

render::Environment noFog() {
  render::Environment e;
  e.fogDensity = 0.0f;
  return e;
}

/** The world sphere centre of anchor `i`. */
glm::vec3 centreOf(const FoliageRenderer& foliage, const Forest& forest, std::size_t i) {
  std::vector<gpu::JointFrame> frames;
  forestFrames(forest, {}, frames);
  return anchorCentre(foliage.anchors()[i], frames);
}

/** Pixel (column, row from the top) showing world point `p`. */
glm::ivec2 pixelOf(const render::Camera& camera, glm::vec3 p) {
  const glm::vec4 clip = camera.viewProjection(1.0f) * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {static_cast<int>((ndc.x * 0.5f + 0.5f) * kSize), static_cast<int>((0.5f - ndc.y * 0.5f) * kSize)};
}

bool covered(const Image& image, glm::ivec2 p) {
  return image.get(p.x, p.y, 3) > 0.5f;
}

std::string colourAt(const Image& image, glm::ivec2 p) {
  return fmt::format("({:.3f}, {:.3f}, {:.3f}, {:.3f})", image.get(p.x, p.y, 0), image.get(p.x, p.y, 1),
                     image.get(p.x, p.y, 2), image.get(p.x, p.y, 3));
}

bool red(const Image& image, glm::ivec2 p) {
  return covered(image, p) && image.get(p.x, p.y, 0) > 0.3f && image.get(p.x, p.y, 1) < 0.05f &&
         image.get(p.x, p.y, 2) < 0.05f;
}
bool blue(const Image& image, glm::ivec2 p) {
  return covered(image, p) && image.get(p.x, p.y, 2) > 0.3f && image.get(p.x, p.y, 0) < 0.05f &&
         image.get(p.x, p.y, 1) < 0.05f;
}
bool green(const Image& image, glm::ivec2 p) {
  return covered(image, p) && image.get(p.x, p.y, 1) > 0.5f && image.get(p.x, p.y, 0) < 0.05f;
}

/** An opaque green quad across the view in the plane through `centre` perpendicular to the view (z = c.z). */
class SolidQuad {
public:
  SolidQuad()
      : mProgram(
            {{GL_VERTEX_SHADER,
              "#version 450\n"
              "uniform mat4 uViewProj;\n"
              "uniform vec3 uCentre;\n"
              "void main() {\n"
              "  vec2 xy = vec2((gl_VertexID & 1) != 0 ? 3.0 : -3.0, (gl_VertexID & 2) != 0 ? 3.0 : -3.0);\n"
              "  gl_Position = uViewProj * vec4(uCentre + vec3(xy, 0.0), 1.0);\n"
              "}\n",
              {"solid.vert"}},
             {GL_FRAGMENT_SHADER,
              "#version 450\n"
              "layout(location = 0) out vec4 outColour;\n"
              "void main() { outColour = vec4(0.0, 1.0, 0.0, 1.0); }\n",
              {"solid.frag"}}},
            "solid quad") {}

  void draw(const render::Camera& camera, glm::vec3 centre) const {
    mProgram.use();
    mProgram.setUniform("uViewProj", camera.viewProjection(1.0f));
    mProgram.setUniform("uCentre", centre);
    mVao.bind();
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  }

private:
  gl::Program mProgram;
  gl::VertexArray mVao;
};

/** One foliage frame: optional solid quad before or after, into `target`. */
struct Frame {
  Image colour;
  Image depth;
};

Frame drawFrame(render::RenderTarget& target, FoliageRenderer& foliage, const TreeRenderer& trees,
                const render::Camera& camera, const TreeLod& lod = {}, const SolidQuad* solid = nullptr,
                glm::vec3 solidCentre = glm::vec3(0.0f), bool solidFirst = true) {
  foliage.bake(camera, noFog());
  target.begin(kBackground);
  if (solid != nullptr && solidFirst) {
    solid->draw(camera, solidCentre);
  }
  foliage.draw(camera, kSize, kSize, 0.0, trees, lod, nullptr, noFog());
  if (solid != nullptr && !solidFirst) {
    solid->draw(camera, solidCentre);
  }
  return {target.readColor(), target.readDepth()};
}

TEST_F(FoliageRendererTest, FrontCardWinsAndDepthFollowsTheFragmentRule) {
  auto forest = capForest({glm::vec3(0.0f)});
  TreeRenderer trees(shaders(), forest);
  FoliageRenderer foliage(shaders(), forest, unitSettings());
  ASSERT_EQ(foliage.stats().anchors, 1u);
  foliage.setLeafCloud(twoCards());
  foliage.setLeafTexture(whiteLeaf());
  const glm::vec3 c = centreOf(foliage, *forest, 0);
  const render::Camera camera = lookingAlongMinusZ(c, 6.0f);
  render::RenderTarget target(kSize, kSize);
  const Frame frame = drawFrame(target, foliage, trees, camera);

  // Billboard points (on the front plane z = c.z + 1) of cloud-plane points.
  auto at = [&](float x, float y) { return pixelOf(camera, c + glm::vec3(x, y, 1.0f)); };
  const glm::ivec2 overlap = at(0.0f, 0.0f);
  const glm::ivec2 frontOnly = at(-0.45f, 0.1f);
  const glm::ivec2 backOnly = at(0.45f, -0.1f);
  const glm::ivec2 empty = at(0.0f, 0.7f);
  EXPECT_TRUE(red(frame.colour, overlap)) << colourAt(frame.colour, overlap);
  EXPECT_TRUE(red(frame.colour, frontOnly)) << colourAt(frame.colour, frontOnly);
  EXPECT_TRUE(blue(frame.colour, backOnly)) << colourAt(frame.colour, backOnly);
  EXPECT_FALSE(covered(frame.colour, empty)) << colourAt(frame.colour, empty);
  EXPECT_EQ(frame.depth.get(empty.x, empty.y, 0), 1.0f);

  // Depth of every covered pixel against the CPU rule, for the pixel centre's point on the front plane.
  const glm::mat4 viewProj = camera.viewProjection(1.0f);
  const glm::mat4 inverse = glm::inverse(viewProj);
  const glm::vec3 forward(0.0f, 0.0f, -1.0f);
  const float tFront = decodeFoliageDepth(encodeFoliageDepth(0.275f));
  const float tBack = decodeFoliageDepth(encodeFoliageDepth(0.725f));
  int checked = 0;
  float worst = 0.0f;
  float worstEye = 0.0f;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const glm::ivec2 p(x, y);
      if (!covered(frame.colour, p)) {
        continue;
      }
      const bool isFront = red(frame.colour, p);
      ASSERT_TRUE(isFront || blue(frame.colour, p)) << x << ", " << y << ": " << colourAt(frame.colour, p);
      // The camera ray through the pixel centre (GL rows run bottom-up) meets the front plane at P_q.
      const glm::vec2 ndc((x + 0.5f) / kSize * 2.0f - 1.0f, 1.0f - (y + 0.5f) / kSize * 2.0f);
      const glm::vec4 far = inverse * glm::vec4(ndc, 1.0f, 1.0f);
      const glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w - camera.position);
      const float s = (c.z + 1.0f - camera.position.z) / dir.z;
      const glm::vec3 quad = camera.position + dir * s;
      const float t = isFront ? tFront : tBack;
      const float expected = foliageFragmentDepth(quad, camera.position, forward, 1.0f, t, viewProj);
      const float depth = frame.depth.get(x, y, 0);
      worst = std::max(worst, std::abs(depth - expected));
      // In metres along the view: against the card's true depth, before the 8-bit code.
      const glm::vec4 back = inverse * glm::vec4(ndc, 2.0f * depth - 1.0f, 1.0f);
      const float eye = glm::dot(glm::vec3(back) / back.w - camera.position, forward);
      const float card = camera.position.z - c.z + (isFront ? -0.45f : 0.45f);
      worstEye = std::max(worstEye, std::abs(eye - card));
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
  // One step of the code is 2R/254 = 7.9 mm, 3.3e-4 of window depth at 5 m with these planes; 1e-5 (a third
  // of a millimetre) leaves room for float interpolation of the quad point and the projection, never a step.
  EXPECT_LT(worst, 1e-5f);
  // Against the unquantised card depth: half a step (R/254) plus the same float slack.
  EXPECT_LT(worstEye, 1.0f / 254.0f + 5e-4f);
}

TEST_F(FoliageRendererTest, OpaqueQuadBetweenTheCardsHidesOnlyTheBackCard) {
  auto forest = capForest({glm::vec3(0.0f)});
  TreeRenderer trees(shaders(), forest);
  FoliageRenderer foliage(shaders(), forest, unitSettings());
  foliage.setLeafCloud(twoCards());
  foliage.setLeafTexture(whiteLeaf());
  const glm::vec3 c = centreOf(foliage, *forest, 0);
  const render::Camera camera = lookingAlongMinusZ(c, 6.0f);
  render::RenderTarget target(kSize, kSize);
  const SolidQuad solid;
  auto at = [&](float x, float y) { return pixelOf(camera, c + glm::vec3(x, y, 1.0f)); };
  for (const bool solidFirst : {true, false}) {
    SCOPED_TRACE(solidFirst ? "quad drawn first" : "quad drawn last");
    const Frame frame = drawFrame(target, foliage, trees, camera, {}, &solid, c, solidFirst);
    EXPECT_TRUE(red(frame.colour, at(0.0f, 0.0f))) << colourAt(frame.colour, at(0.0f, 0.0f));
    EXPECT_TRUE(red(frame.colour, at(-0.45f, 0.1f))) << colourAt(frame.colour, at(-0.45f, 0.1f));
    EXPECT_TRUE(green(frame.colour, at(0.45f, -0.1f))) << colourAt(frame.colour, at(0.45f, -0.1f));
    EXPECT_TRUE(green(frame.colour, at(0.0f, 0.7f))) << colourAt(frame.colour, at(0.0f, 0.7f));
    int blueLeft = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        blueLeft += blue(frame.colour, {x, y}) ? 1 : 0;
      }
    }
    EXPECT_EQ(blueLeft, 0) << "the back card shows through the quad";
  }
}

TEST_F(FoliageRendererTest, BillboardBehindIsHiddenWhereTheFrontOneHasLeaves) {
  const glm::vec3 nearBase(0.0f);
  // The far sphere overlaps the near one in depth: its front plane (z = c.z − 0.2) lies between the near
  // cards (c.z ± 0.45), its cards (c.z − 0.75, c.z − 1.65) behind both.
  const glm::vec3 farBase(1.1f, 0.0f, -1.2f);
  auto single = capForest({nearBase});
  TreeRenderer singleTrees(shaders(), single);
  FoliageRenderer singleFoliage(shaders(), single, unitSettings());
  singleFoliage.setLeafCloud(twoCards());
  singleFoliage.setLeafTexture(whiteLeaf());
  const glm::vec3 c = centreOf(singleFoliage, *single, 0);
  const render::Camera camera = lookingAlongMinusZ(c, 6.0f);
  render::RenderTarget target(kSize, kSize);
  const Frame alone = drawFrame(target, singleFoliage, singleTrees, camera);
  const glm::vec4 frontClip = camera.viewProjection(1.0f) * glm::vec4(c + farBase + glm::vec3(0, 0, 1), 1.0f);
  const float farFront = 0.5f * frontClip.z / frontClip.w + 0.5f;
  // Both orders of the instances: the far billboard drawn first (overwritten) and last (depth-rejected).
  for (const bool farFirst : {true, false}) {
    SCOPED_TRACE(farFirst ? "far billboard first" : "far billboard last");
    auto both = capForest(farFirst ? std::vector{farBase, nearBase} : std::vector{nearBase, farBase});
    TreeRenderer trees(shaders(), both);
    FoliageRenderer foliage(shaders(), both, unitSettings());
    ASSERT_EQ(foliage.stats().anchors, 2u);
    foliage.setLeafCloud(twoCards());
    foliage.setLeafTexture(whiteLeaf());
    const Frame frame = drawFrame(target, foliage, trees, camera);
    int kept = 0;
    int behindShows = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const glm::ivec2 p(x, y);
        if (covered(alone.colour, p)) {
          // The near billboard's leaves: untouched by the one behind.
          bool same = true;
          for (int ch = 0; ch < 4; ++ch) {
            same = same && alone.colour.get(x, y, ch) == frame.colour.get(x, y, ch);
          }
          ASSERT_TRUE(same) << x << ", " << y << ": " << colourAt(alone.colour, p) << " became "
                            << colourAt(frame.colour, p);
          ASSERT_EQ(alone.depth.get(x, y, 0), frame.depth.get(x, y, 0)) << x << ", " << y;
          ++kept;
        } else if (covered(frame.colour, p)) {
          // Only the far billboard is here: its leaves lie behind its front plane.
          EXPECT_GT(frame.depth.get(x, y, 0), farFront) << x << ", " << y;
          ++behindShows;
        }
      }
    }
    EXPECT_GT(kept, 300);
    EXPECT_GT(behindShows, 100) << "the far billboard must show beside the near one";
  }
}

TEST_F(FoliageRendererTest, BillboardsFollowTheJointFrames) {
  // The wind moves joints by rewriting the frames buffer; the billboards must move with it.
  auto forest = capForest({glm::vec3(0.0f)});
  TreeRenderer trees(shaders(), forest);
  FoliageRenderer foliage(shaders(), forest, unitSettings());
  foliage.setLeafCloud(twoCards());
  foliage.setLeafTexture(whiteLeaf());
  const glm::vec3 c = centreOf(foliage, *forest, 0);
  const render::Camera camera = lookingAlongMinusZ(c, 6.0f);
  render::RenderTarget target(kSize, kSize);
  auto centroid = [&] {
    const Image image = drawFrame(target, foliage, trees, camera).colour;
    glm::dvec2 sum(0.0);
    int n = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        if (covered(image, {x, y})) {
          sum += glm::dvec2(x, y);
          ++n;
        }
      }
    }
    EXPECT_GT(n, 300);
    return glm::vec2(sum / static_cast<double>(std::max(n, 1)));
  };
  const glm::vec2 before = centroid();
  std::vector<gpu::JointFrame> frames;
  forestFrames(*forest, {}, frames);
  for (gpu::JointFrame& f : frames) {
    f.x.w += 0.4f; // every joint 0.4 m along +x
    f.y.w += 0.2f; // and 0.2 m up
  }
  trees.setFrames(frames);
  const glm::vec2 after = centroid();
  const glm::vec2 expected =
      glm::vec2(pixelOf(camera, c + glm::vec3(0.4f, 0.2f, 1.0f)) - pixelOf(camera, c + glm::vec3(0, 0, 1)));
  EXPECT_NEAR(after.x - before.x, expected.x, 1.0f);
  EXPECT_NEAR(after.y - before.y, expected.y, 1.0f);
  EXPECT_GT(expected.x, 5.0f);
}

TEST_F(FoliageRendererTest, BakeRunsAgainOnlyForANewViewDirection) {
  auto forest = capForest({glm::vec3(0.0f)});
  FoliageSettings settings;
  settings.textureSize = 64;
  FoliageRenderer foliage(shaders(), forest, settings);
  const glm::vec3 c(0.0f, 1.0f, 0.0f);
  const render::Camera a = lookingAlongMinusZ(c, 6.0f);
  render::Camera b = a;
  b.position = c + glm::vec3(5.0f, 2.0f, 3.0f);
  render::Camera moved = a;
  moved.position += glm::vec3(0.0f, 0.0f, 10.0f); // same direction, farther
  moved.target += glm::vec3(0.0f, 0.0f, 10.0f);
  auto texture = [&] { return foliage.cloudTexture().download(4, PixelType::U8); };
  EXPECT_TRUE(foliage.bake(a));
  const Image first = texture();
  EXPECT_FALSE(foliage.bake(a));
  EXPECT_FALSE(foliage.bake(moved)) << "moving without turning keeps the texture";
  EXPECT_TRUE(foliage.bake(b));
  const Image second = texture();
  EXPECT_FALSE(first == second);
  EXPECT_TRUE(foliage.bake(a));
  EXPECT_TRUE(texture() == first) << "the bake is deterministic";
  EXPECT_EQ(foliage.stats().bakes, 3u);
  // The cloud covers a good part of the texture, with depth codes spread across the sphere.
  int coveredTexels = 0;
  int nearHalf = 0;
  const auto values = first.values<std::uint8_t>();
  for (std::size_t i = 3; i < values.size(); i += 4) {
    coveredTexels += values[i] > 0 ? 1 : 0;
    nearHalf += values[i] > 0 && values[i] <= 128 ? 1 : 0;
  }
  EXPECT_GT(coveredTexels, 64 * 64 / 4);
  EXPECT_GT(nearHalf, coveredTexels / 2) << "the nearest leaf must win (more texels in the front half)";
  // A sun change re-bakes too.
  render::Environment evening;
  evening.sunDirection = glm::vec3(-0.8f, 0.2f, 0.1f);
  EXPECT_TRUE(foliage.bake(a, evening));
}

TEST_F(FoliageRendererTest, ConifersShowTheNeedleCloud) {
  // A species with needles bakes the needle cloud as well and its billboards show it: the share of a
  // billboard's pixels the leaves cover follows the texture its species reads, leaves or needles.
  auto forest = capForest({glm::vec3(0.0f)});
  FoliageSettings settings = unitSettings();
  auto coverage = [](const Image& image) {
    int n = 0;
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        n += image.get(x, y, 3) > 0.0f ? 1 : 0;
      }
    }
    return static_cast<double>(n) / (image.width() * image.height());
  };
  const render::Camera camera = lookingAlongMinusZ(glm::vec3(0.0f, 1.0f, 0.0f), 6.0f);
  auto drawn = [&](FoliageRenderer& foliage, TreeRenderer& trees) {
    render::RenderTarget target(kSize, kSize);
    target.begin(glm::vec4(0.0f));
    foliage.bake(camera, noFog());
    foliage.draw(camera, kSize, kSize, 0.0, trees, TreeLod{}, nullptr, noFog());
    const Image frame = target.readColor();
    int n = 0;
    for (int y = 0; y < frame.height(); ++y) {
      for (int x = 0; x < frame.width(); ++x) {
        n += frame.get(x, y, 0) + frame.get(x, y, 1) + frame.get(x, y, 2) > 0.0f ? 1 : 0;
      }
    }
    return n;
  };
  TreeRenderer leafTrees(shaders(), forest);
  FoliageRenderer leaves(shaders(), forest, settings);
  const int leafPixels = drawn(leaves, leafTrees);
  const double leafCover = coverage(leaves.cloudTexture().download(4, PixelType::U8));
  EXPECT_EQ(leaves.needleTexture().width(), 1) << "no conifer, no needle bake";

  forest->species[0].foliage = FoliageKind::Needles;
  TreeRenderer needleTrees(shaders(), forest);
  FoliageRenderer needles(shaders(), forest, settings);
  const int needlePixels = drawn(needles, needleTrees);
  const double needleCover = coverage(needles.needleTexture().download(4, PixelType::U8));
  EXPECT_GT(needleCover, 0.05);
  EXPECT_GT(leafPixels, 500);
  EXPECT_GT(needlePixels, 200);
  // Drawn coverage follows the baked coverage of the species' cloud (within 20 %).
  const double drawnRatio = static_cast<double>(needlePixels) / leafPixels;
  EXPECT_NEAR(drawnRatio / (needleCover / leafCover), 1.0, 0.2)
      << needlePixels << " needle pixels, " << leafPixels << " leaf pixels; texture cover " << needleCover
      << " against " << leafCover;
  EXPECT_EQ(needles.stats().leafTriangles,
            static_cast<std::size_t>(2 * settings.needles.shoots * settings.needles.needles));
}

TEST_F(FoliageRendererTest, RealLeafTextureIsAlphaTested) {
  // ez-tree's oak leaves (scripts/fetch-sample-data.sh): a palette PNG with transparency.
  const auto path = test::externalData("ez-tree/leaves/oak_color.png");
  SYLVA_REQUIRE_EXTERNAL_DATA(path);
  const Image leaf = loadLeafImage(path);
  ASSERT_EQ(leaf.channels(), 4);
  auto forest = capForest({glm::vec3(0.0f)});
  FoliageSettings settings;
  settings.textureSize = 64;
  FoliageRenderer foliage(shaders(), forest, settings);
  const render::Camera camera = lookingAlongMinusZ(glm::vec3(0.0f, 1.0f, 0.0f), 6.0f);
  auto coverage = [&] {
    foliage.bake(camera);
    const Image cloud = foliage.cloudTexture().download(4, PixelType::U8);
    int n = 0;
    for (int y = 0; y < cloud.height(); ++y) {
      for (int x = 0; x < cloud.width(); ++x) {
        n += cloud.get(x, y, 3) > 0.0f ? 1 : 0;
      }
    }
    return n;
  };
  foliage.setLeafTexture(whiteLeaf());
  const int cards = coverage();
  foliage.setLeafTexture(leaf);
  const int leaves = coverage();
  // The leaf's transparent surround is cut away, yet the cloud still shows leaves.
  EXPECT_LT(leaves, cards * 9 / 10);
  EXPECT_GT(leaves, cards / 5);
}

TEST_F(FoliageRendererTest, FarFieldDissolvesFoliageLikeThePieces) {
  auto forest = capForest({glm::vec3(0.0f)});
  TreeRenderer trees(shaders(), forest);
  FoliageSettings settings = unitSettings();
  FoliageRenderer foliage(shaders(), forest, settings);
  const glm::vec3 c = centreOf(foliage, *forest, 0);
  render::Camera camera = lookingAlongMinusZ(c, 30.0f);
  camera.fovY = glm::radians(8.0f);
  camera.farPlane = 60.0f;
  render::RenderTarget target(kSize, kSize);
  auto coverage = [&](glm::vec2 range) {
    TreeLod lod;
    lod.farRange = range;
    const Image image = drawFrame(target, foliage, trees, camera, lod).colour;
    int n = 0;
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        n += covered(image, {x, y}) ? 1 : 0;
      }
    }
    return n;
  };
  const int full = coverage({0.0f, 0.0f});
  EXPECT_GT(full, 500);
  EXPECT_EQ(coverage({40.0f, 60.0f}), full) << "nearer than farRange.x: no dissolve";
  EXPECT_EQ(coverage({10.0f, 20.0f}), 0) << "beyond farRange.y: no foliage";
  const int half = coverage({20.0f, 40.0f});
  EXPECT_GT(half, full * 3 / 10);
  EXPECT_LT(half, full * 7 / 10);
}

TEST_F(FoliageRendererTest, GridForestCost) {
  // The cost of both passes for a 10 × 10 grid of trees at 640 × 360 (printed, not asserted: timing never
  // gates).
  auto forest = std::make_shared<Forest>(gridForest({"almond", "apple", "quaking-aspen"}, 10, 7.0f, 3));
  TreeRenderer trees(shaders(), forest);
  FoliageRenderer foliage(shaders(), forest);
  if (const auto oak = test::externalData("ez-tree/leaves/oak_color.png"); std::filesystem::exists(oak)) {
    foliage.setLeafTexture(loadLeafImage(oak));
  }
  render::Camera camera;
  camera.position = glm::vec3(-45.0f, 14.0f, 45.0f);
  camera.target = glm::vec3(0.0f, 4.0f, 0.0f);
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 0.5f;
  camera.farPlane = 300.0f;
  const int width = 640;
  const int height = 360;
  render::RenderTarget target(width, height);
  TreeLod lod;
  lod.maxLevel = 4.0f;
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  target.begin(glm::vec4(0.6f, 0.7f, 0.85f, 1.0f));
  trees.cull(camera, target.aspect(), lod);
  trees.draw(camera, width, height, 0.0, lod);
  const Image bark = target.readColor();
  glFinish();
  auto t0 = Clock::now();
  foliage.bake(camera);
  glFinish();
  auto t1 = Clock::now();
  double drawMs = 1e9;
  for (int run = 0; run < 3; ++run) {
    const auto s = Clock::now();
    foliage.draw(camera, width, height, 0.0, trees, lod);
    glFinish();
    drawMs = std::min(drawMs, ms(Clock::now() - s));
  }
  const Image image = target.readColor();
  int changed = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      changed += bark.get(x, y, 0) != image.get(x, y, 0) || bark.get(x, y, 1) != image.get(x, y, 1) ? 1 : 0;
    }
  }
  std::cout << "[ foliage  ] " << forest->trees.size() << " trees, " << foliage.stats().anchors
            << " billboards, cloud " << foliage.stats().leafTriangles << " triangles at "
            << foliage.stats().textureSize << "^2: bake " << ms(t1 - t0) << " ms, draw " << drawMs
            << " ms at " << width << "x" << height << " (" << (onLlvmpipe() ? "llvmpipe" : "GPU") << "), "
            << foliage.gpuBytes() / 1024 << " KiB\n";
  if (const char* dump = std::getenv("SYLVA_FOLIAGE_DUMP"); dump != nullptr) {
    // Debugging aid: the frame, the bark alone and the cloud texture (colour opaque; depth code as grey).
    const std::filesystem::path dir(dump);
    saveImage(dir / "foliage-frame.png", image);
    saveImage(dir / "foliage-bark.png", bark);
    Image cloud = foliage.cloudTexture().download(4, PixelType::U8);
    cloud.flipVertically();
    Image depth(cloud.width(), cloud.height(), 1, PixelType::U8);
    for (int y = 0; y < cloud.height(); ++y) {
      for (int x = 0; x < cloud.width(); ++x) {
        depth.set(x, y, 0, cloud.get(x, y, 3));
        cloud.set(x, y, 3, cloud.get(x, y, 3) > 0.0f ? 1.0f : 0.0f);
      }
    }
    saveImage(dir / "foliage-cloud.png", cloud);
    saveImage(dir / "foliage-cloud-depth.png", depth);
    render::Camera close = camera;
    close.position = glm::vec3(-12.0f, 3.0f, 4.0f);
    close.target = glm::vec3(-3.5f, 3.5f, -3.5f);
    target.begin(glm::vec4(0.6f, 0.7f, 0.85f, 1.0f));
    trees.cull(close, target.aspect(), lod);
    trees.draw(close, width, height, 0.0, lod);
    foliage.bake(close);
    foliage.draw(close, width, height, 0.0, trees, lod);
    saveImage(dir / "foliage-close.png", target.readColor());
  }
  EXPECT_GT(foliage.stats().anchors, 100u);
  EXPECT_GT(changed, width * height / 50) << "the foliage must cover part of the forest";
}

} // namespace
} // namespace sylva::trees
