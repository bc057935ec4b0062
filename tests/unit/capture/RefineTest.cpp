// Skeleton refining: eq. 1–3, the heap refiner against the paper's O(n²) loop (bit-identical results on
// random trajectories and on ties), input validation, and the kinematic sway model that feeds it.
#include <sylva/capture/Refine.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

namespace sylva::capture {
namespace {

/** Runs `body`, which must throw sylva::Error whose message contains `part`. */
template <typename F> void expectError(F&& body, const std::string& part) {
  try {
    body();
    ADD_FAILURE() << "no error; expected one containing '" << part << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

/** `n` knots evenly spaced along +Y from the origin, `spacing` metres apart. */
std::vector<glm::vec3> straightBlade(int n, float spacing) {
  std::vector<glm::vec3> knots;
  for (int k = 0; k < n; ++k) {
    knots.emplace_back(0.0f, static_cast<float>(k) * spacing, 0.0f);
  }
  return knots;
}

/** A wobbly random walk per frame: knots near each other, with per-frame jitter that grows along the blade.
 */
KnotFrames randomFrames(Rng& rng, int knots, int frames) {
  std::vector<glm::vec3> base;
  glm::vec3 p(0.0f);
  for (int k = 0; k < knots; ++k) {
    base.push_back(p);
    p += glm::vec3(rng.uniform(-0.3f, 0.3f), rng.uniform(0.2f, 1.0f), rng.uniform(-0.3f, 0.3f)) * 0.01f;
  }
  KnotFrames result(static_cast<std::size_t>(frames));
  for (auto& frame : result) {
    for (int k = 0; k < knots; ++k) {
      const float jitter = 0.002f * static_cast<float>(k) / static_cast<float>(knots);
      frame.push_back(base[static_cast<std::size_t>(k)] +
                      glm::vec3(rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter), 0.0f));
    }
  }
  return result;
}

bool bitEqual(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof(glm::vec3)) == 0;
}

void expectIdentical(const RefineResult& a, const RefineResult& b) {
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t f = 0; f < a.frames.size(); ++f) {
    ASSERT_EQ(a.frames[f].size(), b.frames[f].size()) << "frame " << f;
    for (std::size_t k = 0; k < a.frames[f].size(); ++k) {
      ASSERT_TRUE(bitEqual(a.frames[f][k], b.frames[f][k])) << "frame " << f << " knot " << k;
    }
  }
  ASSERT_EQ(a.widths.size(), b.widths.size());
  for (std::size_t k = 0; k < a.widths.size(); ++k) {
    ASSERT_EQ(std::memcmp(&a.widths[k], &b.widths[k], sizeof(float)), 0) << "width " << k;
  }
  EXPECT_EQ(a.merged, b.merged);
}

TEST(RefineDifference, MatchesEquationsWithVarianceOverNSquared) {
  // d = 1, 3 over two frames: dis = 2, var = (1 + 9)/2 − 16/4 = 1.
  const std::vector<glm::vec3> a{{0, 0, 0}, {0, 0, 0}};
  const std::vector<glm::vec3> b{{1, 0, 0}, {0, 3, 0}};
  EXPECT_DOUBLE_EQ(movementDifference(a, b, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(movementDifference(a, b, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(movementDifference(a, b, 0.25), 0.25 * 2.0 + 0.75 * 1.0);
}

TEST(RefineDifference, ConstantDistanceHasNoVarianceAndNeverANegativeOne) {
  // A rigidly moving pair at a distance whose square rounds: the variance must come out as exactly 0, not −ε.
  std::vector<glm::vec3> a;
  std::vector<glm::vec3> b;
  for (int i = 0; i < 60; ++i) {
    const glm::vec3 p(0.1f * static_cast<float>(i), 0.3f, -0.7f);
    a.push_back(p);
    b.push_back(p + glm::vec3(0.1f, 0.2f, 0.3f));
  }
  const double d = movementDifference(a, b, 0.0);
  EXPECT_GE(d, 0.0);
  EXPECT_LT(d, 1e-12);
}

TEST(RefineDifference, RejectsMismatchedOrEmptyTrajectoriesAndBadMu) {
  const std::vector<glm::vec3> two{{0, 0, 0}, {1, 0, 0}};
  const std::vector<glm::vec3> one{{0, 0, 0}};
  expectError([&] { (void)movementDifference(two, one, 0.5); }, "2 and 1 frames");
  expectError([&] { (void)movementDifference({}, {}, 0.5); }, "no frames");
  expectError([&] { (void)movementDifference(two, two, 1.5); }, "outside [0, 1]");
}

TEST(RefineKnots, HeapMatchesReferenceExactlyOnRandomTrajectories) {
  Rng rng(20240611);
  int cases = 0;
  for (const int knots : {2, 3, 5, 17, 64, 128, 300}) {
    for (const int frames : {1, 2, 7, 60}) {
      for (const double mu : {0.0, 0.3, 0.5, 1.0}) {
        for (const bool keepEnds : {false, true}) {
          const KnotFrames input = randomFrames(rng, knots, frames);
          std::vector<float> widths;
          for (int k = 0; k < knots; ++k) {
            widths.push_back(rng.uniform(0.0f, 0.02f));
          }
          for (const int target : {2, 3, knots / 2, knots - 1}) {
            if (target < 2) {
              continue;
            }
            RefineOptions options;
            options.knots = target;
            options.mu = mu;
            options.keepEnds = keepEnds;
            SCOPED_TRACE(::testing::Message() << knots << " knots, " << frames << " frames, mu " << mu
                                              << ", keepEnds " << keepEnds << ", target " << target);
            const RefineResult heap = refineKnots(input, widths, options);
            const RefineResult reference = refineKnotsReference(input, widths, options);
            expectIdentical(heap, reference);
            ASSERT_EQ(heap.merged.size(), static_cast<std::size_t>(std::min(target, knots)));
            int total = 0;
            for (const int m : heap.merged) {
              total += m;
            }
            ASSERT_EQ(total, knots);
            ++cases;
          }
        }
      }
    }
  }
  EXPECT_GT(cases, 500);
}

TEST(RefineKnots, TiesOnAnEvenlySpacedStaticLineMatchTheReference) {
  // Exact ties everywhere (spacing a power of two): both pick the pair nearest the root among equals.
  const KnotFrames input{straightBlade(129, 0.0078125f)};
  for (const bool keepEnds : {false, true}) {
    for (const int target : {2, 16, 32, 64, 100}) {
      RefineOptions options;
      options.knots = target;
      options.keepEnds = keepEnds;
      const RefineResult heap = refineKnots(input, {}, options);
      expectIdentical(heap, refineKnotsReference(input, {}, options));
      EXPECT_TRUE(heap.widths.empty());
    }
  }
  // The first merge of all-equal pairs is the root pair.
  RefineOptions one;
  one.knots = 128;
  one.keepEnds = false;
  const RefineResult r = refineKnots(input, {}, one);
  EXPECT_EQ(r.merged[0], 2);
  EXPECT_FLOAT_EQ(r.frames[0][0].y, 0.5f * 0.0078125f);
}

TEST(RefineKnots, StaticStraightLineKeepsItsEndsAndStaysOnTheLine) {
  const std::vector<glm::vec3> line = straightBlade(128, 0.003f);
  std::vector<float> widths(128, 0.004f);
  widths.back() = 0.0f;
  RefineOptions options;
  options.knots = 16;
  const RefineResult r = refineKnots({line}, widths, options);
  ASSERT_EQ(r.frames.size(), 1u);
  ASSERT_EQ(r.frames[0].size(), 16u);
  EXPECT_EQ(r.frames[0].front(), line.front());
  EXPECT_EQ(r.frames[0].back(), line.back());
  EXPECT_EQ(r.widths.back(), 0.0f) << "keepEnds keeps the tip's own width";
  for (std::size_t k = 0; k < 16; ++k) {
    EXPECT_EQ(r.frames[0][k].x, 0.0f);
    EXPECT_EQ(r.frames[0][k].z, 0.0f);
    if (k > 0) {
      EXPECT_GT(r.frames[0][k].y, r.frames[0][k - 1].y) << "knots stay in root → tip order";
    }
  }
  // Without keepEnds the paper's midpoints shorten the blade.
  options.keepEnds = false;
  const RefineResult shortened = refineKnots({line}, widths, options);
  EXPECT_GT(shortened.frames[0].front().y, 0.0f);
  EXPECT_LT(shortened.frames[0].back().y, line.back().y);
}

TEST(RefineKnots, TargetAtOrAboveTheInputReturnsTheInput) {
  Rng rng(7);
  const KnotFrames input = randomFrames(rng, 10, 3);
  const std::vector<float> widths(10, 0.01f);
  for (const int target : {10, 11, 1000}) {
    RefineOptions options;
    options.knots = target;
    const RefineResult r = refineKnots(input, widths, options);
    EXPECT_EQ(r.frames, input);
    EXPECT_EQ(r.widths, widths);
    EXPECT_EQ(r.merged, std::vector<int>(10, 1));
  }
}

TEST(RefineKnots, RejectsInvalidInputWithMessages) {
  const KnotFrames good{straightBlade(4, 0.01f), straightBlade(4, 0.01f)};
  const RefineOptions defaults;
  using Refiner = RefineResult (*)(const KnotFrames&, std::span<const float>, const RefineOptions&);
  for (const Refiner refine : {Refiner{&refineKnots}, Refiner{&refineKnotsReference}}) {
    expectError([&] { (void)refine({}, {}, defaults); }, "refine: no frames");
    expectError([&] { (void)refine({straightBlade(1, 0.01f)}, {}, defaults); }, "1 knots; at least 2");
    expectError(
        [&] {
          (void)refine({straightBlade(4, 0.01f), straightBlade(3, 0.01f)}, {}, defaults);
        },
        "frame 1 has 3 knots, frame 0 has 4");
    KnotFrames nan = good;
    nan[1][2].y = std::numeric_limits<float>::quiet_NaN();
    expectError([&] { (void)refine(nan, {}, defaults); }, "frame 1, knot 2: position is not finite");
    RefineOptions options;
    options.knots = 1;
    expectError([&] { (void)refine(good, {}, options); }, "cannot refine to 1 knots");
    options = {};
    options.mu = -0.1;
    expectError([&] { (void)refine(good, {}, options); }, "mu = -0.1 is outside [0, 1]");
    options.mu = std::numeric_limits<double>::quiet_NaN();
    expectError([&] { (void)refine(good, {}, options); }, "is outside [0, 1]");
    const std::vector<float> three(3, 0.01f);
    expectError([&] { (void)refine(good, three, defaults); }, "3 widths for 4 knots");
    const std::vector<float> negative{0.01f, -0.01f, 0.01f, 0.01f};
    expectError([&] { (void)refine(good, negative, defaults); }, "width 1 is -0.01");
  }
}

/** Input knots per output knot, averaged over the output knots of the root half and of the tip half. */
struct HalfSpacing {
  int rootKnots = 0;
  int tipKnots = 0;
  double root = 0.0;
  double tip = 0.0;
};
HalfSpacing halfSpacing(const RefineResult& r, double inputKnots) {
  HalfSpacing h;
  int start = 0;
  for (const int m : r.merged) {
    const double centre = start + 0.5 * (m - 1);
    if (centre < 0.5 * (inputKnots - 1)) {
      h.root += m;
      ++h.rootKnots;
    } else {
      h.tip += m;
      ++h.tipKnots;
    }
    start += m;
  }
  h.root /= std::max(h.rootKnots, 1);
  h.tip /= std::max(h.tipKnots, 1);
  return h;
}

TEST(RefineKnots, SwayingBladeKeepsMoreKnotsWhereItMoves) {
  // A straight blade of 128 knots 1/512 m apart (exact in float, so a still blade ties exactly) swaying about
  // X. Adjacent knots keep their distance (segments are rigid): only merged knots' distances vary, with the
  // bend, which grows towards the tip. D's variance is in m² against metres for the distance, so at blade
  // scale motion only shows with μ near 0; refined by it alone, the still base is merged first.
  const std::vector<glm::vec3> rest = straightBlade(128, 1.0f / 512.0f);
  const KnotFrames moving = swayFrames(rest, {1.0f, 0.0f, 0.0f}, SwayOptions{});
  RefineOptions options;
  options.knots = 16;
  options.mu = 0.0;
  const RefineResult swayed = refineKnots(moving, {}, options);
  expectIdentical(swayed, refineKnotsReference(moving, {}, options));
  // The still blade refined by distance (its variance is 0 everywhere) comes out evenly spaced.
  options.mu = 1.0;
  const RefineResult still = refineKnots({rest}, {}, options);

  const HalfSpacing s = halfSpacing(swayed, 128);
  const HalfSpacing e = halfSpacing(still, 128);
  EXPECT_EQ(e.tipKnots, 8);
  EXPECT_NEAR(e.root / e.tip, 1.0, 0.1) << "a still, evenly spaced blade refines evenly";
  EXPECT_GE(s.tipKnots, 10) << "the moving tip half keeps more knots";
  EXPECT_GT(s.root / s.tip, 1.5) << "spacing in the moving half is smaller";
  // Not the degenerate answer of a variance that is always 0 (every tie merged into the root).
  EXPECT_GE(s.tip, 3.0);
  EXPECT_LE(*std::max_element(swayed.merged.begin(), swayed.merged.end()), 40);
}

TEST(RefineSway, RootStaysLengthsArePreservedAndTheTipMovesMost) {
  std::vector<glm::vec3> rest;
  for (int k = 0; k < 32; ++k) {
    const float s = static_cast<float>(k) / 31.0f;
    rest.emplace_back(0.01f * s * s, 0.25f * s, 0.002f * s); // slightly curved
  }
  SwayOptions options;
  options.frames = 90;
  const KnotFrames frames = swayFrames(rest, {2.0f, 0.0f, 0.0f}, options); // axis normalised
  ASSERT_EQ(frames.size(), 90u);
  std::vector<double> travel(rest.size(), 0.0);
  for (const auto& frame : frames) {
    ASSERT_EQ(frame.size(), rest.size());
    EXPECT_EQ(frame[0], rest[0]);
    for (std::size_t k = 0; k + 1 < rest.size(); ++k) {
      EXPECT_NEAR(glm::length(frame[k + 1] - frame[k]), glm::length(rest[k + 1] - rest[k]), 1e-6f) << k;
      // Rotation about X: x stays.
      EXPECT_NEAR(frame[k + 1].x, rest[k + 1].x, 1e-6f);
    }
    for (std::size_t k = 0; k < rest.size(); ++k) {
      travel[k] = std::max(travel[k], static_cast<double>(glm::length(frame[k] - rest[k])));
    }
  }
  for (std::size_t k = 1; k < rest.size(); ++k) {
    EXPECT_GE(travel[k], travel[k - 1]) << "displacement grows towards the tip, knot " << k;
  }
  EXPECT_GT(travel.back(), 0.03);
  EXPECT_LT(travel[3], 0.01 * travel.back());
}

TEST(RefineSway, DeterministicForASeedAndTurbulentAcrossSeeds) {
  const std::vector<glm::vec3> rest = straightBlade(16, 0.02f);
  SwayOptions options;
  options.seed = 42;
  const KnotFrames a = swayFrames(rest, {1, 0, 0}, options);
  const KnotFrames b = swayFrames(rest, {1, 0, 0}, options);
  EXPECT_EQ(a, b);
  options.seed = 43;
  EXPECT_NE(swayFrames(rest, {1, 0, 0}, options), a);
}

TEST(RefineSway, RejectsInvalidInput) {
  const std::vector<glm::vec3> rest = straightBlade(4, 0.02f);
  SwayOptions options;
  expectError([&] { (void)swayFrames(straightBlade(1, 0.02f), {1, 0, 0}, options); }, "at least 2");
  expectError([&] { (void)swayFrames(straightBlade(4, 0.0f), {1, 0, 0}, options); }, "zero length");
  expectError([&] { (void)swayFrames(rest, {0, 0, 0}, options); }, "bend axis");
  std::vector<glm::vec3> nan = rest;
  nan[2].z = std::numeric_limits<float>::infinity();
  expectError([&] { (void)swayFrames(nan, {1, 0, 0}, options); }, "knot 2: position is not finite");
  options.frames = 0;
  expectError([&] { (void)swayFrames(rest, {1, 0, 0}, options); }, "0 frames");
  options = {};
  options.fps = 0.0;
  expectError([&] { (void)swayFrames(rest, {1, 0, 0}, options); }, "fps = 0");
}

} // namespace
} // namespace sylva::capture
