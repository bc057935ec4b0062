// Foliage as 2.5D impostors, CPU side: the depth code round-trips within its precision (2R/254 per step, half
// a step after rounding), the fragment rule puts a texel's leaf exactly 2R·t behind the front plane,
// procedural clouds are deterministic and fill the unit sphere, anchors are one per foliage-bearing piece
// instance, and bad leaf models fail with one line naming the file.
#include "TempDir.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/trees/Foliage.hpp>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <cstring>
#include <string>

namespace sylva::trees {
namespace {

void expectLeafCloudError(const std::filesystem::path& file, const std::string& expected) {
  try {
    (void)loadLeafCloud(file);
    FAIL() << file << " loaded";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
  }
}

TEST(FoliageDepth, CodeRoundTripsWithinHalfAStep) {
  const float radius = 1.7f;
  EXPECT_EQ(encodeFoliageDepth(0.0f), 1);
  EXPECT_EQ(encodeFoliageDepth(1.0f), 255);
  EXPECT_EQ(encodeFoliageDepth(-0.3f), 1);
  EXPECT_EQ(encodeFoliageDepth(2.0f), 255);
  EXPECT_FLOAT_EQ(decodeFoliageDepth(0), -1.0f); // empty
  std::uint8_t previous = 0;
  float worst = 0.0f;
  for (int i = 0; i <= 10000; ++i) {
    // z across the sphere (centre 5 m away along the view direction), t from it, the code and back.
    const float z = 5.0f - radius + 2.0f * radius * static_cast<float>(i) / 10000.0f;
    const float t = foliageDepthT(z, 5.0f, radius);
    const std::uint8_t code = encodeFoliageDepth(t);
    ASSERT_GE(code, 1);
    ASSERT_GE(code, previous) << "the code must not decrease with depth";
    previous = code;
    const float back = 5.0f - radius + 2.0f * radius * decodeFoliageDepth(code);
    worst = std::max(worst, std::abs(back - z));
  }
  // Steps of 2R/254; rounding to the nearest step errs by half of one at most.
  EXPECT_LE(worst, radius / kFoliageDepthSteps + 1e-5f);
  EXPECT_GE(worst, 0.9f * radius / kFoliageDepthSteps) << "the code is finer than claimed";
  for (int a = 1; a <= 255; ++a) {
    EXPECT_EQ(encodeFoliageDepth(decodeFoliageDepth(static_cast<std::uint8_t>(a))), a);
  }
}

TEST(FoliageDepth, FragmentRulePutsTheLeafTwoRTBehindTheFrontPlane) {
  const glm::vec3 camera(3.0f, 2.0f, 9.0f);
  const glm::vec3 target(0.5f, 1.0f, -2.0f);
  const FoliageBasis basis = foliageBasis(target - camera, glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_NEAR(glm::dot(basis.right, basis.up), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(basis.right, basis.forward), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(glm::cross(basis.right, basis.up) + basis.forward), 0.0f, 1e-6f)
      << "right × up must point at the viewer";
  const glm::mat4 viewProj = glm::perspective(glm::radians(50.0f), 1.5f, 0.5f, 80.0f) *
                             glm::lookAt(camera, target, glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::vec3 centre(0.2f, 1.3f, -1.0f);
  const float radius = 1.2f;
  float previous = -1.0f;
  for (const glm::vec2 xy : {glm::vec2(0.0f), glm::vec2(-0.8f, 0.6f), glm::vec2(0.9f, -0.9f)}) {
    const glm::vec3 quad = foliageQuadPoint(basis, centre, radius, xy);
    // On the sphere's front plane.
    EXPECT_NEAR(glm::dot(quad - centre, basis.forward), -radius, 1e-5f);
    previous = -1.0f;
    for (float t : {0.0f, 0.25f, 0.5f, 1.0f}) {
      const glm::vec3 p = foliageFragmentPoint(quad, camera, basis.forward, radius, t);
      // On the camera ray through the quad point, 2R·t farther along the view direction.
      EXPECT_NEAR(glm::length(glm::cross(glm::normalize(p - camera), glm::normalize(quad - camera))), 0.0f,
                  1e-5f);
      EXPECT_NEAR(glm::dot(p - quad, basis.forward), 2.0f * radius * t, 1e-4f);
      // Window depth depends only on the distance along the view direction: the same as the point straight
      // behind the quad point (what the orthographic bake saw).
      const float depth = foliageFragmentDepth(quad, camera, basis.forward, radius, t, viewProj);
      const glm::vec4 clip = viewProj * glm::vec4(quad + basis.forward * (2.0f * radius * t), 1.0f);
      EXPECT_NEAR(depth, 0.5f * clip.z / clip.w + 0.5f, 2e-6f);
      EXPECT_GT(depth, previous) << "deeper leaves must be farther";
      previous = depth;
    }
  }
}

TEST(FoliageDepth, BakeMatrixMapsTheSphereOntoTheTexture) {
  const FoliageBasis basis = foliageBasis(glm::vec3(1.0f, -0.5f, 0.3f), glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::mat4 bake = foliageBakeMatrix(basis);
  for (const glm::vec3 p : {glm::vec3(0.3f, -0.2f, 0.5f), basis.right, -basis.up, basis.forward * 0.5f}) {
    const glm::vec4 clip = bake * glm::vec4(p, 1.0f);
    EXPECT_FLOAT_EQ(clip.w, 1.0f);
    EXPECT_NEAR(clip.x, glm::dot(p, basis.right), 1e-6f);
    EXPECT_NEAR(clip.y, glm::dot(p, basis.up), 1e-6f);
    // Window depth (clip z + 1) / 2 is t across the unit sphere.
    EXPECT_NEAR(0.5f * (clip.z + 1.0f), foliageDepthT(glm::dot(p, basis.forward), 0.0f, 1.0f), 1e-6f);
  }
  // Straight up or down still gives a basis.
  const FoliageBasis down = foliageBasis(glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_NEAR(glm::length(down.right), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(down.right, down.forward), 0.0f, 1e-6f);
}

TEST(LeafCloud, ProceduralCloudIsDeterministicAndFillsTheUnitSphere) {
  LeafCloudSettings settings;
  settings.leaves = 150;
  settings.seed = 11;
  const LeafCloud a = makeLeafCloud(settings);
  const LeafCloud b = makeLeafCloud(settings);
  ASSERT_EQ(a.triangles(), 2u * 150u);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  EXPECT_EQ(std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(LeafVertex)), 0);
  settings.seed = 12;
  const LeafCloud c = makeLeafCloud(settings);
  EXPECT_NE(std::memcmp(a.vertices.data(), c.vertices.data(), a.vertices.size() * sizeof(LeafVertex)), 0);
  EXPECT_NO_THROW(validate(a, "cloud"));
  float farthest = 0.0f;
  glm::vec3 lo(1e9f);
  glm::vec3 hi(-1e9f);
  for (const LeafVertex& v : a.vertices) {
    farthest = std::max(farthest, glm::length(v.position));
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
    EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
  }
  EXPECT_LE(farthest, 1.0f + 1e-5f);
  EXPECT_GE(farthest, 0.999f);
  // Centred: the bounding box's middle is the origin.
  EXPECT_NEAR(glm::length(0.5f * (lo + hi)), 0.0f, 1e-4f);
  LeafCloudSettings bad;
  bad.leaves = 0;
  EXPECT_THROW((void)makeLeafCloud(bad), Error);
}

TEST(LeafCloud, NeedleCloudIsShootsOfNarrowNeedles) {
  NeedleCloudSettings settings;
  settings.shoots = 10;
  settings.needles = 30;
  const LeafCloud a = makeNeedleCloud(settings);
  const LeafCloud b = makeNeedleCloud(settings);
  ASSERT_EQ(a.triangles(), 2u * 10u * 30u);
  EXPECT_EQ(std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(LeafVertex)), 0);
  EXPECT_NO_THROW(validate(a, "needles"));
  float farthest = 0.0f;
  for (const LeafVertex& v : a.vertices) {
    farthest = std::max(farthest, glm::length(v.position));
  }
  EXPECT_LE(farthest, 1.0f + 1e-5f);
  EXPECT_GE(farthest, 0.999f);
  // Every card (two triangles, six vertices) is a needle: several times longer than wide.
  int needles = 0;
  for (std::size_t i = 0; i + 5 < a.vertices.size(); i += 6) {
    float longest = 0.0f;
    float shortest = 1e9f;
    for (std::size_t k = 0; k < 3; ++k) {
      const float edge = glm::length(a.vertices[i + k].position - a.vertices[i + (k + 1) % 3].position);
      longest = std::max(longest, edge);
      shortest = std::min(shortest, edge);
    }
    needles += shortest > 0.0f && longest / shortest > 4.0f ? 1 : 0;
  }
  EXPECT_EQ(needles, 300);
  settings.needleWidth = 0.0f;
  try {
    (void)makeNeedleCloud(settings);
    ADD_FAILURE() << "a zero needle width was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("needleWidth"), std::string::npos) << e.what();
  }
}

TEST(LeafCloud, CardsKeepTheirOrientationAndNormalisationFitsTheSphere) {
  LeafCard card;
  card.centre = glm::vec3(4.0f, 0.0f, 0.0f);
  card.normal = glm::vec3(0.0f, 0.0f, 2.0f); // not unit
  card.up = glm::vec3(0.3f, 1.0f, 0.5f);     // not perpendicular
  card.size = glm::vec2(2.0f, 1.0f);
  LeafCloud cloud = leafCloudFromCards(std::span<const LeafCard>(&card, 1));
  ASSERT_EQ(cloud.triangles(), 2u);
  for (const LeafVertex& v : cloud.vertices) {
    EXPECT_NEAR(v.normal.z, 1.0f, 1e-6f);
    EXPECT_NEAR(v.position.z, 0.0f, 1e-6f);
  }
  // uv (1, 0) − uv (0, 0) runs along +x (right = up × normal), the width.
  EXPECT_NEAR(glm::length(cloud.vertices[1].position - cloud.vertices[0].position), 2.0f, 1e-5f);
  EXPECT_GT(cloud.vertices[1].position.x, cloud.vertices[0].position.x);
  EXPECT_THROW(validate(cloud, "cards"), Error); // outside the unit sphere
  normaliseLeafCloud(cloud, "cards");
  EXPECT_NO_THROW(validate(cloud, "cards"));
  float farthest = 0.0f;
  for (const LeafVertex& v : cloud.vertices) {
    farthest = std::max(farthest, glm::length(v.position));
  }
  EXPECT_NEAR(farthest, 1.0f, 1e-5f);
}

TEST(LeafCloud, LeafImageIsAnOpaqueLeafOnATransparentGround) {
  const Image image = makeLeafImage(64);
  EXPECT_TRUE(image == makeLeafImage(64));
  int opaque = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      opaque += image.get(x, y, 3) > 0.5f ? 1 : 0;
    }
  }
  EXPECT_GT(opaque, 64 * 64 / 5);
  EXPECT_LT(opaque, 64 * 64 * 2 / 3);
  EXPECT_EQ(image.get(0, 0, 3), 0.0f);   // corners are empty
  EXPECT_EQ(image.get(32, 32, 3), 1.0f); // the middle is leaf
  const glm::vec3 mean = leafImageMean(image);
  EXPECT_GT(mean.g, mean.r);
  EXPECT_GT(mean.r, mean.b);
  EXPECT_THROW((void)leafImageMean(Image(4, 4, 3, PixelType::U8)), Error);
}

TEST(FoliageAnchors, OnePerFoliageBearingPieceInstance) {
  const Forest forest = gridForest({"almond", "apple"}, 3, 6.0f, 4);
  FoliageSettings settings;
  const std::vector<FoliageAnchor> anchors = foliageAnchors(forest, settings);
  std::size_t expected = 0;
  std::vector<gpu::JointFrame> frames;
  forestFrames(forest, {}, frames);
  std::size_t k = 0;
  for (std::size_t t = 0; t < forest.trees.size(); ++t) {
    for (const TreeNode& node : forest.trees[t].topology.nodes) {
      if (!forest.pieces[static_cast<std::size_t>(node.piece)].bearsFoliage) {
        continue;
      }
      ++expected;
      ASSERT_LT(k, anchors.size());
      const FoliageAnchor& a = anchors[k++];
      EXPECT_EQ(a.joint, forest.jointOffset[t] + node.rootJoint);
      EXPECT_EQ(a.tree, t);
      EXPECT_EQ(a.species, static_cast<std::uint32_t>(forest.trees[t].species));
      EXPECT_GE(a.radius, settings.minRadius * (1.0f - settings.sizeVariation) - 1e-5f);
      EXPECT_LE(a.radius, settings.maxRadius * (1.0f + settings.sizeVariation) + 1e-5f);
      EXPECT_LE(std::abs(a.rotation), settings.rotationVariation);
      // The sphere sits on the twig tip: its centre within one radius of the joint.
      const glm::vec3 joint(frames[a.joint].x.w, frames[a.joint].y.w, frames[a.joint].z.w);
      EXPECT_LT(glm::length(anchorCentre(a, frames) - joint), a.radius);
    }
  }
  EXPECT_GT(expected, 9u) << "every tree should carry foliage";
  EXPECT_EQ(anchors.size(), expected);
  const std::vector<FoliageAnchor> again = foliageAnchors(forest, settings);
  ASSERT_EQ(again.size(), anchors.size());
  EXPECT_EQ(std::memcmp(again.data(), anchors.data(), anchors.size() * sizeof(FoliageAnchor)), 0);
  const gpu::FoliageAnchorGpu packed = packAnchor(anchors[0]);
  EXPECT_EQ(packed.info.x, anchors[0].joint);
  EXPECT_FLOAT_EQ(packed.place.w, anchors[0].radius);
  FoliageSettings bad;
  bad.maxRadius = 0.1f;
  EXPECT_THROW((void)foliageAnchors(forest, bad), Error);
}

TEST(FoliageAnchors, LeafDensityThinsTheCrownAndLeafFallOnlyEverRemoves) {
  // A species' leafDensity keeps that share of its clusters; a lower density keeps a subset of a higher
  // one's (leaves fall, none grow back), and a bare crown (0) keeps none.
  Forest forest = gridForest({"california-black-oak"}, 2, 8.0f, 4);
  const FoliageSettings settings;
  auto joints = [&](float density) {
    forest.species[0].leafDensity = density;
    std::set<std::uint32_t> out;
    for (const FoliageAnchor& a : foliageAnchors(forest, settings)) {
      out.insert(a.joint);
    }
    return out;
  };
  const std::set<std::uint32_t> all = joints(1.0f);
  const std::set<std::uint32_t> most = joints(0.7f);
  const std::set<std::uint32_t> few = joints(0.3f);
  ASSERT_GT(all.size(), 200u);
  EXPECT_NEAR(static_cast<double>(most.size()) / all.size(), 0.7, 0.08);
  EXPECT_NEAR(static_cast<double>(few.size()) / all.size(), 0.3, 0.08);
  EXPECT_TRUE(std::includes(most.begin(), most.end(), few.begin(), few.end()));
  EXPECT_TRUE(std::includes(all.begin(), all.end(), most.begin(), most.end()));
  EXPECT_TRUE(joints(0.0f).empty());
}

TEST(LeafCloudLoader, ReadsTrianglesWithUvsIntoTheUnitSphere) {
  const test::TempDir dir;
  writeTextFile(dir / "two.obj", "v 0 0 0\nv 4 0 0\nv 4 2 0\nv 0 2 0\n"
                                 "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                 "f 1/1 2/2 3/3 4/4\n");
  const LeafCloud cloud = loadLeafCloud(dir / "two.obj");
  ASSERT_EQ(cloud.triangles(), 2u); // the quad, triangulated
  float farthest = 0.0f;
  for (const LeafVertex& v : cloud.vertices) {
    farthest = std::max(farthest, glm::length(v.position));
    EXPECT_NEAR(std::abs(v.normal.z), 1.0f, 1e-6f); // from the triangle: the file has none
    // uv follows position: the 4 × 2 quad is centred and divided by its half-diagonal √5.
    EXPECT_NEAR(v.uv.x, 0.5f + v.position.x * std::sqrt(5.0f) / 4.0f, 1e-5f);
    EXPECT_NEAR(v.uv.y, 0.5f + v.position.y * std::sqrt(5.0f) / 2.0f, 1e-5f);
  }
  EXPECT_NEAR(farthest, 1.0f, 1e-5f);
}

TEST(LeafCloudLoader, BadFilesFailWithOneLineNamingTheFile) {
  const test::TempDir dir;
  expectLeafCloudError(dir / "missing.obj", "missing.obj: no such file");
  writeTextFile(dir / "garbage.dae", "<COLLADA><oops");
  expectLeafCloudError(dir / "garbage.dae", "garbage.dae: cannot read the file");
  writeTextFile(dir / "nouv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectLeafCloudError(dir / "nouv.obj", "nouv.obj: mesh 0 has no texture coordinates");
  writeTextFile(dir / "nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  expectLeafCloudError(dir / "nan.obj", "nan.obj: vertex 0 of mesh 0 is not finite");
  writeTextFile(dir / "point.obj", "v 1 1 1\nv 1 1 1\nv 1 1 1\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  expectLeafCloudError(dir / "point.obj", "point.obj: all vertices at one point");
  writeTextFile(dir / "lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nl 2 3\n");
  expectLeafCloudError(dir / "lines.obj", "lines.obj");
  writeTextFile(dir / "empty.obj", "# nothing\n");
  expectLeafCloudError(dir / "empty.obj", "empty.obj");
  writeTextFile(dir / "many.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n"
                                  "f 1/1 2/2 3/3\nf 2/2 4/4 3/3\n");
  try {
    (void)loadLeafCloud(dir / "many.obj", 1);
    FAIL() << "over the triangle limit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("many.obj: more than 1 triangles"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace sylva::trees
