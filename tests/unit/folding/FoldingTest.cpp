// Folding textures on the CPU: the equations of docs/folding.md checked against their definitions.
#include <sylva/core/Error.hpp>
#include <sylva/core/Files.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/folding/Edit.hpp>
#include <sylva/folding/Field.hpp>
#include <sylva/folding/Renderer.hpp>
#include <sylva/folding/Synthesis.hpp>

#include "Patterns.hpp"
#include "TempDir.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

namespace sylva::folding {
namespace {

using nlohmann::json;

Image pattern(int w, int h) {
  return test::patternImage(w, h, false);
}

std::array<std::uint8_t, 4> pixel(const Image& img, int x, int y) {
  const auto* d =
      reinterpret_cast<const std::uint8_t*>(img.data()) + (static_cast<std::size_t>(y) * img.width() + x) * 4;
  return {d[0], d[1], d[2], d[3]};
}

int maxDifference(const Image& a, const Image& b) {
  EXPECT_EQ(a.width(), b.width());
  EXPECT_EQ(a.height(), b.height());
  const auto* p = reinterpret_cast<const std::uint8_t*>(a.data());
  const auto* q = reinterpret_cast<const std::uint8_t*>(b.data());
  int m = 0;
  for (std::size_t i = 0; i < a.byteSize(); ++i) {
    m = std::max(m, std::abs(int(p[i]) - int(q[i])));
  }
  return m;
}

/** A project JSON over one image "img" of the given size, with one zone (filled in by the caller). */
json baseProject(const json& zone, const json& fn = {{"type", "linear"}, {"slope", 2.0}}) {
  return {{"format", "sylva-fold"},
          {"version", 1},
          {"seed", 3},
          {"atlas", {{"gutter_px", 4}, {"images", {{{"id", "img"}, {"file", "img.png"}}}}}},
          {"profiles", {{{"id", "p"}, {"period_s", 2.0}, {"fn", fn}}}},
          {"zones", zone.is_null() ? json::array() : json::array({zone})}};
}

struct Fixture {
  Project project;
  ProjectImages images;
};

Fixture make(const json& j, std::vector<Image> imgs) {
  Fixture f;
  f.project = parseProject(j, "test.json");
  f.images.images = std::move(imgs);
  std::vector<glm::ivec2> sizes;
  for (const Image& i : f.images.images) {
    sizes.emplace_back(i.width(), i.height());
  }
  validateAgainstImages(f.project, sizes, "test.json");
  f.images.freezeMasks.resize(f.project.zones.size());
  f.images.foldMasks.resize(f.project.zones.size());
  return f;
}

std::string errorOf(const json& j) {
  try {
    parseProject(j, "bad.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// ---------------------------------------------------------------------------------------------------------

TEST(FoldingFunctions, EndpointsAndShapes) {
  PositionFunction fn;
  for (auto type : {PositionFunction::Type::Linear, PositionFunction::Type::Exponential,
                    PositionFunction::Type::Sigmoid}) {
    fn.type = type;
    EXPECT_NEAR(fn.evaluate(0.0), 0.0, 1e-12);
    EXPECT_NEAR(fn.evaluate(1.0), 1.0, 1e-12);
    for (double phi = 0.0; phi < 1.0; phi += 0.01) {
      EXPECT_LE(fn.evaluate(phi), fn.evaluate(phi + 0.01) + 1e-12) << "monotone";
    }
  }
  fn.type = PositionFunction::Type::Exponential;
  fn.k = 1e-9;
  EXPECT_DOUBLE_EQ(fn.evaluate(0.3), 0.3); // k → 0 gives φ
  fn.type = PositionFunction::Type::Linear;
  fn.slope = 2.0;
  fn.delay = 0.25; // temporal shift: nothing moves before φ = 0.25
  EXPECT_EQ(fn.evaluate(0.2), 0.0);
  EXPECT_DOUBLE_EQ(fn.evaluate(0.5), 0.5);
  fn.type = PositionFunction::Type::Piecewise;
  fn.knots = {{0, 0}, {0.3, 1}, {0.5, 1}, {0.8, 0}, {1, 0}};
  EXPECT_DOUBLE_EQ(fn.evaluate(0.15), 0.5);
  EXPECT_DOUBLE_EQ(fn.evaluate(0.4), 1.0); // a flat segment holds (a closed eye)
  EXPECT_DOUBLE_EQ(fn.evaluate(0.65), 0.5);
  fn.type = PositionFunction::Type::Sine;
  EXPECT_NEAR(fn.evaluate(0.0), 0.0, 1e-12);
  EXPECT_NEAR(fn.evaluate(0.5), 1.0, 1e-12);
  EXPECT_NEAR(fn.evaluate(1.0), 0.0, 1e-12); // integer frequency: seamless
}

TEST(FoldingFunctions, LoopsAreSeamless) {
  Profile p;
  p.periodS = 1.5;
  p.fn.type = PositionFunction::Type::Linear; // one-way: p(0) = 0, p(1⁻) = 1
  p.loop = LoopMode::PingPong;
  EXPECT_NEAR(progressAt(p, 0.0, 0.0), progressAt(p, 1.5 - 1e-7, 0.0), 1e-5);
  EXPECT_NEAR(progressAt(p, 0.75, 0.0), 1.0, 1e-6); // the turn at half period
  p.loop = LoopMode::Crossfade;
  const CrossfadePhases a = crossfadePhases(p, 0.0, 0.0);
  const CrossfadePhases b = crossfadePhases(p, 1.5 - 1e-6, 0.0);
  EXPECT_NEAR(a.w, 0.0, 1e-5);
  EXPECT_NEAR(b.w, 0.0, 1e-5); // the weight is 0 at both ends, so only the second phase shows at the seam
  EXPECT_NEAR(a.s2, b.s2, 1e-5);
}

TEST(FoldingFunctions, ProfilesOfDifferentPeriodsLoopAtTheirCommonMultiple) {
  const auto periods = [](std::initializer_list<double> list) {
    std::vector<Profile> profiles;
    for (double s : list) {
      profiles.emplace_back().periodS = s;
    }
    return loopPeriod(profiles);
  };
  EXPECT_EQ(periods({}).seconds, 1.0);
  EXPECT_EQ(periods({2.0}).seconds, 2.0);
  EXPECT_EQ(periods({4.0, 3.0}).seconds, 12.0);             // the blink and a 3 s template
  EXPECT_DOUBLE_EQ(periods({1.5, 4.0, 3.0}).seconds, 12.0); // every built-in template period
  EXPECT_DOUBLE_EQ(periods({0.3, 0.4}).seconds, 1.2);       // decimal periods, to 1e-6
  EXPECT_EQ(periods({100.0}).seconds, 100.0);               // one long period is its own loop
  const LoopPeriod none = periods({3.0, 4.1});              // 123 s: beyond the limits
  EXPECT_FALSE(none.seamless);
  EXPECT_EQ(none.seconds, 4.1);
  // Where it is seamless, every profile is at its start again: the frame at the loop is the frame at 0.
  std::vector<Profile> profiles(2);
  profiles[0].periodS = 0.3;
  profiles[1].periodS = 0.4;
  const double loop = loopPeriod(profiles).seconds;
  for (Profile& p : profiles) {
    p.fn.type = PositionFunction::Type::Linear;
    EXPECT_NEAR(progressAt(p, loop, 0.0), progressAt(p, 0.0, 0.0), 1e-5);
    EXPECT_NEAR(progressAt(p, loop + 0.05, 0.0), progressAt(p, 0.05, 0.0), 1e-5);
  }
}

// ---------------------------------------------------------------------------------------------------------

TEST(FoldingInterpolation, ExactAtAnchorsAndPartitionOfUnity) {
  Rng rng(11);
  std::vector<Anchor> anchors;
  std::vector<Anchor> constant;
  for (int i = 0; i < 200; ++i) {
    const Vec2 p(rng.uniform(0, 256), rng.uniform(0, 256));
    anchors.push_back({p, Vec2(rng.uniform(-20, 20), rng.uniform(-20, 20))});
    constant.push_back({p, Vec2(3.25, -1.5)});
  }
  for (auto type : {Interpolation::Type::Shepard, Interpolation::Type::ModifiedShepard,
                    Interpolation::Type::ModifiedShepardRandom}) {
    Interpolation interp;
    interp.type = type;
    interp.radius = 48.0;
    interp.ring = 12.0;
    const AnchorField field(anchors, interp, 5);
    for (const Anchor& a : anchors) {
      const Vec2 v = field.evaluate(a.position, 0);
      EXPECT_NEAR(v.x, a.vector.x, 1e-6);
      EXPECT_NEAR(v.y, a.vector.y, 1e-6);
    }
    const AnchorField flat(constant, interp, 5);
    for (int i = 0; i < 500; ++i) {
      const Vec2 x(rng.uniform(0, 256), rng.uniform(0, 256));
      const Vec2 v = flat.evaluate(x, static_cast<std::uint64_t>(i));
      if (v == Vec2(0.0)) {
        continue; // modified variants: no anchor within R gives 0
      }
      EXPECT_NEAR(v.x, 3.25, 1e-6);
      EXPECT_NEAR(v.y, -1.5, 1e-6);
    }
  }
}

TEST(FoldingInterpolation, ModifiedShepardIsLocalAndGridMatchesBruteForce) {
  Rng rng(3);
  std::vector<Anchor> anchors;
  for (int i = 0; i < 400; ++i) {
    anchors.push_back(
        {Vec2(rng.uniform(0, 512), rng.uniform(0, 512)), Vec2(rng.uniform(-9, 9), rng.uniform(-9, 9))});
  }
  Interpolation interp;
  interp.radius = 40.0;
  const AnchorField field(anchors, interp, 1);
  for (int i = 0; i < 300; ++i) {
    const Vec2 x(rng.uniform(0, 512), rng.uniform(0, 512));
    Vec2 sum(0.0);
    double weights = 0.0;
    for (const Anchor& a : anchors) {
      const double d = glm::length(x - a.position);
      if (d < interp.radius) {
        const double w = std::pow((interp.radius - d) / (interp.radius * d), 2.0);
        sum += w * a.vector;
        weights += w;
      }
    }
    const Vec2 expected = weights > 0 ? sum / weights : Vec2(0.0);
    const Vec2 v = field.evaluate(x, 0);
    EXPECT_NEAR(v.x, expected.x, 1e-9);
    EXPECT_NEAR(v.y, expected.y, 1e-9);
  }
}

TEST(FoldingInterpolation, RandomRingIsSeededAndDeterministic) {
  std::vector<Anchor> anchors{{Vec2(10, 10), Vec2(5, 0)}, {Vec2(60, 10), Vec2(-5, 0)}};
  Interpolation interp;
  interp.type = Interpolation::Type::ModifiedShepardRandom;
  interp.radius = 40.0;
  interp.ring = 20.0;
  const AnchorField a(anchors, interp, 1);
  const AnchorField b(anchors, interp, 1);
  const AnchorField c(anchors, interp, 2);
  int differ = 0;
  for (int i = 0; i < 200; ++i) {
    const Vec2 x(35.0 + 0.1 * i, 10.0 + 0.05 * i);
    EXPECT_EQ(a.evaluate(x, i), b.evaluate(x, i));
    differ += a.evaluate(x, i) != c.evaluate(x, i);
  }
  EXPECT_GT(differ, 0) << "another seed must change the ring";
  for (std::uint64_t i = 0; i < 1000; ++i) {
    const double h = ringHash(i, 3, 9);
    EXPECT_GE(h, 0.0);
    EXPECT_LT(h, 1.0);
  }
}

TEST(FoldingInterpolation, MeanValueCoordinatesReproduceLinearFunctions) {
  // A non-convex (L-shaped) polygon: MVC still reproduce linear functions and interpolate on the boundary.
  const std::vector<Vec2> poly{{0, 0}, {40, 0}, {40, 10}, {10, 10}, {10, 40}, {0, 40}};
  for (const Vec2 p : {Vec2(5, 5), Vec2(30, 5), Vec2(5, 30), Vec2(9.9, 9.9), Vec2(20, 0), Vec2(40, 10)}) {
    const std::vector<double> l = meanValueCoordinates(poly, p);
    Vec2 sum(0.0);
    double total = 0.0;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      sum += l[i] * poly[i];
      total += l[i];
    }
    EXPECT_NEAR(total, 1.0, 1e-9);
    EXPECT_NEAR(sum.x, p.x, 1e-9);
    EXPECT_NEAR(sum.y, p.y, 1e-9);
  }
}

TEST(FoldingInterpolation, CurveSamplesAreArcLengthUniform) {
  const std::array<Vec2, 4> c{Vec2(0, 0), Vec2(10, 60), Vec2(90, -40), Vec2(100, 0)};
  const std::vector<double> u = arcLengthParameters(c, 11);
  ASSERT_EQ(u.size(), 11u);
  std::vector<double> gaps;
  for (std::size_t i = 1; i < u.size(); ++i) {
    double len = 0.0;
    for (int k = 0; k < 200; ++k) {
      len += glm::length(bezier(c, u[i - 1] + (u[i] - u[i - 1]) * (k + 1) / 200.0) -
                         bezier(c, u[i - 1] + (u[i] - u[i - 1]) * k / 200.0));
    }
    gaps.push_back(len);
  }
  for (double g : gaps) {
    EXPECT_NEAR(g, gaps[0], 0.02 * gaps[0]);
  }
}

// ---------------------------------------------------------------------------------------------------------

TEST(FoldingThresholds, PolygonIntervalsMatchABruteForceMarch) {
  Rng rng(21);
  // A star: non-convex, so paths enter and leave several times.
  std::vector<Vec2> star;
  for (int i = 0; i < 64; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / 64;
    const double r = i % 2 ? 18.0 : 40.0;
    star.emplace_back(50 + r * std::cos(a), 50 + r * std::sin(a));
  }
  const std::vector<std::vector<Vec2>> polys{star, {{80, 80}, {95, 82}, {90, 96}}};
  int multi = 0;
  for (int trial = 0; trial < 250; ++trial) {
    const Vec2 q(rng.uniform(0, 100), rng.uniform(0, 100));
    const Vec2 j(rng.uniform(-80, 80), rng.uniform(-80, 80));
    const std::vector<Interval> intervals = foldIntervals(polys, q, j);
    multi += intervals.size() > 1;
    constexpr int kSteps = 20000;
    std::vector<Interval> brute;
    bool prev = false;
    for (int i = 0; i <= kSteps; ++i) {
      const double s = static_cast<double>(i) / kSteps;
      const Vec2 p = q + s * j;
      const bool in = insidePolygon(polys[0], p) || insidePolygon(polys[1], p);
      if (in && !prev) {
        brute.push_back({s, 1.0});
      }
      if (!in && prev) {
        brute.back().t1 = s;
      }
      prev = in;
    }
    ASSERT_EQ(intervals.size(), brute.size()) << "trial " << trial;
    for (std::size_t k = 0; k < brute.size(); ++k) {
      EXPECT_NEAR(intervals[k].t0, brute[k].t0, 1e-3);
      EXPECT_NEAR(intervals[k].t1, brute[k].t1, 1e-3);
    }
  }
  EXPECT_GT(multi, 10) << "the star must produce several intervals per path";
}

TEST(FoldingThresholds, MaskMarchAgreesWithPolygon) {
  const int w = 64;
  std::vector<float> mask(w * w, 0.0f);
  const std::vector<Vec2> square{{20, 20}, {44, 20}, {44, 44}, {20, 44}};
  for (int y = 0; y < w; ++y) {
    for (int x = 0; x < w; ++x) {
      mask[y * w + x] = insidePolygon(square, Vec2(x + 0.5, y + 0.5)) ? 1.0f : 0.0f;
    }
  }
  const std::vector<std::vector<Vec2>> polys{square};
  for (const auto& [q, j] :
       {std::pair{Vec2(10.5, 30.5), Vec2(40, 0)}, std::pair{Vec2(30.5, 30.5), Vec2(0, -25)},
        std::pair{Vec2(5.5, 5.5), Vec2(50, 50)}}) {
    const auto exact = foldIntervals(polys, q, j);
    const auto marched = foldIntervalsFromMask(mask, w, w, q, j);
    ASSERT_EQ(exact.size(), marched.size());
    for (std::size_t k = 0; k < exact.size(); ++k) {
      EXPECT_NEAR(exact[k].t0, marched[k].t0, 1.0 / glm::length(j) + 1e-9);
      EXPECT_NEAR(exact[k].t1, marched[k].t1, 1.0 / glm::length(j) + 1e-9);
    }
  }
}

TEST(FoldingThresholds, PolygonChecks) {
  const std::vector<Vec2> bowtie{{0, 0}, {10, 10}, {10, 0}, {0, 10}};
  EXPECT_TRUE(selfIntersects(bowtie));
  const std::vector<Vec2> square{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  EXPECT_FALSE(selfIntersects(square));
  EXPECT_DOUBLE_EQ(std::abs(signedArea(square)), 100.0);
}

// ---------------------------------------------------------------------------------------------------------

TEST(FoldingSynthesis, TranslateZoneShiftsPixelsExactly) {
  const json zone = {{"id", "z"},
                     {"image", "img"},
                     {"shape", {{"type", "rect"}, {"min", {8, 8}}, {"max", {56, 40}}}},
                     {"profile", "p"},
                     {"tools", {{{"type", "translate"}, {"v", {3, -2}}}}}};
  Fixture f = make(baseProject(zone), {pattern(64, 48)});
  const Textures tex = synthesize(f.project, f.images);
  // linear slope 2: s = 1 for φ ≥ ½ → t = 1.5 s of a 2 s period.
  const Image frame = renderFrame(tex, f.project.profiles, f.project.jumpLayers, 1.5);
  const Image input = cropToEntry(tex.atlas.color, tex.atlas.entries[0]);
  const Image shown = cropToEntry(frame, tex.atlas.entries[0]);
  for (int y = 8; y < 40; ++y) {
    for (int x = 8; x < 56; ++x) {
      ASSERT_EQ(pixel(shown, x, y), pixel(input, x - 3, y + 2)) << x << "," << y;
    }
  }
  EXPECT_EQ(pixel(shown, 2, 2), pixel(input, 2, 2)) << "outside the zone nothing moves";
}

// The class: a translate whose own zone_boundary zero anchors reach every texel (R at least the zone's depth)
// is cancelled everywhere; tools that undo each other leave a zone still. Both are named, with what to
// change; with R below the depth the same zone moves by its translate in the middle and says nothing.
TEST(FoldingSynthesis, ZonesWhoseSettingsCancelTheirMotionAreNamed) {
  const auto run = [](double radius, const json& tools) {
    json zone = {{"id", "eye"},
                 {"image", "img"},
                 {"shape", {{"type", "rect"}, {"min", {8, 8}}, {"max", {56, 40}}}}, // 48x32: 16 px deep
                 {"profile", "p"},
                 {"zero_anchors", "zone_boundary"},
                 {"interp", {{"type", "modified_shepard"}, {"R", radius}}},
                 {"tools", tools}};
    Fixture f = make(baseProject(zone), {pattern(64, 48)});
    SynthesisStats stats;
    (void)synthesize(f.project, f.images, nullptr, &stats);
    return std::pair{stats.zoneJumpMax.at(0), stillZoneWarnings(f.project, stats)};
  };
  const json translate = {{{"type", "translate"}, {"v", {0, 6}}}};
  const auto [cancelledJump, cancelled] = run(40.0, translate);
  EXPECT_LT(cancelledJump, kStillZonePx);
  ASSERT_EQ(cancelled.size(), 1u);
  EXPECT_THAT(cancelled[0], ::testing::HasSubstr("/zones/0 ('eye')"));
  EXPECT_THAT(cancelled[0], ::testing::HasSubstr("R = 40"));
  EXPECT_THAT(cancelled[0], ::testing::HasSubstr("give R below 15 px"));
  const auto [movingJump, moving] = run(12.0, translate);
  EXPECT_NEAR(movingJump, 6.0, 1e-6);
  EXPECT_TRUE(moving.empty()) << moving.front();
  // Points that go nowhere: tools, but no motion.
  const auto [stillJump, still] = run(12.0, json{{{"type", "points"}, {"pairs", {{{30, 20}, {30, 20}}}}}});
  EXPECT_EQ(stillJump, 0.0);
  ASSERT_EQ(still.size(), 1u);
  EXPECT_THAT(still[0], ::testing::HasSubstr("cancel out"));
}

TEST(FoldingSynthesis, ScaleMatchesTheAnalyticField) {
  const json zone = {{"id", "z"},
                     {"image", "img"},
                     {"shape", {{"type", "polygon"}, {"pts", {{4, 4}, {60, 6}, {58, 44}, {6, 40}}}}},
                     {"profile", "p"},
                     {"tools", {{{"type", "scale"}, {"factor", 1.5}, {"centre", {30, 22}}}}}};
  Fixture f = make(baseProject(zone), {pattern(64, 48)});
  const Textures tex = synthesize(f.project, f.images);
  const glm::ivec2 o = tex.atlas.entries[0].origin();
  const std::span<const float> jump = tex.jump[0].values<float>();
  const std::span<const float> init = tex.init.values<float>();
  int inside = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const std::size_t i = (static_cast<std::size_t>(y + o.y) * tex.width() + x + o.x) * 4;
      if (init[i + 3] < 0.0f) {
        continue;
      }
      ++inside;
      const Vec2 expected = (Vec2(x + 0.5, y + 0.5) - Vec2(30, 22)) * (1.0 / 1.5 - 1.0);
      EXPECT_NEAR(jump[i], expected.x, 1e-4);
      EXPECT_NEAR(jump[i + 1], expected.y, 1e-4);
      EXPECT_EQ(init[i], static_cast<float>(x + o.x));
    }
  }
  EXPECT_GT(inside, 1500);
}

TEST(FoldingSynthesis, FeatherFadesTheJumpInFromTheZoneBorder) {
  const json zone = {{"id", "z"},
                     {"image", "img"},
                     {"shape", {{"type", "rect"}, {"min", {8, 8}}, {"max", {56, 40}}}},
                     {"profile", "p"},
                     {"feather_px", 6.0},
                     {"tools", {{{"type", "translate"}, {"v", {3, -2}}}}}};
  Fixture f = make(baseProject(zone), {pattern(64, 48)});
  const Textures tex = synthesize(f.project, f.images);
  const glm::ivec2 o = tex.atlas.entries[0].origin();
  const std::span<const float> jump = tex.jump[0].values<float>();
  auto jx = [&](int x, int y) {
    return jump[(static_cast<std::size_t>(y + o.y) * tex.width() + x + o.x) * 4];
  };
  EXPECT_FLOAT_EQ(jx(30, 24), -3.0f) << "deeper than the feather: the full translate";
  const double d = 0.5 / 6.0; // texel (8, 24): its centre is ½ px inside the border
  EXPECT_NEAR(jx(8, 24), -3.0 * d * d * (3.0 - 2.0 * d), 1e-6);
  EXPECT_LT(std::abs(jx(9, 24)), std::abs(jx(12, 24)));
  EXPECT_LT(std::abs(jx(12, 24)), 3.0f);
  // The project round-trips the field.
  EXPECT_EQ(parseProject(toJson(f.project), "f.json").zones[0].feather, 6.0);
}

TEST(FoldingSynthesis, AnAtlasTooLargeForTheRenderersIsAnError) {
  Fixture f = make(baseProject(nullptr), {Image(kMaxAtlasSide + 1, 2, 4, PixelType::U8)});
  try {
    (void)synthesize(f.project, f.images);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("atlas: packing needs 16385×2 texels, more than the 16384"));
  }
}

json richZone() {
  return {{"id", "z"},
          {"image", "img"},
          {"shape", {{"type", "polygon"}, {"pts", {{4, 4}, {92, 6}, {90, 60}, {6, 58}}}}},
          {"profile", "p"},
          {"interp", {{"type", "modified_shepard_random"}, {"R", 30}, {"ring", 8}}},
          {"zero_anchors", "zone_boundary"},
          {"tools",
           {{{"type", "points"}, {"pairs", {{{40, 20}, {46, 28}}, {{60, 40}, {55, 44}}}}},
            {{"type", "curve"},
             {"source", {{20, 50}, {30, 40}, {50, 40}, {70, 50}}},
             {"vectors", {{0, {0, -4}}, {1, {2, -6}}}}},
            {{"type", "lasso"},
             {"from", {{70, 10}, {85, 12}, {80, 25}}},
             {"to", {{72, 14}, {86, 16}, {82, 28}}}}}},
          {"folding", {{"type", "polygon"}, {"pts", {{30, 24}, {60, 22}, {62, 40}, {45, 30}, {28, 40}}}}}};
}

TEST(FoldingSynthesis, DeterministicAndTheZeroFrameIsTheInput) {
  Fixture f = make(baseProject(richZone()), {pattern(96, 64)});
  const Textures a = synthesize(f.project, f.images);
  const Textures b = synthesize(f.project, f.images);
  EXPECT_EQ(a.init, b.init);
  EXPECT_EQ(a.jump, b.jump);
  EXPECT_EQ(a.fold, b.fold);
  const Image f0 = renderFrame(a, f.project.profiles, f.project.jumpLayers, 0.0);
  EXPECT_EQ(f0, a.atlas.color) << "s = 0 must show the input bit-exactly";
  EXPECT_EQ(renderFrame(a, f.project.profiles, f.project.jumpLayers, 0.7),
            renderFrame(b, f.project.profiles, f.project.jumpLayers, 0.7, 2));
  test::TempDir dir;
  saveTextures(dir / "a", f.project, a);
  saveTextures(dir / "b", f.project, b);
  for (const char* name : {"color.png", "init.png", "jump.png", "folding.json"}) {
    EXPECT_EQ(readTextFile(dir / "a" / name), readTextFile(dir / "b" / name)) << name;
  }
  // Another seed changes the randomised ring, so the textures.
  json other = baseProject(richZone());
  other["seed"] = 4;
  Fixture g = make(other, {pattern(96, 64)});
  EXPECT_NE(synthesize(g.project, g.images).jump, a.jump);
}

TEST(FoldingSynthesis, LoopSeam) {
  json j = baseProject(richZone(), {{"type", "sine"}, {"frequency", 1}});
  Fixture f = make(j, {pattern(96, 64)});
  const Textures tex = synthesize(f.project, f.images);
  const Image a = renderFrame(tex, f.project.profiles, f.project.jumpLayers, 0.0);
  const Image b = renderFrame(tex, f.project.profiles, f.project.jumpLayers, 2.0);
  const Image c = renderFrame(tex, f.project.profiles, f.project.jumpLayers, 20.0);
  EXPECT_LE(maxDifference(a, b), 1);
  EXPECT_LE(maxDifference(a, c), 1);
  EXPECT_GT(maxDifference(a, renderFrame(tex, f.project.profiles, f.project.jumpLayers, 1.0)), 10)
      << "mid-cycle the image must have moved";
}

TEST(FoldingSynthesis, FoldHoldsColourUntilThePathEntersTheFoldingZone) {
  // Zone: translate down by 20 px; folding zone = the top band, so texels below read the band only once
  // their backward path reaches it: the band slides over the rest instead of squeezing it.
  const json zone = {{"id", "z"},
                     {"image", "img"},
                     {"shape", {{"type", "rect"}, {"min", {0, 0}}, {"max", {32, 48}}}},
                     {"profile", "p"},
                     {"tools", {{{"type", "translate"}, {"v", {0, 20}}}}},
                     {"folding", {{"type", "polygon"}, {"pts", {{0, 0}, {32, 0}, {32, 10}, {0, 10}}}}}};
  Fixture f = make(baseProject(zone, {{"type", "linear"}, {"slope", 1.0}}), {pattern(32, 48)});
  const Textures tex = synthesize(f.project, f.images);
  const glm::ivec2 o = tex.atlas.entries[0].origin();
  const std::span<const float> jump = tex.jump[0].values<float>();
  auto at = [&](int x, int y) { return (static_cast<std::size_t>(y + o.y) * tex.width() + x + o.x) * 4; };
  // Texel (5, 25.5): path y = 25.5 − 20 s enters the band (y < 10) at s = 0.775 and stays.
  EXPECT_NEAR(jump[at(5, 25) + 2], 0.775, 1e-6);
  EXPECT_NEAR(jump[at(5, 25) + 3], 1.0, 1e-6);
  // Texel (5, 40.5) never reaches the band: it never changes.
  EXPECT_GE(jump[at(5, 40) + 2], jump[at(5, 40) + 3]);
  const Image input = cropToEntry(tex.atlas.color, tex.atlas.entries[0]);
  const Image early =
      cropToEntry(renderFrame(tex, f.project.profiles, f.project.jumpLayers, 1.4), tex.atlas.entries[0]);
  EXPECT_EQ(pixel(early, 5, 25), pixel(input, 5, 25)) << "s = 0.7: colour held";
  const Image late =
      cropToEntry(renderFrame(tex, f.project.profiles, f.project.jumpLayers, 1.9), tex.atlas.entries[0]);
  EXPECT_EQ(pixel(late, 5, 25), pixel(input, 5, 6)) << "s = 0.95: reads the band 19 px up";
  EXPECT_EQ(pixel(late, 5, 40), pixel(input, 5, 40));
}

TEST(FoldingSynthesis, RegionResynthesisEqualsAFullSynthesis) {
  json j = baseProject(richZone());
  j["zones"][0]["interp"] = {{"type", "modified_shepard"}, {"R", 20}};
  Fixture f = make(j, {pattern(96, 64)});
  Textures tex = synthesize(f.project, f.images);
  EditHistory history(f.project);
  movePointAnchor(history, 0, 0, 0, 1, Vec2(50, 30));
  const Project& moved = history.project();
  // The moved anchor influences texels within R of its old and new position.
  const glm::ivec2 o = tex.atlas.entries[0].origin();
  const Rect region{o + glm::ivec2(46 - 21, 28 - 21), o + glm::ivec2(50 + 21, 30 + 21)};
  resynthesize(moved, f.images, tex, region);
  const Textures full = synthesize(moved, f.images);
  EXPECT_EQ(tex.init, full.init);
  EXPECT_EQ(tex.jump, full.jump);
}

TEST(FoldingSynthesis, MultiJumpLayersChainTheirPaths) {
  json j = baseProject(nullptr, {{"type", "linear"}, {"slope", 1.0}});
  j["jump_layers"] = {0.0, 0.5, 1.0};
  j["zones"] = {{{"id", "a"},
                 {"image", "img"},
                 {"shape", {{"type", "rect"}, {"min", {0, 0}}, {"max", {40, 40}}}},
                 {"profile", "p"},
                 {"layer", 0},
                 {"tools", {{{"type", "translate"}, {"v", {4, 0}}}}}},
                {{"id", "b"},
                 {"image", "img"},
                 {"shape", {{"type", "rect"}, {"min", {0, 0}}, {"max", {40, 40}}}},
                 {"profile", "p"},
                 {"layer", 1},
                 {"tools", {{{"type", "translate"}, {"v", {0, 6}}}}}}};
  Fixture f = make(j, {pattern(40, 40)});
  const Textures tex = synthesize(f.project, f.images);
  ASSERT_EQ(tex.jump.size(), 2u);
  const Image input = cropToEntry(tex.atlas.color, tex.atlas.entries[0]);
  // t = 1 s: s = 0.5 (first leg done); t = 1.999 s: s ≈ 1 (both legs: −4 in x, −6 in y).
  const Image half =
      cropToEntry(renderFrame(tex, f.project.profiles, f.project.jumpLayers, 1.0), tex.atlas.entries[0]);
  EXPECT_EQ(pixel(half, 20, 20), pixel(input, 16, 20));
  const Image end =
      cropToEntry(renderFrame(tex, f.project.profiles, f.project.jumpLayers, 1.99999), tex.atlas.entries[0]);
  EXPECT_EQ(pixel(end, 20, 20), pixel(input, 16, 14));
}

TEST(FoldingSynthesis, AtlasPacksCropsWithGuttersAndPlacesFlyingObjects) {
  json j = baseProject(nullptr, {{"type", "linear"}, {"slope", 1.0}});
  j["atlas"]["images"] = {{{"id", "bg"}, {"file", "bg.png"}},
                          {{"id", "car"}, {"file", "car.png"}},
                          {{"id", "extra"}, {"file", "extra.png"}}};
  j["zones"] = {
      {{"id", "road"},
       {"image", "bg"},
       {"shape", {{"type", "rect"}, {"min", {0, 20}}, {"max", {80, 36}}}},
       {"profile", "p"},
       {"tools", {{{"type", "fly_over"}, {"object", "car"}, {"from", {-30, 24}}, {"to", {90, 24}}}}},
       {"folding", {{"type", "object"}}}},
      {{"id", "flag"},
       {"image", "extra"},
       {"shape", {{"type", "rect"}, {"min", {10, 10}}, {"max", {20, 20}}}},
       {"profile", "p"},
       {"tools", {{{"type", "translate"}, {"v", {2, 0}}}}}}};
  Image car = pattern(24, 10);
  Fixture f = make(j, {pattern(80, 60), car, pattern(200, 100)});
  const Atlas atlas = packAtlas(f.project, f.images);
  const AtlasEntry& bg = atlas.entries[0];
  const AtlasEntry& obj = atlas.entries[1];
  const AtlasEntry& extra = atlas.entries[2];
  EXPECT_EQ(bg.crop, (Rect{{0, 0}, {80, 60}})) << "the canvas is never cropped";
  EXPECT_EQ(obj.origin() - bg.origin(), glm::ivec2(-30, 24)) << "the object sits where it starts flying";
  EXPECT_LT(extra.crop.width(), 40) << "a zone-only image is cropped to what its zone reads";
  const std::vector<Rect> rects{bg.atlasRect(), obj.atlasRect(), extra.atlasRect()};
  for (std::size_t a = 0; a < rects.size(); ++a) {
    for (std::size_t b = a + 1; b < rects.size(); ++b) {
      const bool apart = rects[a].max.x + 4 <= rects[b].min.x || rects[b].max.x + 4 <= rects[a].min.x ||
                         rects[a].max.y + 4 <= rects[b].min.y || rects[b].max.y + 4 <= rects[a].min.y;
      EXPECT_TRUE(apart) << a << " and " << b << " closer than the gutter";
    }
  }
  // The car crosses the road: at s = 0.5 it is at x = 30, so road texel (40, 28) shows car pixel (10, 4).
  const Textures tex = synthesize(f.project, f.images);
  const Image frame = renderFrame(tex, f.project.profiles, f.project.jumpLayers, 1.0);
  EXPECT_EQ(pixel(cropToEntry(frame, bg), 40, 28), pixel(car, 10, 4));
  EXPECT_EQ(pixel(cropToEntry(frame, bg), 10, 28), pixel(f.images.images[0], 10, 28)) << "behind the car";
}

// ---------------------------------------------------------------------------------------------------------

TEST(FoldingEncoding, RoundTripWithinHalfAQuantum) {
  for (double j : {-37.5, -1.0, 0.0, 0.001, 12.25, 40.0}) {
    EXPECT_NEAR(decodeJump(encodeJump(j, 40.0), 40.0), j, 0.5 * 40.0 / 32767.0 + 1e-12);
  }
  EXPECT_EQ(decodeJump(encodeJump(0.0, 17.0), 17.0), 0.0) << "zero is exact";
  for (double t : {0.0, 0.1234567, 0.5, 1.0}) {
    EXPECT_NEAR(decodeUnit(encodeUnit(t)), t, 0.5 / 65535.0 + 1e-12);
  }
  Fixture f = make(baseProject(richZone()), {pattern(96, 64)});
  const Textures tex = synthesize(f.project, f.images);
  test::TempDir dir;
  saveTextures(dir.path(), f.project, tex);
  std::vector<Profile> profiles;
  std::vector<double> layers;
  const Textures back = loadTextures(dir.path(), &profiles, &layers);
  EXPECT_EQ(profiles, f.project.profiles);
  EXPECT_EQ(back.init.values<float>().size(), tex.init.values<float>().size());
  const double quantum = tex.jumpMax() / 32767.0;
  const auto a = tex.jump[0].values<float>();
  const auto b = back.jump[0].values<float>();
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_NEAR(a[i], b[i], (i % 4 < 2 ? 0.5 * quantum : 0.5 / 65535.0) + 1e-6) << i;
  }
  EXPECT_EQ(tex.init.values<float>()[0], back.init.values<float>()[0]);
  const Image fromPng = renderFrame(back, profiles, layers, 0.8);
  const Image fromFloat = renderFrame(tex, profiles, layers, 0.8);
  EXPECT_LE(maxDifference(fromPng, fromFloat), 2);
  // EXR keeps the floats as they are.
  f.project.outputs.encoding = Outputs::Encoding::Exr;
  f.project.outputs.init = "init.exr";
  f.project.outputs.jump = "jump.exr";
  saveTextures(dir / "exr", f.project, tex);
  EXPECT_EQ(loadTextures(dir / "exr").jump, tex.jump);
}

// ---------------------------------------------------------------------------------------------------------

TEST(FoldingProject, JsonRoundTrip) {
  json j = baseProject(richZone());
  j["jump_layers"] = {0.0, 0.4, 1.0};
  j["zones"][0]["layer"] = 1;
  j["zones"][0]["tools"].push_back({{"type", "zero"}, {"pts", {{10, 10}, {20, 30}}}});
  j["zones"][0]["tools"].push_back({{"type", "curve"},
                                    {"source", {{1, 1}, {2, 2}, {3, 3}, {4, 5}}},
                                    {"dest", {{1, 2}, {2, 3}, {3, 4}, {4, 6}}},
                                    {"samples", 8}});
  j["profiles"].push_back(
      {{"id", "q"}, {"fn", {{"type", "sigmoid"}, {"k", 8}, {"centre", 0.3}}}, {"loop", "crossfade"}});
  const Project p = parseProject(j, "a.json");
  const Project back = parseProject(toJson(p), "b.json");
  EXPECT_EQ(p, back);
  test::TempDir dir;
  saveProject(dir / "p.json", p);
  Project loaded = loadProject(dir / "p.json");
  loaded.baseDir.clear();
  EXPECT_EQ(loaded, p);
}

TEST(FoldingProject, RebasingKeepsEveryFileWhereverTheProjectGoes) {
  Project p;
  p.images.push_back({"a", "pic.png", true});
  p.images.push_back({"b", "/abs/pic.png", true});
  Zone z;
  z.freezeMask = "masks/freeze.png";
  p.zones.push_back(z);
  // Bare names where the project is the working directory (an empty baseDir once threw).
  const Project same = rebasedProject(p, "out.json");
  EXPECT_EQ(same.images[0].file, "pic.png");
  EXPECT_EQ(same.images[1].file, "/abs/pic.png");
  EXPECT_EQ(same.zones[0].freezeMask, "masks/freeze.png");
  const Project down = rebasedProject(p, "sub/dir/out.json");
  EXPECT_EQ(down.images[0].file, "../../pic.png");
  EXPECT_EQ(down.zones[0].freezeMask, "../../masks/freeze.png");
  EXPECT_EQ(down.baseDir, "sub/dir");
  p.baseDir = "projects";
  EXPECT_EQ(rebasedProject(p, "projects/copy.json").images[0].file, "pic.png");
  EXPECT_EQ(rebasedProject(p, "elsewhere/copy.json").images[0].file, "../projects/pic.png");
}

TEST(FoldingProject, BadInputNamesTheField) {
  const json good = baseProject(richZone());
  auto with = [&](const std::string& pointer, const json& value) {
    json j = good;
    j[json::json_pointer(pointer)] = value;
    return errorOf(j);
  };
  using ::testing::HasSubstr;
  EXPECT_THAT(with("/zones/0/colour", 1), HasSubstr("bad.json: /zones/0/colour: unknown field"));
  EXPECT_THAT(with("/version", 2), HasSubstr("newer than this sylva understands"));
  EXPECT_THAT(with("/zones/0/shape/pts/2", {1, "x"}), HasSubstr("/zones/0/shape/pts/2/1: expected a number"));
  EXPECT_THAT(with("/zones/0/shape/pts", {{0, 0}, {10, 10}, {10, 0}, {0, 10}}),
              HasSubstr("/zones/0/shape/pts: self-intersecting polygon"));
  EXPECT_THAT(with("/zones/0/shape/pts", {{0, 0}, {10, 10}, {20, 20}}), HasSubstr("degenerate polygon"));
  EXPECT_THAT(with("/zones/0/profile", "nope"), HasSubstr("/zones/0/profile: no profile with id 'nope'"));
  EXPECT_THAT(with("/zones/0/interp/ring", 40), HasSubstr("/zones/0/interp/ring: the ring must be narrower"));
  EXPECT_THAT(with("/profiles/0/period_s", 0), HasSubstr("/profiles/0/period_s"));
  EXPECT_THAT(
      with("/profiles/0/fn", json{{"type", "piecewise"}, {"knots", {{0, 0}, {0.5, 1}, {0.4, 1}, {1, 0}}}}),
      HasSubstr("/profiles/0/fn/knots/2: knot phases must increase"));
  EXPECT_THAT(with("/seed", -1), HasSubstr("seed: expected a non-negative integer"));
  EXPECT_THAT(with("/atlas/gutter_px", 1), HasSubstr("/atlas/gutter_px"));
  EXPECT_THAT(with("/zones/0/tools/0/pairs/0/1/0", 1e300 * 10), HasSubstr("/zones/0/tools/0/pairs/0/1/0"));
  EXPECT_THAT(with("/outputs", json{{"init", "../x.png"}}),
              HasSubstr("/outputs/init: must be a plain file name"));
  EXPECT_THAT(errorOf(json::parse("[1,2]")), HasSubstr("bad.json: /: expected an object, got array"));
  // Zones outside their image are caught once the image sizes are known.
  const Project p = parseProject(good, "bad.json");
  try {
    validateAgainstImages(p, {{50, 50}}, "bad.json");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("bad.json: /zones/0/shape/pts/1: (92, 6) lies outside image 'img' (50×50"));
  }
}

TEST(FoldingProject, NaNAndInfinityAreRefused) {
  // JSON text has no NaN literal and a number that overflows a double fails to parse; both are one line
  // naming the file. A NaN built in memory (e.g. by an editor) is refused by the validation.
  test::TempDir dir;
  std::ofstream(dir / "inf.json")
      << R"({"format":"sylva-fold","version":1,"atlas":{"images":[{"id":"a","file":"a.png"}]},
    "profiles":[{"id":"p","period_s":1e999}],"zones":[]})";
  try {
    loadProject(dir / "inf.json");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("inf.json"));
  }
  json j = baseProject(richZone());
  j["profiles"][0]["period_s"] = std::nan("");
  EXPECT_THAT(errorOf(j), ::testing::HasSubstr("/profiles/0/period_s: expected a finite number"));
  j = baseProject(richZone());
  j["zones"][0]["tools"][0]["pairs"][0][1][0] = std::numeric_limits<double>::infinity();
  EXPECT_THAT(errorOf(j), ::testing::HasSubstr("/zones/0/tools/0/pairs/0/1/0: expected a finite number"));
}

TEST(FoldingEdit, UndoRedoAndInvalidEditsChangeNothing) {
  const Project start = parseProject(baseProject(richZone()), "e.json");
  EditHistory history(start);
  setProfileTiming(history, 0, 3.0, 0.25);
  moveZoneVertex(history, 0, 1, Vec2(80, 5));
  EXPECT_EQ(history.project().profiles[0].periodS, 3.0);
  EXPECT_EQ(history.project().zones[0].shape.pts[1], Vec2(80, 5));
  // A vertex move that makes the polygon cross itself is refused and leaves the project as it was.
  const Project before = history.project();
  EXPECT_THROW(moveZoneVertex(history, 0, 1, Vec2(95, 70)), Error);
  EXPECT_EQ(history.project(), before);
  EXPECT_EQ(history.undoNames(), (std::vector<std::string>{"set profile timing", "move zone vertex"}));
  EXPECT_EQ(history.undo().zone, 0);
  EXPECT_EQ(history.undo().name, "set profile timing");
  EXPECT_EQ(history.project(), start);
  EXPECT_FALSE(history.canUndo());
  history.redo();
  history.redo();
  EXPECT_EQ(history.project(), before);
  addTool(history, 0, TranslateTool{Vec2(1, 1)});
  EXPECT_FALSE(history.canRedo()) << "a new edit clears the redo stack";
  removeTool(history, 0, static_cast<int>(history.project().zones[0].tools.size()) - 1);
  EXPECT_EQ(history.project(), before);
}

} // namespace
} // namespace sylva::folding
