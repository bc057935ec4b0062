#include <sylva/trees/gpu/SpeciesSheet.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/trees/Skeleton.hpp>
#include <sylva/trees/gpu/ForestScene.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace sylva::trees {
namespace {

constexpr float kCameraDistance = 2000.0f; // metres: a near-orthographic view
const glm::vec4 kSky(0.78f, 0.85f, 0.93f, 1.0f);
const glm::vec3 kGround(0.42f, 0.36f, 0.27f);
const glm::vec3 kMarker(0.12f, 0.12f, 0.14f);

/** Horizontal extent (x) and height of a tree at rest, metres, from its joints, widened by its leaf clusters.
 */
struct Extent {
  float left = std::numeric_limits<float>::infinity();
  float right = -std::numeric_limits<float>::infinity();
  float top = 0.0f;
};

Extent extentOf(const Forest& forest, const ForestTree& tree) {
  std::vector<glm::mat4> frames;
  jointFrames(forest.pieces, tree.topology, tree.base, tree.pose, frames);
  const Species& species = forest.species[static_cast<std::size_t>(tree.species)];
  const float leaves = species.leafCluster > 0.0f ? 1.3f * species.leafCluster : 1.5f;
  Extent e;
  for (const glm::mat4& f : frames) {
    e.left = std::min(e.left, f[3].x - leaves);
    e.right = std::max(e.right, f[3].x + leaves);
    e.top = std::max(e.top, f[3].y + leaves);
  }
  return e;
}

void fill(Image& image, int x0, int y0, int x1, int y1, const glm::vec3& colour) {
  for (int y = std::max(y0, 0); y < std::min(y1, image.height()); ++y) {
    for (int x = std::max(x0, 0); x < std::min(x1, image.width()); ++x) {
      for (int c = 0; c < 3; ++c) {
        image.set(x, y, c, colour[c]);
      }
    }
  }
}

} // namespace

Image renderSpeciesSheet(const shader::Library& library, const std::vector<Species>& species,
                         const SpeciesSheetOptions& options) {
  if (species.empty()) {
    fail("species sheet: needs at least one species");
  }
  if (options.height < 16 || options.height > 8192) {
    fail("species sheet: height {} px is out of range [16, 8192]", options.height);
  }
  // One tree per species, each grown at the origin, then moved along x so crowns and markers do not meet.
  auto forest = std::make_shared<Forest>();
  forest->pieces = standardPieces();
  std::vector<float> markers;
  float cursor = 0.0f;
  float top = kSheetMarkerHeight;
  for (std::size_t i = 0; i < species.size(); ++i) {
    Forest one = gridForestOf({species[i]}, 1, 1.0f, options.seed);
    ForestTree tree = std::move(one.trees.front());
    const Extent e = extentOf(one, tree);
    tree.species = static_cast<int>(i);
    forest->species.push_back(species[i]);
    const float markerX = cursor + options.gap * 0.5f;
    const float shift = markerX + options.gap * 0.5f - e.left;
    tree.base = glm::translate(glm::mat4(1.0f), glm::vec3(shift, 0.0f, 0.0f)) * tree.base;
    markers.push_back(markerX);
    cursor = e.right + shift;
    top = std::max(top, e.top);
    forest->trees.push_back(std::move(tree));
  }
  forest->index();
  const float width = cursor + options.gap * 0.5f;
  top *= 1.05f;                    // sky above the tallest crown
  const float below = 0.06f * top; // ground strip
  const float tall = top + below;
  const int heightPx = options.height;
  const double widthPx = std::ceil(static_cast<double>(heightPx) * width / tall);
  if (widthPx > 16384.0) {
    fail("species sheet: {} species at {} px high make an image {} px wide (at most 16,384)", species.size(),
         heightPx, widthPx);
  }
  const int w = static_cast<int>(widthPx);
  const float metresPerPixel = tall / static_cast<float>(heightPx);

  render::Camera camera;
  camera.target = glm::vec3(0.5f * width, top - 0.5f * tall, 0.0f);
  camera.position = camera.target + glm::vec3(0.0f, 0.0f, kCameraDistance);
  camera.fovY = 2.0f * std::atan(0.5f * tall / kCameraDistance);
  camera.nearPlane = kCameraDistance - 100.0f;
  camera.farPlane = kCameraDistance + 100.0f;

  ForestScene scene(library, forest, false);
  check(options.look);
  scene.setBark(barkSources(options.look));
  scene.applyFoliage(options.look);
  render::RenderTarget target(w, heightPx);
  target.begin(kSky);
  TreeDrawOptions draw;
  draw.environment.fogDensity =
      0.0f; // the camera stands kilometres away; the trees are not seen through haze
  scene.draw(camera, w, heightPx, 0.0, TreeLod{}, draw);
  Image image = target.readColor();

  // Image rows run top down: world y = top − (row + ½) · metres per pixel.
  auto row = [&](float y) { return static_cast<int>(std::lround((top - y) / metresPerPixel)); };
  auto column = [&](float x) { return static_cast<int>(std::lround(x / metresPerPixel)); };
  fill(image, 0, row(0.0f), w, heightPx, kGround);
  for (const float x : markers) {
    // A person: body 0.45 m wide to 1.5 m, a head 0.24 m across on top.
    fill(image, column(x - 0.225f), row(1.5f), column(x + 0.225f), row(0.0f), kMarker);
    fill(image, column(x - 0.12f), row(kSheetMarkerHeight), column(x + 0.12f), row(1.5f), kMarker);
  }
  return image;
}

} // namespace sylva::trees
