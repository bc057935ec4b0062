// Geomorphing (CPU reference): morphedHeight is the plain surface near the camera and when off, matches the
// lattice surfaces at their vertices, is continuous as the camera moves, and removes the pops of the surface
// a selection draws when patches split or merge.
#include <sylva/terrain/Geomorph.hpp>

#include <sylva/core/Random.hpp>
#include <sylva/terrain/HeightQuery.hpp>
#include <sylva/terrain/Noise.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace sylva::terrain {
namespace {

HeightField testField() {
  ProceduralSpec spec;
  spec.seed = 11;
  spec.frequency = 1.0f / 160.0f;
  spec.heightScale = 80.0f;
  return generate(spec, 0.0, 0.0, 257, 257, 2.0f); // 512 m square
}

QuadtreeConfig testConfig() {
  QuadtreeConfig config;
  config.rootSize = 128.0f;
  config.maxDepth = 4; // 8 m leaves
  config.patchTessLevel = 4;
  config.lodDistanceFactor = 2.0f;
  return config;
}

TEST(Geomorph, PlainSurfaceWhenOffAndNearTheCamera) {
  const HeightField field = testField();
  GeomorphParams params = GeomorphParams::of(testConfig());
  const glm::vec3 camera(200.0f, heightAt(field, 200.0f, 210.0f) + 2.0f, 210.0f);
  // λ ≥ maxDepth within F · rootSize / 2^maxDepth = 16 m of the camera.
  Rng rng(5);
  for (int i = 0; i < 500; ++i) {
    const glm::vec2 xz(rng.uniform(195.0f, 205.0f), rng.uniform(205.0f, 215.0f));
    EXPECT_EQ(morphedHeight(field, xz, camera, params), heightAt(field, xz.x, xz.y));
  }
  params.enabled = false;
  double far = 0.0;
  for (int i = 0; i < 500; ++i) {
    const glm::vec2 xz(rng.uniform(0.0f, 512.0f), rng.uniform(0.0f, 512.0f));
    EXPECT_EQ(morphedHeight(field, xz, camera, params), heightAt(field, xz.x, xz.y));
    params.enabled = true;
    far = std::max(far, static_cast<double>(std::abs(morphedHeight(field, xz, camera, params) -
                                                     heightAt(field, xz.x, xz.y))));
    params.enabled = false;
  }
  EXPECT_GT(far, 0.5) << "far from the camera the morph must smooth the surface";
}

TEST(Geomorph, LatticeSurfacesPassThroughTheirVertices) {
  const HeightField field = testField();
  const GeomorphParams params = GeomorphParams::of(testConfig());
  for (int depth = 0; depth < params.maxDepth; ++depth) {
    const float step = params.rootSize / (std::exp2(static_cast<float>(depth)) * params.patchTessLevel);
    for (int j = 0; j * step <= 512.0f; j += 3) {
      for (int i = 0; i * step <= 512.0f; i += 5) {
        const glm::vec2 xz(i * step, j * step);
        EXPECT_NEAR(latticeHeight(field, xz, depth, params), heightAt(field, xz.x, xz.y), 1e-4f)
            << "depth " << depth << " vertex " << i << "," << j;
      }
    }
  }
}

TEST(Geomorph, ContinuousAsTheCameraMoves) {
  const HeightField field = testField();
  const GeomorphParams params = GeomorphParams::of(testConfig());
  Rng rng(9);
  float worstJump = 0.0f;
  float travel = 0.0f;
  for (int p = 0; p < 20; ++p) {
    const glm::vec2 xz(rng.uniform(0.0f, 512.0f), rng.uniform(0.0f, 512.0f));
    // A camera flying away from the point, 3 m to 600 m: λ sweeps every band and boundary.
    const glm::vec3 dir = glm::normalize(glm::vec3(rng.uniform(-1.0f, 1.0f), 0.3f, rng.uniform(-1.0f, 1.0f)));
    const glm::vec3 base(xz.x, heightAt(field, xz.x, xz.y), xz.y);
    float last = morphedHeight(field, xz, base + dir * 3.0f, params);
    float lo = last;
    float hi = last;
    for (float d = 3.0f; d < 600.0f; d += 0.01f) {
      const float h = morphedHeight(field, xz, base + dir * d, params);
      worstJump = std::max(worstJump, std::abs(h - last));
      lo = std::min(lo, h);
      hi = std::max(hi, h);
      last = h;
    }
    travel = std::max(travel, hi - lo);
  }
  RecordProperty("worst_jump_per_cm_mm", std::to_string(worstJump * 1000.0f));
  EXPECT_GT(travel, 0.5f) << "the morph must move some vertices";
  EXPECT_LT(worstJump, 0.005f) << "a 1 cm camera step moved a vertex by more than 5 mm";
}

/** Height a selection draws at xz: bilinear over the T×T vertex grid of the leaf containing xz. */
float drawnHeight(const QuadtreeSelection& selection, const glm::vec2& xz,
                  const std::function<float(glm::vec2)>& height) {
  const float t = static_cast<float>(selection.config.patchTessLevel);
  for (const SelectedNode& n : selection.nodes) {
    if (xz.x < n.x || xz.y < n.z || xz.x >= n.x + n.size || xz.y >= n.z + n.size) {
      continue;
    }
    const float cell = n.size / t;
    const glm::vec2 local = (xz - glm::vec2(n.x, n.z)) / cell;
    const glm::vec2 k = glm::clamp(glm::floor(local), glm::vec2(0.0f), glm::vec2(t - 1.0f));
    const glm::vec2 f = local - k;
    const glm::vec2 p0 = glm::vec2(n.x, n.z) + k * cell;
    const glm::vec2 p1 = p0 + cell;
    const float a = glm::mix(height(p0), height({p1.x, p0.y}), f.x);
    const float b = glm::mix(height({p0.x, p1.y}), height(p1), f.x);
    return glm::mix(a, b, f.y);
  }
  return std::nanf("");
}

// The camera walks in 1 m steps; wherever the selection changes, the surface drawn before and after the step
// is compared at the same camera (the pop alone), without and with the morph.
TEST(Geomorph, RemovesPopsWhenPatchesSplitOrMerge) {
  const HeightField field = testField();
  const QuadtreeConfig config = testConfig();
  Quadtree quadtree(config, field);
  const GeomorphParams params = GeomorphParams::of(config);
  double popOff = 0.0;
  double popOn = 0.0;
  double worstOff = 0.0;
  double worstOn = 0.0;
  long long samples = 0;
  int changedSteps = 0;
  QuadtreeSelection before = quadtree.select({40.0f, 120.0f, 60.0f}, nullptr);
  for (int step = 1; step < 480 && changedSteps < 30; ++step) {
    const float s = static_cast<float>(step);
    const glm::vec3 camera(40.0f + 0.9f * s, 120.0f - 0.1f * s, 60.0f + 0.8f * s);
    QuadtreeSelection after = quadtree.select(camera, nullptr);
    if (after.nodes.size() != before.nodes.size()) {
      ++changedSteps;
      const auto plain = [&](glm::vec2 xz) { return heightAt(field, xz.x, xz.y); };
      const auto morphed = [&](glm::vec2 xz) { return morphedHeight(field, xz, camera, params); };
      for (float z = 1.0f; z < 512.0f; z += 4.0f) {
        for (float x = 1.0f; x < 512.0f; x += 4.0f) {
          const double off = std::abs(drawnHeight(before, {x, z}, plain) - drawnHeight(after, {x, z}, plain));
          const double on =
              std::abs(drawnHeight(before, {x, z}, morphed) - drawnHeight(after, {x, z}, morphed));
          popOff += off;
          popOn += on;
          worstOff = std::max(worstOff, off);
          worstOn = std::max(worstOn, on);
          ++samples;
        }
      }
    }
    before = std::move(after);
  }
  ASSERT_GE(changedSteps, 10);
  RecordProperty("mean_pop_off_mm", std::to_string(1000.0 * popOff / samples));
  RecordProperty("mean_pop_on_mm", std::to_string(1000.0 * popOn / samples));
  RecordProperty("worst_pop_off_m", std::to_string(worstOff));
  RecordProperty("worst_pop_on_m", std::to_string(worstOn));
  std::printf("pop over %d changed steps: mean %.3f mm off, %.3f mm on; worst %.3f m off, %.3f m on\n",
              changedSteps, 1000.0 * popOff / samples, 1000.0 * popOn / samples, worstOff, worstOn);
  EXPECT_GT(worstOff, 0.2) << "the walk must produce visible pops without the morph";
  EXPECT_LT(popOn, 0.05 * popOff);
  EXPECT_LT(worstOn, 0.1 * worstOff);
}

} // namespace
} // namespace sylva::terrain
