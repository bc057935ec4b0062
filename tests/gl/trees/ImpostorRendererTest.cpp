// Far-field impostors against the pieces they stand in for (docs/trees.md "Far field"): seen from a baked
// direction an impostor has the tree's silhouette and colour; in the fade band the two passes draw disjoint
// pixel sets whose union is the tree; moving through the band changes the image gradually where a hard
// switch pops; 100,000 far trees draw in one instanced draw; the baked depth hides impostors behind nearer
// surfaces.
#include <sylva/gl/Query.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/gpu/ImpostorRenderer.hpp>
#include <sylva/trees/gpu/TreeRenderer.hpp>
#include <sylva/wind/Wind.hpp>

#include "GlTest.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace sylva::trees {
namespace {

using ImpostorRendererTest = test::GlTest;

constexpr int kImpostorSize = 160;
const glm::vec4 kClear(0.0f, 0.0f, 0.0f, 0.0f);

/**
 * The almond as first modelled (segments as long as the pieces, the Branch piece's own side radii, twig-sized
 * leaf clouds): solid wood that fills these tests' small views. They test the impostor machinery, which must
 * not hang on how the presets are tuned (docs/trees.md "Species targets").
 */
Species stoutAlmond() {
  Species s = speciesPreset("almond");
  s.name = "stout-almond";
  s.maxOrder = 4;
  s.minRadius = 0.04f;
  s.leafCluster = 0.0f;
  s.orders = {OrderParams{2, 3, 0.85f, 0.05f, 0.0f, 0.1f, 0.12f, 0.0f},
              OrderParams{1, 2, 0.8f, 0.0f, 0.1f, 0.15f, 0.15f, 0.02f},
              OrderParams{1, 2, 0.7f, 0.0f, 0.2f, 0.2f, 0.18f, 0.04f}};
  return s;
}

/** One stout almond tree at the origin, its pieces and its baked impostor. */
struct Scene {
  std::shared_ptr<Forest> forest;
  std::unique_ptr<TreeRenderer> pieces;
  std::unique_ptr<ImpostorRenderer> impostors;
  std::vector<FarTree> far;
  glm::vec3 centre{0.0f}; // bounding sphere centre, world
  float radius = 0.0f;
  glm::vec3 crown{0.0f}; // where the dissolve measures distance to

  explicit Scene(const shader::Library& library, ImpostorLayout layout = {6, 64}) {
    forest = std::make_shared<Forest>(gridForestOf({stoutAlmond()}, 1, 6.0f, 4));
    pieces = std::make_unique<TreeRenderer>(library, forest);
    ImpostorSettings settings;
    settings.layout = layout;
    impostors = std::make_unique<ImpostorRenderer>(library, settings);
    impostors->bake(*forest);
    far = farTrees(*forest);
    impostors->setTrees(far);
    const glm::vec4 s = impostors->speciesSphere(0);
    centre = far[0].position + yawRotate(glm::vec3(s) * far[0].height, far[0].yaw);
    radius = s.w * far[0].height;
    crown = far[0].position + glm::vec3(0.0f, 0.5f * far[0].height, 0.0f);
  }

  /** The world direction of baked view `cell` (towards the viewer). */
  glm::vec3 viewDirection(glm::ivec2 cell) const {
    return yawRotate(impostorViewDirection(cell, impostors->settings().layout.views), far[0].yaw);
  }

  /** A camera `distance` radii from the sphere centre along `direction`, the sphere filling `fill` of the
   * view's height. */
  render::Camera camera(glm::vec3 direction, float distance, float fill = 0.8f) const {
    render::Camera c;
    c.position = centre + direction * distance * radius;
    c.target = centre;
    c.fovY = 2.0f * std::atan(1.0f / (distance * fill));
    c.nearPlane = 0.5f * distance * radius;
    c.farPlane = 3.0f * distance * radius;
    return c;
  }

  Image drawPieces(render::RenderTarget& target, const render::Camera& c, glm::vec2 farRange) {
    TreeLod lod;
    lod.farRange = farRange;
    target.begin(kClear);
    pieces->cull(c, target.aspect(), lod);
    pieces->draw(c, target.width(), target.height(), 0.0, lod);
    return target.readColor();
  }
  Image drawImpostor(render::RenderTarget& target, const render::Camera& c, glm::vec2 farRange) {
    target.begin(kClear);
    impostors->draw(c, target.width(), target.height(), 0.0, farRange);
    return target.readColor();
  }
  Image drawBoth(render::RenderTarget& target, const render::Camera& c, glm::vec2 farRange) {
    TreeLod lod;
    lod.farRange = farRange;
    target.begin(kClear);
    pieces->cull(c, target.aspect(), lod);
    pieces->draw(c, target.width(), target.height(), 0.0, lod);
    impostors->draw(c, target.width(), target.height(), 0.0, farRange);
    return target.readColor();
  }
};

bool covered(const Image& image, int x, int y) {
  return image.get(x, y, 3) > 0.0f;
}

struct Coverage {
  int count = 0;
  glm::vec3 mean{0.0f};
};

Coverage coverageOf(const Image& image) {
  Coverage c;
  glm::dvec3 sum(0.0);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      if (covered(image, x, y)) {
        ++c.count;
        sum += glm::dvec3(image.get(x, y, 0), image.get(x, y, 1), image.get(x, y, 2));
      }
    }
  }
  c.mean = c.count > 0 ? glm::vec3(sum / static_cast<double>(c.count)) : glm::vec3(0.0f);
  return c;
}

double iou(const Image& a, const Image& b) {
  int both = 0;
  int either = 0;
  for (int y = 0; y < a.height(); ++y) {
    for (int x = 0; x < a.width(); ++x) {
      both += covered(a, x, y) && covered(b, x, y) ? 1 : 0;
      either += covered(a, x, y) || covered(b, x, y) ? 1 : 0;
    }
  }
  return either > 0 ? static_cast<double>(both) / either : 0.0;
}

/** Saves pictures for a look when SYLVA_TEST_IMAGES names a folder. */
void keep(const Image& image, const std::string& name) {
  if (const char* dir = std::getenv("SYLVA_TEST_IMAGES")) {
    saveImage(std::string(dir) + "/" + name + ".png", image);
  }
}

TEST_F(ImpostorRendererTest, BakedViewReproducesTheMeshFarAway) {
  Scene scene(shaders());
  keep(scene.impostors->readAtlas(0), "impostor-atlas");
  keep(scene.impostors->readAtlasNormal(0), "impostor-atlas-normal");
  render::RenderTarget target(kImpostorSize, kImpostorSize);
  // The impostor draws alone from 1 m on; the pieces always (no far field).
  const glm::vec2 impostorOnly(0.5f, 1.0f);
  int views = 0;
  for (const glm::ivec2 cell : {glm::ivec2(2, 3), glm::ivec2(4, 1), glm::ivec2(1, 1), glm::ivec2(3, 3)}) {
    const render::Camera camera = scene.camera(scene.viewDirection(cell), 25.0f);
    const Image mesh = scene.drawPieces(target, camera, glm::vec2(0.0f));
    const Image impostor = scene.drawImpostor(target, camera, impostorOnly);
    if (std::getenv("SYLVA_TEST_IMAGES") != nullptr) {
      ImpostorSettings flat = scene.impostors->settings();
      flat.depthParallax = false;
      ImpostorRenderer plain(shaders(), flat);
      plain.bake(*scene.forest);
      plain.setTrees(scene.far);
      target.begin(kClear);
      plain.draw(camera, kImpostorSize, kImpostorSize, 0.0, impostorOnly);
      keep(target.readColor(), "impostor-flat-" + std::to_string(views));
    }
    keep(mesh, "impostor-mesh-" + std::to_string(views));
    keep(impostor, "impostor-view-" + std::to_string(views));
    const Coverage a = coverageOf(mesh);
    const Coverage b = coverageOf(impostor);
    ASSERT_GT(a.count, 300) << "the tree must fill a good part of the view";
    const double overlap = iou(mesh, impostor);
    // Thin branches are one or two pixels wide here: each pixel of misplacement along their edges costs a
    // lot of IoU; 0.6 leaves room for that while a wrong view (below) falls far short of it.
    EXPECT_GE(overlap, 0.6) << "view " << cell.x << "," << cell.y;
    EXPECT_LT(glm::length(a.mean - b.mean), 0.06f) << "view " << cell.x << "," << cell.y;
    EXPECT_NEAR(static_cast<double>(b.count) / a.count, 1.0, 0.25);
    std::printf("view (%d, %d): IoU %.3f, pixels %d / %d, mean colour (%.3f %.3f %.3f) / (%.3f %.3f %.3f)\n",
                cell.x, cell.y, overlap, a.count, b.count, a.mean.r, a.mean.g, a.mean.b, b.mean.r, b.mean.g,
                b.mean.b);
    ++views;
  }
  // Control: the impostor turned by 90° no longer matches the mesh.
  std::vector<FarTree> turned = scene.far;
  turned[0].yaw += 1.5707963f;
  scene.impostors->setTrees(turned);
  const render::Camera camera = scene.camera(scene.viewDirection({2, 3}), 25.0f);
  const Image mesh = scene.drawPieces(target, camera, glm::vec2(0.0f));
  const Image wrong = scene.drawImpostor(target, camera, impostorOnly);
  std::printf("turned impostor: IoU %.3f\n", iou(mesh, wrong));
  EXPECT_LT(iou(mesh, wrong), 0.6);
}

TEST_F(ImpostorRendererTest, FadeBandPassesDrawDisjointPixels) {
  Scene scene(shaders());
  render::RenderTarget target(kImpostorSize, kImpostorSize);
  const render::Camera camera = scene.camera(glm::normalize(glm::vec3(0.6f, 0.3f, 0.75f)), 25.0f);
  const float d = glm::distance(camera.position, scene.crown);
  const Image full = scene.drawPieces(target, camera, glm::vec2(0.0f));
  const Image impostorFull = scene.drawImpostor(target, camera, glm::vec2(0.5f, 1.0f));
  // Off the baked views the blend of three views loses some thin twigs, yet keeps most of the tree.
  EXPECT_GT(iou(full, impostorFull), 0.5);
  for (const float blend : {0.25f, 0.5f, 0.75f}) {
    const glm::vec2 band(d - blend * 40.0f, d + (1.0f - blend) * 40.0f);
    ASSERT_NEAR(farBlend(d, band), blend, 1e-4f);
    const Image piecesPass = scene.drawPieces(target, camera, band);
    const Image impostorPass = scene.drawImpostor(target, camera, band);
    const Image both = scene.drawBoth(target, camera, band);
    int overlap = 0;
    int fromPieces = 0;
    int fromImpostor = 0;
    int unionCount = 0;
    int bothCount = 0;
    for (int y = 0; y < kImpostorSize; ++y) {
      for (int x = 0; x < kImpostorSize; ++x) {
        const bool p = covered(piecesPass, x, y);
        const bool i = covered(impostorPass, x, y);
        overlap += p && i ? 1 : 0;
        fromPieces += p ? 1 : 0;
        fromImpostor += i ? 1 : 0;
        unionCount += p || i ? 1 : 0;
        bothCount += covered(both, x, y) ? 1 : 0;
      }
    }
    const int all = coverageOf(full).count;
    const int impostorAll = coverageOf(impostorFull).count;
    std::printf("blend %.2f: pieces %d, impostor %d, overlap %d, union %d; alone: pieces %d, impostor %d\n",
                blend, fromPieces, fromImpostor, overlap, unionCount, all, impostorAll);
    EXPECT_EQ(overlap, 0);
    EXPECT_EQ(bothCount, unionCount);
    // Each pass keeps its share of its own silhouette, so the union lies between the two silhouettes.
    EXPECT_NEAR(static_cast<double>(fromPieces) / all, 1.0 - blend, 0.1);
    EXPECT_NEAR(static_cast<double>(fromImpostor) / impostorAll, blend, 0.1);
    EXPECT_GE(unionCount, 0.95 * std::min(all, impostorAll));
    EXPECT_LE(unionCount, 1.05 * std::max(all, impostorAll));
  }
}

/** The largest change between consecutive frames of a dolly through the band: covered pixels (relative),
 * mean colour, and pixels whose colour changed by more than 0.1 (relative to the covered pixels). */
struct Popping {
  double count = 0.0;
  double colour = 0.0;
  double changed = 0.0;
};

Popping dolly(Scene& scene, glm::vec2 band, float from, float to, int steps) {
  render::RenderTarget target(kImpostorSize, kImpostorSize);
  const glm::vec3 direction = glm::normalize(glm::vec3(-0.5f, 0.25f, 0.8f));
  Popping worst;
  Image previous;
  Coverage last;
  for (int k = 0; k <= steps; ++k) {
    // Crown distance from `from` to `to`; the view narrows as it backs off so the tree keeps its size (a
    // dolly zoom): what changes is the far field, not the framing.
    const float d = from + (to - from) * static_cast<float>(k) / static_cast<float>(steps);
    render::Camera camera = scene.camera(direction, 25.0f);
    camera.position = scene.crown + direction * d + (scene.centre - scene.crown);
    camera.fovY = 2.0f * std::atan(scene.radius / (0.8f * glm::distance(camera.position, scene.centre)));
    camera.nearPlane = 0.5f * d;
    camera.farPlane = 2.0f * d;
    const Image image = scene.drawBoth(target, camera, band);
    const Coverage c = coverageOf(image);
    if (std::getenv("SYLVA_TEST_VERBOSE") != nullptr && k == 20) {
      const std::string tag = std::to_string(static_cast<int>(band.y - band.x));
      keep(image, "dolly-both" + tag);
      keep(scene.drawPieces(target, camera, band), "dolly-pieces" + tag);
      keep(scene.drawImpostor(target, camera, band), "dolly-impostor" + tag);
      keep(scene.drawImpostor(target, camera, {0.5f, 1.0f}), "dolly-impostor-full" + tag);
      keep(scene.drawPieces(target, camera, {0.0f, 0.0f}), "dolly-pieces-full" + tag);
    }
    if (k > 0) {
      int changed = 0;
      for (int y = 0; y < kImpostorSize; ++y) {
        for (int x = 0; x < kImpostorSize; ++x) {
          float diff = 0.0f;
          for (int ch = 0; ch < 4; ++ch) {
            diff = std::max(diff, std::abs(image.get(x, y, ch) - previous.get(x, y, ch)));
          }
          changed += diff > 0.1f ? 1 : 0;
        }
      }
      if (std::getenv("SYLVA_TEST_VERBOSE") != nullptr) {
        std::printf("  d %.1f blend %.3f: count %d changed %d mean %.3f\n", d, farBlend(d, band), c.count,
                    changed, c.mean.g);
      }
      worst.count = std::max(worst.count,
                             std::abs(static_cast<double>(c.count - last.count)) / std::max(last.count, 1));
      worst.colour = std::max(worst.colour, static_cast<double>(glm::length(c.mean - last.mean)));
      worst.changed = std::max(worst.changed, static_cast<double>(changed) / std::max(last.count, 1));
    }
    previous = image;
    last = c;
  }
  return worst;
}

TEST_F(ImpostorRendererTest, MovingThroughTheBandDoesNotPop) {
  Scene scene(shaders());
  // 40 steps of 1 m from 230 m to 270 m: the band 240 … 260 m covers 20 of them; the hard switch is at 250 m.
  const Popping band = dolly(scene, {240.0f, 260.0f}, 230.0f, 270.0f, 40);
  const Popping hard = dolly(scene, {250.0f, 250.001f}, 230.0f, 270.0f, 40);
  std::printf("band: count %.4f colour %.4f changed %.4f; hard switch: count %.4f colour %.4f changed %.4f\n",
              band.count, band.colour, band.changed, hard.count, hard.colour, hard.changed);
  // A step in the band swaps a twentieth of the pixels: few change, coverage and colour barely move.
  EXPECT_LT(band.changed, 0.08);
  EXPECT_LT(band.count, 0.03);
  EXPECT_LT(band.colour, 0.01);
  // The hard switch swaps them all in one step: many pixels and the mean colour jump (the silhouettes agree
  // well enough that the covered count jumps little either way).
  EXPECT_GT(hard.changed, 3.0 * band.changed);
  EXPECT_GT(hard.colour, 3.0 * band.colour);
}

TEST_F(ImpostorRendererTest, HundredThousandFarTreesDraw) {
  Scene scene(shaders());
  FarTreeFieldSettings field;
  field.count = 100000;
  field.innerRadius = 60.0f;
  field.outerRadius = 3000.0f;
  field.seed = 5;
  const std::vector<FarTree> trees = farTreeField(field);
  scene.impostors->setTrees(trees);
  EXPECT_EQ(scene.impostors->treeCount(), 100000u);
  int width = 320;
  int height = 180;
  if (const char* size = std::getenv("SYLVA_IMPOSTOR_SIZE")) {
    std::sscanf(size, "%dx%d", &width, &height);
  }
  render::RenderTarget target(width, height);
  render::Camera camera;
  camera.position = {0.0f, 40.0f, 0.0f};
  camera.target = {600.0f, 0.0f, 500.0f};
  camera.fovY = glm::radians(50.0f);
  camera.nearPlane = 1.0f;
  camera.farPlane = 5000.0f;
  gl::Query primitives(GL_PRIMITIVES_GENERATED);
  gl::Query samples(GL_SAMPLES_PASSED);
  // Once to warm up (shader variants are compiled at the first draw), then measured.
  target.begin(kClear);
  scene.impostors->draw(camera, width, height, 0.0, {100.0f, 120.0f});
  target.begin(kClear);
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  primitives.begin();
  samples.begin();
  scene.impostors->draw(camera, width, height, 0.0, {100.0f, 120.0f});
  samples.end();
  primitives.end();
  glFinish();
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const Image image = target.readColor();
  keep(image, "impostor-field");
  // The cull keeps what its CPU twin keeps (a float tie or two aside); two triangles per kept tree drawn.
  const glm::vec2 farRange(100.0f, 120.0f);
  const Frustum frustum = camera.frustum(target.aspect());
  std::uint32_t expected = 0;
  for (const FarTree& t : trees) {
    expected += impostorVisible(t, scene.impostors->speciesSphere(t.species), frustum.planes(),
                                camera.position, farRange)
                    ? 1u
                    : 0u;
  }
  const std::uint32_t kept = scene.impostors->readVisibleCount();
  std::printf("kept %u of 100,000 (CPU twin: %u)\n", kept, expected);
  EXPECT_NEAR(static_cast<double>(kept), static_cast<double>(expected), 5.0);
  EXPECT_GT(kept, 10000u);
  EXPECT_LT(kept, 90000u);
  EXPECT_EQ(primitives.result().value_or(0), 2u * kept);
  EXPECT_GT(samples.result().value_or(0), 1000u);
  EXPECT_GT(coverageOf(image).count, width * height / 20);
  std::printf("100,000 impostors at %dx%d: %.1f ms; atlas %d x %d x %d, %.1f MiB GPU\n", width, height, ms,
              scene.impostors->settings().layout.side(), scene.impostors->settings().layout.side(),
              scene.impostors->speciesCount(), static_cast<double>(scene.impostors->gpuBytes()) / (1 << 20));
}

TEST_F(ImpostorRendererTest, BakedDepthSortsAgainstOpaqueSurfaces) {
  Scene scene(shaders());
  render::RenderTarget target(kImpostorSize, kImpostorSize);
  const glm::vec3 direction = glm::normalize(glm::vec3(0.4f, 0.2f, -0.9f));
  const render::Camera camera = scene.camera(direction, 25.0f);
  const float distance = glm::distance(camera.position, scene.centre);
  const glm::vec2 impostorOnly(0.5f, 1.0f);
  const Image alone = scene.drawImpostor(target, camera, impostorOnly);
  const Image depth = target.readDepth();
  // The depth written is the baked one: it varies across the tree and stays within its sphere.
  const glm::mat4 projection = camera.projection(1.0f);
  auto windowDepth = [&](float eyeDistance) {
    const glm::vec4 clip = projection * glm::vec4(0.0f, 0.0f, -eyeDistance, 1.0f);
    return 0.5f * clip.z / clip.w + 0.5f;
  };
  float lo = 1.0f;
  float hi = 0.0f;
  for (int y = 0; y < kImpostorSize; ++y) {
    for (int x = 0; x < kImpostorSize; ++x) {
      if (covered(alone, x, y)) {
        lo = std::min(lo, depth.get(x, y, 0));
        hi = std::max(hi, depth.get(x, y, 0));
      }
    }
  }
  EXPECT_GE(lo, windowDepth(distance - 1.05f * scene.radius));
  EXPECT_LE(hi, windowDepth(distance + 1.05f * scene.radius));
  EXPECT_GT(hi - lo, 0.1f * (windowDepth(distance + scene.radius) - windowDepth(distance - scene.radius)));
  // An opaque screen-aligned quad over the lower half of the view, in front of the tree and then behind it.
  int aloneInQuad = 0;
  for (int y = kImpostorSize / 2; y < kImpostorSize; ++y) {
    for (int x = 0; x < kImpostorSize; ++x) {
      aloneInQuad += covered(alone, x, y) ? 1 : 0;
    }
  }
  ASSERT_GT(aloneInQuad, 100);
  for (const bool inFront : {true, false}) {
    target.begin(kClear);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, kImpostorSize, kImpostorSize / 2);
    target.framebuffer().clearColor(0, glm::vec4(1.0f, 0.0f, 1.0f, 1.0f));
    target.framebuffer().clearDepth(windowDepth(distance + (inFront ? -1.2f : 1.2f) * scene.radius));
    glDisable(GL_SCISSOR_TEST);
    scene.impostors->draw(camera, kImpostorSize, kImpostorSize, 0.0, impostorOnly);
    const Image image = target.readColor();
    int treeInQuad = 0;
    int treeOutside = 0;
    for (int y = 0; y < kImpostorSize; ++y) {
      for (int x = 0; x < kImpostorSize; ++x) {
        const bool inQuad = y >= kImpostorSize / 2; // file order: the lower half
        const bool magenta =
            image.get(x, y, 0) == 1.0f && image.get(x, y, 1) == 0.0f && image.get(x, y, 2) == 1.0f;
        if (inQuad) {
          treeInQuad += !magenta ? 1 : 0;
        } else {
          treeOutside += covered(image, x, y) ? 1 : 0;
        }
      }
    }
    std::printf("quad %s: tree pixels in the quad %d, outside %d\n", inFront ? "in front" : "behind",
                treeInQuad, treeOutside);
    EXPECT_GT(treeOutside, 100);
    if (inFront) {
      EXPECT_EQ(treeInQuad, 0);
    } else {
      EXPECT_EQ(treeInQuad, aloneInQuad);
    }
  }
}

// Far trees lean in the wind (issue 30: impostors did not sway): the impostor is sheared about its base, so,
// seen side-on, each row of the crown moves downwind by the lean times its height above the base, the lean
// the CPU's impostorLean gives; in still air the image is the upright tree's, bit for bit.
TEST_F(ImpostorRendererTest, FarTreesLeanInTheWind) {
  Scene scene(shaders());
  render::RenderTarget target(kImpostorSize, kImpostorSize);
  const glm::vec2 impostorOnly(0.5f, 1.0f);
  // Seen along −z: world +x is screen right, the wind blows along +x.
  const float distance = 25.0f;
  const render::Camera camera = scene.camera(glm::vec3(0.0f, 0.0f, 1.0f), distance);
  const Image upright = scene.drawImpostor(target, camera, impostorOnly);
  wind::WindSettings still;
  still.speed = 0.0f;
  scene.impostors->setWind(wind::toUniforms(still, 3.0f));
  EXPECT_TRUE(scene.drawImpostor(target, camera, impostorOnly) == upright) << "still air leans nothing";

  wind::WindSettings steady;
  steady.speed = 8.0f;
  steady.gustStrength = 0.0f;
  steady.turbulence = 0.0f;
  const gpu::WindUniforms w = wind::toUniforms(steady, 3.0f);
  scene.impostors->setWind(w);
  const Image leaning = scene.drawImpostor(target, camera, impostorOnly);
  keep(upright, "impostor-upright");
  keep(leaning, "impostor-leaning");
  const glm::vec2 lean = impostorLean(scene.far[0], scene.impostors->speciesSway(0), w);
  ASSERT_GT(lean.x, 0.02f) << "an 8 m/s wind leans the tree";
  EXPECT_NEAR(lean.y, 0.0f, 1e-6f);
  // Metres per pixel on the plane through the sphere's centre (Scene::camera: the sphere fills 0.8 of it).
  const float metresPerPixel = 2.0f * scene.radius / 0.8f / static_cast<float>(kImpostorSize);
  double measured = 0.0;
  double expected = 0.0;
  double lowShift = 0.0;
  double highShift = 0.0;
  int rows = 0;
  for (int y = 0; y < kImpostorSize; ++y) {
    double a = 0.0;
    double b = 0.0;
    int na = 0;
    int nb = 0;
    for (int x = 0; x < kImpostorSize; ++x) {
      if (covered(upright, x, y)) {
        a += x;
        ++na;
      }
      if (covered(leaning, x, y)) {
        b += x;
        ++nb;
      }
    }
    if (na < 4 || nb < 4) {
      continue;
    }
    // Image rows run top down (readColor: file order).
    const float worldY =
        scene.centre.y + (0.5f * kImpostorSize - (static_cast<float>(y) + 0.5f)) * metresPerPixel;
    const double shift = b / nb - a / na;
    measured += shift;
    expected += lean.x * (worldY - scene.far[0].position.y) / metresPerPixel;
    (worldY > scene.centre.y ? highShift : lowShift) += shift;
    ++rows;
  }
  ASSERT_GT(rows, 40);
  std::printf("lean %.4f: mean row shift %.2f px, expected %.2f px\n", lean.x, measured / rows,
              expected / rows);
  EXPECT_GT(measured / rows, 1.0) << "the crown moves downwind";
  EXPECT_NEAR(measured / expected, 1.0, 0.3) << "by the lean times the height above the base";
  EXPECT_GT(highShift, lowShift) << "the top moves more than the trunk";
}

} // namespace
} // namespace sylva::trees
