#include <sylva/core/Error.hpp>
#include <sylva/scene/Quality.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace sylva::scene {
namespace {

/** Frame times of a scene whose cost falls by `gain` per step from `full` ms at step 0. */
std::vector<double> costs(double full, double gain) {
  std::vector<double> c;
  double ms = full;
  for (std::size_t i = 0; i < qualityLadder().size(); ++i) {
    c.push_back(ms);
    ms /= gain;
  }
  return c;
}

/** Runs `frames` frames of cost `cost[step]`; returns the steps drawn and counts the changes. */
std::vector<int> run(QualityGovernor& g, const std::vector<double>& cost, int frames,
                     int* changes = nullptr) {
  std::vector<int> steps;
  int previous = g.step();
  for (int f = 0; f < frames; ++f) {
    steps.push_back(g.step());
    const int next = g.update(cost[static_cast<std::size_t>(g.step())]);
    EXPECT_GE(next, 0);
    EXPECT_LT(next, static_cast<int>(g.steps()));
    if (changes != nullptr && next != previous) {
      ++*changes;
    }
    previous = next;
  }
  return steps;
}

TEST(QualityLadder, StartsFullAndEachStepGivesSomethingUp) {
  const auto ladder = qualityLadder();
  ASSERT_GE(ladder.size(), 4u);
  EXPECT_EQ(describe(ladder[0]), "full");
  for (std::size_t i = 1; i < ladder.size(); ++i) {
    const QualityStep& a = ladder[i - 1];
    const QualityStep& b = ladder[i];
    EXPECT_LE(b.renderScale, a.renderScale) << i;
    EXPECT_LE(b.grassDistance, a.grassDistance) << i;
    EXPECT_LE(static_cast<int>(b.shadows), static_cast<int>(a.shadows)) << i;
    EXPECT_TRUE(b.renderScale < a.renderScale || b.grassDistance < a.grassDistance || b.shadows != a.shadows)
        << "step " << i << " gives nothing up";
    EXPECT_GT(b.renderScale, 0.0f);
    EXPECT_GT(b.grassDistance, 0.0f);
  }
  EXPECT_EQ(describe(ladder[4]), "render 50 %, grass 50 %, shadows off");
}

TEST(QualityLadder, RenderSizeRoundsAndNeverVanishes) {
  EXPECT_EQ(renderSize({960, 540}, 1.0f), glm::ivec2(960, 540));
  EXPECT_EQ(renderSize({960, 540}, 0.5f), glm::ivec2(480, 270));
  EXPECT_EQ(renderSize({960, 540}, 0.35f), glm::ivec2(336, 189));
  EXPECT_EQ(renderSize({3, 1}, 0.1f), glm::ivec2(1, 1));
  EXPECT_EQ(renderSize({100, 100}, 2.0f), glm::ivec2(100, 100));
}

TEST(QualityGovernor, RejectsSettingsThatCannotWork) {
  GovernorSettings s;
  s.targetMs = 0.0;
  EXPECT_THROW(validate(s), Error);
  s = {};
  s.settleFrames = 0;
  EXPECT_THROW(validate(s), Error);
  s = {};
  s.raiseBelow = 1.0;
  EXPECT_THROW(validate(s), Error);
  s = {};
  s.holdFrames = -1;
  EXPECT_THROW(QualityGovernor{s}, Error);
  EXPECT_THROW(QualityGovernor({}, 0), Error);
}

TEST(QualityGovernor, StaysAtFullQualityWhenTheSceneIsFastEnough) {
  QualityGovernor g;
  int changes = 0;
  const std::vector<int> steps = run(g, costs(40.0, 1.5), 200, &changes);
  EXPECT_EQ(g.step(), 0);
  EXPECT_EQ(changes, 0);
}

TEST(QualityGovernor, FindsTheBestStepUnderTheTargetQuicklyAndHoldsIt) {
  // A frame of 1 s (llvmpipe, the meadow) falling by 1.5 per step: step 6 is the first under 100 ms.
  const std::vector<double> cost = costs(1000.0, 1.5);
  int best = 0;
  while (cost[static_cast<std::size_t>(best)] > 100.0) {
    ++best;
  }
  ASSERT_EQ(best, 6);
  QualityGovernor g;
  int changes = 0;
  const std::vector<int> steps = run(g, cost, 400, &changes);
  // There within the first dozen frames (one large step down, not one step per few frames)...
  int reached = -1;
  for (std::size_t f = 0; f < steps.size(); ++f) {
    if (steps[f] == best) {
      reached = static_cast<int>(f);
      break;
    }
  }
  ASSERT_GE(reached, 0);
  EXPECT_LE(reached, 12);
  // ...and it stays (step 5 misses, so it is never tried again once barred long enough: few changes).
  EXPECT_EQ(g.step(), best);
  EXPECT_LE(changes, 8);
  for (std::size_t f = 200; f < steps.size(); ++f) {
    EXPECT_GE(steps[f], best) << "frame " << f << " drew a step that misses";
  }
}

TEST(QualityGovernor, StepsBackUpWhenTheLoadDrops) {
  QualityGovernor g;
  (void)run(g, costs(1000.0, 1.5), 60);
  ASSERT_GT(g.step(), 3);
  // The camera turned to the sky: every step is cheap now. One step up per few frames, back to full.
  (void)run(g, costs(20.0, 1.5), 200);
  EXPECT_EQ(g.step(), 0);
}

TEST(QualityGovernor, DoesNotFlickerBetweenAStepThatMissesAndOneThatIsFast) {
  // Step 2 takes 105 ms, step 3 takes 55 ms (under raiseBelow × target): without the bar the governor would
  // go up and down every few frames.
  std::vector<double> cost(qualityLadder().size(), 30.0);
  cost[0] = 300.0;
  cost[1] = 200.0;
  cost[2] = 105.0;
  cost[3] = 55.0;
  QualityGovernor g;
  int changes = 0;
  const std::vector<int> steps = run(g, cost, 3000, &changes);
  int missing = 0;
  for (int s : steps) {
    missing += s <= 2 ? 1 : 0;
  }
  // Tries of step 2 grow further apart (hold doubling): a few dozen changes in 3,000 frames, and few frames
  // drawn at a step that misses.
  EXPECT_LE(changes, 40);
  EXPECT_LE(missing, 3000 / 20);
}

TEST(QualityGovernor, IsDeterministicAndIgnoresBadSamples) {
  const std::vector<double> cost = costs(700.0, 1.4);
  QualityGovernor a;
  QualityGovernor b;
  EXPECT_EQ(run(a, cost, 300), run(b, cost, 300));
  const int before = a.step();
  EXPECT_EQ(a.update(std::nan("")), before);
  EXPECT_EQ(a.update(-5.0), before);
  a.reset(100);
  EXPECT_EQ(a.step(), static_cast<int>(a.steps()) - 1);
  a.reset();
  EXPECT_EQ(a.step(), 0);
}

} // namespace
} // namespace sylva::scene
