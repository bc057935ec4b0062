// Interactive quality: the ladder and the governor (Quality.hpp).
#include <sylva/scene/Quality.hpp>

#include <sylva/core/Error.hpp>

#include <fmt/format.h>
#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace sylva::scene {

namespace {

// Resolution first (cheap to give up: the frame is scaled up smoothly), then the grass's draw distance (the
// blades drawn fall with its square), then shadows (a large change of look, and on llvmpipe a large cost).
constexpr std::array<QualityStep, 8> kLadder{{
    {1.0f, 1.0f, true},
    {0.75f, 1.0f, true},
    {0.75f, 0.7f, true},
    {0.5f, 0.7f, true},
    {0.5f, 0.5f, false},
    {0.5f, 0.3f, false},
    {0.35f, 0.3f, false},
    {0.35f, 0.2f, false},
}};

/** A step is assumed to cost this much less than the one before: a miss by a factor f drops log_1.5 f steps.
 */
constexpr double kStepGain = 1.5;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

} // namespace

std::span<const QualityStep> qualityLadder() {
  return kLadder;
}

std::string describe(const QualityStep& step) {
  if (step.renderScale >= 1.0f && step.grassDistance >= 1.0f && step.shadows) {
    return "full";
  }
  return fmt::format("render {:.0f} %, grass {:.0f} %, shadows {}", 100.0f * step.renderScale,
                     100.0f * step.grassDistance, step.shadows ? "on" : "off");
}

glm::ivec2 renderSize(glm::ivec2 output, float scale) {
  const float s = std::clamp(scale, 0.0f, 1.0f);
  return glm::max(glm::ivec2(std::lround(static_cast<float>(output.x) * s),
                             std::lround(static_cast<float>(output.y) * s)),
                  glm::ivec2(1));
}

void validate(const GovernorSettings& s) {
  if (!(s.targetMs > 0.0) || !std::isfinite(s.targetMs)) {
    fail("quality: target frame time {} ms must be > 0", s.targetMs);
  }
  if (s.settleFrames < 1) {
    fail("quality: settleFrames {} must be ≥ 1", s.settleFrames);
  }
  if (!(s.raiseBelow > 0.0 && s.raiseBelow < 1.0)) {
    fail("quality: raiseBelow {} must lie in (0, 1)", s.raiseBelow);
  }
  if (s.holdFrames < 0) {
    fail("quality: holdFrames {} must be ≥ 0", s.holdFrames);
  }
}

QualityGovernor::QualityGovernor(const GovernorSettings& settings, std::size_t steps) : mSettings(settings) {
  validate(settings);
  if (steps < 1) {
    fail("quality: a governor needs at least one step");
  }
  mBarredUntil.assign(steps, 0);
  mHold.assign(steps, settings.holdFrames);
}

void QualityGovernor::reset(int step) {
  std::fill(mBarredUntil.begin(), mBarredUntil.end(), 0);
  std::fill(mHold.begin(), mHold.end(), mSettings.holdFrames);
  mRaisedFrom = -1;
  mSamples.clear();
  mFirstAfterChange = false;
  mStep = std::clamp(step, 0, static_cast<int>(steps()) - 1);
}

void QualityGovernor::moveTo(int step) {
  mRaisedFrom = step < mStep ? mStep : -1;
  mStep = step;
  mChangedAt = mFrame;
  mSamples.clear();
  mFirstAfterChange = true;
}

int QualityGovernor::update(double frameMs) {
  ++mFrame;
  if (mFirstAfterChange) {
    mFirstAfterChange = false;
    return mStep;
  }
  if (!std::isfinite(frameMs) || frameMs < 0.0) {
    return mStep;
  }
  mSamples.push_back(frameMs);
  if (static_cast<int>(mSamples.size()) < mSettings.settleFrames) {
    return mStep;
  }
  const double m = median(mSamples);
  mSamples.erase(mSamples.begin()); // a sliding window: decide again next frame
  const int last = static_cast<int>(steps()) - 1;
  if (m > mSettings.targetMs && mStep < last) {
    if (mRaisedFrom >= 0 &&
        mFrame - mChangedAt <= std::max(mSettings.holdFrames, 2 * mSettings.settleFrames)) {
      // Stepping up into this step was a mistake (it missed soon after): bar it for a while, longer each
      // time.
      const auto s = static_cast<std::size_t>(mStep);
      mBarredUntil[s] = mFrame + mHold[s];
      mHold[s] = std::min(2 * mHold[s], 64 * mSettings.holdFrames);
    }
    const int drop = 1 + static_cast<int>(std::floor(std::log(m / mSettings.targetMs) / std::log(kStepGain)));
    moveTo(std::min(last, mStep + std::max(drop, 1)));
  } else if (m < mSettings.raiseBelow * mSettings.targetMs && mStep > 0 &&
             mFrame >= mBarredUntil[static_cast<std::size_t>(mStep - 1)]) {
    moveTo(mStep - 1);
  }
  return mStep;
}

} // namespace sylva::scene
