// Streamed terrain (docs/terrain-data.md, "Streaming") on the GPU: no holes or cracks while tiles stream in
// and coarser tiles stand in, drawn vertices equal the CPU query of the drawn surface, precision far from the
// world's origin, and budgets that do not fit are refused.
#include <sylva/core/Error.hpp>
#include <sylva/gl/Framebuffer.hpp>
#include <sylva/gl/Texture.hpp>
#include <sylva/terrain/TileSource.hpp>
#include <sylva/terrain/gpu/StreamedTerrain.hpp>

#include "GlTest.hpp"
#include "TestUtil.hpp"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <memory>
#include <random>

namespace sylva::terrain {
namespace {

class StreamedTerrainTest : public test::GlTest {};

std::shared_ptr<ProceduralWorld> world(int side) {
  ProceduralSpec spec = defaultLandscapeSpec(11);
  spec.heightScale = 500.0f;
  return std::make_shared<ProceduralWorld>(spec, side, 1.0f, 64);
}

/** A float target that keeps world positions (alpha 0 = nothing drawn). */
struct StreamTarget {
  StreamTarget(int w, int h)
      : width(w), height(h), colour(gl::Texture::create2D(GL_RGBA32F, w, h)),
        depth(gl::Texture::create2D(GL_DEPTH_COMPONENT32F, w, h)) {
    fb.attachColor(0, colour);
    fb.attachDepth(depth);
    fb.checkComplete();
  }
  Image draw(StreamedTerrain& terrain, const render::Camera& camera, bool points,
             StreamedView view = StreamedView::WorldPosition) {
    fb.bindForDraw(width, height);
    fb.clearColor(0, glm::vec4(0.0f));
    fb.clearDepth();
    glEnable(GL_DEPTH_TEST);
    terrain.draw(camera, width, height, 0.0, view, {}, points);
    return colour.download(4, PixelType::F32);
  }
  int width;
  int height;
  gl::Texture colour;
  gl::Texture depth;
  gl::Framebuffer fb;
};

int emptyPixels(const Image& image) {
  int empty = 0;
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      empty += image.get(x, y, 3) == 0.0f ? 1 : 0;
    }
  }
  return empty;
}

constexpr float kFov = 0.87f; // 50 degrees

/** A camera `altitude` metres above the ground at (x, z), looking forward (heading) and down (pitch). */
void pose(const ProceduralWorld& w, double x, double z, double altitude, double heading, double pitch,
          glm::dvec3& eye, glm::dvec3& target) {
  eye = glm::dvec3(x, w.heightAt(x, z) + altitude, z);
  const glm::dvec3 dir(std::cos(pitch) * std::cos(heading), std::sin(pitch),
                       std::cos(pitch) * std::sin(heading));
  target = eye + dir * 100.0;
}

TEST_F(StreamedTerrainTest, NoHolesOrCracksWhileTilesStreamInBehindStandIns) {
  const auto source = world(16385);
  StreamedTerrainOptions options;
  options.gpuBudget = std::size_t{48} << 20;
  options.ramBudget = std::size_t{96} << 20;
  options.uploadsPerFrame = 6; // few per frame: many frames mix stand-ins and fresh tiles
  StreamedTerrain terrain(shaders(), source, options);
  StreamTarget target(320, 180);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> pos(4000.0, 12000.0); // views stay inside the world
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int framesWithStandIns = 0;
  int coarserEdges = 0;
  int frames = 0;
  for (int view = 0; view < 8; ++view) {
    glm::dvec3 eye;
    glm::dvec3 look;
    pose(*source, pos(rng), pos(rng), 30.0 + 900.0 * unit(rng) * unit(rng), 6.28 * unit(rng),
         -(1.0 + 0.45 * unit(rng)), eye, look);
    // Frame by frame while the loaders work, then complete.
    for (int step = 0; step < 8; ++step) {
      const StreamedFrame frame = terrain.update(eye, look, glm::dvec3(0.0), kFov, 320.0f / 180.0f, 30000.0f);
      framesWithStandIns += frame.waited ? 1 : 0;
      for (const SelectedTile& t : terrain.selection().tiles) {
        coarserEdges += t.coarserEdges != 0 ? 1 : 0;
      }
      const Image image = target.draw(terrain, terrain.relativeCamera(kFov, 0.5f, 30000.0f), false);
      ASSERT_EQ(emptyPixels(image), 0) << "view " << view << " step " << step << ": a hole in the ground";
      ++frames;
      if (step % 2 == 1) {
        const_cast<TileStreamer&>(terrain.streamer()).waitIdle();
      }
    }
    const StreamedFrame done = terrain.updateComplete(eye, look, kFov, 320.0f / 180.0f, 30000.0f);
    EXPECT_FALSE(done.waited);
    const Image image = target.draw(terrain, terrain.relativeCamera(kFov, 0.5f, 30000.0f), false);
    ASSERT_EQ(emptyPixels(image), 0) << "view " << view << " complete";
  }
  EXPECT_GT(framesWithStandIns, frames / 4) << "stand-ins must be exercised";
  EXPECT_GT(coarserEdges, 0) << "edges beside coarser tiles must be exercised";
  RecordProperty("frames_with_stand_ins", framesWithStandIns);
}

TEST_F(StreamedTerrainTest, DrawnVerticesEqualTheHeightQueryEvenFarFromTheOrigin) {
  const auto source = world(kProceduralWorldSide);
  StreamedTerrain terrain(shaders(), source);
  StreamTarget target(240, 150);
  for (const double at : {3000.0, 1048000.0}) { // near the world's origin, and 1,048 km away
    glm::dvec3 eye;
    glm::dvec3 look;
    pose(*source, at, at - 1200.0, 40.0, 0.7, -0.5, eye, look);
    terrain.updateComplete(eye, look, kFov, 240.0f / 150.0f, 20000.0f);
    const Image image = target.draw(terrain, terrain.relativeCamera(kFov, 0.5f, 20000.0f), true);
    const glm::dvec3 origin = terrain.origin();
    double worst = 0.0;
    int points = 0;
    for (int y = 0; y < image.height(); ++y) {
      for (int x = 0; x < image.width(); ++x) {
        if (image.get(x, y, 3) == 0.0f) {
          continue;
        }
        const double wx = origin.x + image.get(x, y, 0);
        const double wz = origin.z + image.get(x, y, 2);
        const float query = terrain.drawnHeightAt(wx, wz);
        ASSERT_FALSE(std::isnan(query)) << wx << "," << wz;
        worst = std::max(worst, std::abs(static_cast<double>(query) - image.get(x, y, 1)));
        ++points;
      }
    }
    EXPECT_GT(points, 2000) << at;
    EXPECT_LE(worst, 0.01) << "drawn vertices and the query disagree " << worst << " m at " << at;
    // Near the camera the drawn tiles are level 0: the query is the world's own surface there.
    EXPECT_NEAR(terrain.drawnHeightAt(eye.x, eye.z), source->heightAt(eye.x, eye.z), 0.01);
  }
}

// Shading is continuous across tile borders: every drawn vertex's normal is the central difference of its
// level's samples, also on a tile's border, where the sample beyond lies in the neighbouring tile (read from
// its layer when it is on the GPU). One-sided differences there drew a seam along every tile edge.
TEST_F(StreamedTerrainTest, NormalsTakeCentralDifferencesAcrossTileBorders) {
  const auto source = world(kProceduralWorldSide);
  StreamedTerrain terrain(shaders(), source);
  StreamTarget target(240, 150);
  const int T = terrain.layout().tileSize;
  glm::dvec3 eye;
  glm::dvec3 look;
  pose(*source, 5000.0, 3800.0, 60.0, 0.7, -0.6, eye, look);
  terrain.updateComplete(eye, look, kFov, 240.0f / 150.0f, 20000.0f);
  const render::Camera camera = terrain.relativeCamera(kFov, 0.5f, 20000.0f);
  const Image positions = target.draw(terrain, camera, true);
  const Image normals = target.draw(terrain, camera, true, StreamedView::Normal);
  const glm::dvec3 origin = terrain.origin();
  double worst = 0.0;
  int checked = 0;
  int borders = 0;
  for (int y = 0; y < positions.height(); ++y) {
    for (int x = 0; x < positions.width(); ++x) {
      if (positions.get(x, y, 3) == 0.0f) {
        continue;
      }
      ASSERT_GT(normals.get(x, y, 3), 0.0f) << "the two draws cover the same points";
      const int level = static_cast<int>(normals.get(x, y, 3)) - 1;
      const double step = std::ldexp(1.0, level); // metres between the level's samples (1 m spacing)
      const long long i = std::llround((origin.x + positions.get(x, y, 0)) / step);
      const long long j = std::llround((origin.z + positions.get(x, y, 2)) / step);
      const bool borderX = i % T == 0;
      const bool borderZ = j % T == 0;
      // Where the tile beyond a border is not on the GPU the shader falls back to one side: not checked.
      const auto beyond = [&](long long di, long long dj) {
        return terrain.onGpu(TileKey{level, static_cast<int>((i + di) / T), static_cast<int>((j + dj) / T)});
      };
      if ((borderX && (!beyond(-1, 0) || !beyond(1, 0))) || (borderZ && (!beyond(0, -1) || !beyond(0, 1)))) {
        continue;
      }
      const auto h = [&](long long a, long long b) {
        return static_cast<double>(
            source->heightAt(static_cast<double>(a) * step, static_cast<double>(b) * step));
      };
      const glm::dvec3 expected = glm::normalize(glm::dvec3(-(h(i + 1, j) - h(i - 1, j)) / (2.0 * step), 1.0,
                                                            -(h(i, j + 1) - h(i, j - 1)) / (2.0 * step)));
      const glm::dvec3 drawn(normals.get(x, y, 0), normals.get(x, y, 1), normals.get(x, y, 2));
      worst = std::max(worst, glm::length(drawn - expected));
      ++checked;
      borders += borderX || borderZ ? 1 : 0;
    }
  }
  EXPECT_GT(checked, 2000);
  EXPECT_GT(borders, 100) << "the view must show tile borders";
  EXPECT_LE(worst, 1e-4) << "a drawn normal differs from the central difference by " << worst;
  RecordProperty("border_vertices", borders);
}

TEST_F(StreamedTerrainTest, BudgetsThatDoNotFitAreRefused) {
  const auto source = world(4097);
  StreamedTerrainOptions options;
  options.gpuBudget = 10 * 65 * 65 * 4;
  EXPECT_NE(test::errorOf([&] { StreamedTerrain(shaders(), source, options); }).find("--gpu-budget"),
            std::string::npos);
  options.gpuBudget = std::size_t{64} << 20;
  options.ramBudget = std::size_t{8} << 20;
  EXPECT_NE(test::errorOf([&] { StreamedTerrain(shaders(), source, options); }).find("--ram-budget"),
            std::string::npos);
}

} // namespace
} // namespace sylva::terrain
