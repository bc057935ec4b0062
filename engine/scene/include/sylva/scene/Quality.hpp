#pragma once
// Interactive quality (docs/scenes.md "Interactive quality"): a ladder of steps, each giving up a little more
// of the frame (resolution, grass distance, shadows) to draw it sooner, and a governor that picks the step
// from the frame times it is fed, so the viewer stays interactive where the GPU (or llvmpipe) cannot draw the
// scene as described at the rate asked. Pure CPU: the world applies a step (SceneWorld::setQuality), the
// caller sizes its target with renderSize.

#include <glm/vec2.hpp>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace sylva::scene {

/** What one step of the ladder draws. */
struct QualityStep {
  /** Fraction (0, 1] of the output's width and height the frame is drawn at, then scaled up to the output. */
  float renderScale = 1.0f;
  /** Multiplies every grass layer's draw distance (its level-of-detail and fade distances scale with it). */
  float grassDistance = 1.0f;
  /** Whether shadow cascades are drawn (off: everything fully sunlit, as with the shadows pass off). */
  bool shadows = true;
};

/**
 * The ladder, best first: step 0 draws the scene as its file describes; each later step costs less than the
 * one before (resolution first, then grass distance, then shadows).
 */
std::span<const QualityStep> qualityLadder();

/** "render 50 %, grass 70 %, shadows off"; step 0 gives "full". */
std::string describe(const QualityStep& step);

/** The size a frame of `output` pixels is drawn at under `scale` (each side rounded, at least 1 pixel). */
glm::ivec2 renderSize(glm::ivec2 output, float scale);

/** How the governor decides. */
struct GovernorSettings {
  /** Frame time to stay at or under, milliseconds (100: 10 frames/s). */
  double targetMs = 100.0;
  /** Frames measured at a step before deciding (the median of them); the first frame after a change is not
   * counted (it pays for the change). */
  int settleFrames = 3;
  /** Step up (better quality) when the median is under this fraction of the target. */
  double raiseBelow = 0.6;
  /** Frames a step that was just left for missing the target stays barred from stepping up into; doubles
   * every time the same step misses again (up to 64 times this). */
  int holdFrames = 30;
};

/** Throws sylva::Error naming the field for a target ≤ 0 or not finite, settleFrames < 1, raiseBelow outside
 * (0, 1), holdFrames < 0. */
void validate(const GovernorSettings& settings);

/**
 * Picks the quality step from measured frame times: steps down (cheaper) when the median frame of a step
 * misses the target, by as many steps as the miss is large (one per factor 1.5), and up one step when the
 * median is well under the target, unless that step missed soon after it was last stepped up into (then it
 * waits, longer each time, so the quality does not flicker between two steps). Deterministic: the same frame
 * times give the same steps.
 */
class QualityGovernor {
public:
  /** A governor over `steps` steps (≥ 1), starting at step 0. */
  explicit QualityGovernor(const GovernorSettings& settings = {}, std::size_t steps = qualityLadder().size());

  /** Feeds the wall time (ms) of the frame just drawn at step(); returns the step for the next frame. */
  int update(double frameMs);
  /** The step the next frame is drawn at. */
  int step() const { return mStep; }
  /** How many steps the governor chooses from. */
  std::size_t steps() const { return mHold.size(); }
  /** The settings the governor was made with. */
  const GovernorSettings& settings() const { return mSettings; }
  /** Starts again at `step` (clamped to the ladder) with nothing measured and nothing barred. */
  void reset(int step = 0);

private:
  void moveTo(int step);

  GovernorSettings mSettings;
  int mStep = 0;
  bool mFirstAfterChange = false;
  std::vector<double> mSamples;
  long long mFrame = 0;
  long long mChangedAt = 0;
  /** Per step: frame count before which stepping up into it is barred, and its current hold length. */
  std::vector<long long> mBarredUntil;
  std::vector<int> mHold;
  /** The step we last stepped up from (−1: the last change was a step down or none). */
  int mRaisedFrom = -1;
};

} // namespace sylva::scene
