#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Synthesis.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sylva::folding {

/** Live overrides of a preview (the viewer's sliders); defaults leave the project as it is. */
struct PlaybackOptions {
  double speed = 1.0;                             ///< multiplies time
  double shift = 0.0;                             ///< cycles added to every profile's shift
  std::optional<PositionFunction::Type> function; ///< replaces every profile's function type
};

/**
 * Progress s of profile `profile` at time t (seconds) for a texel with phase offset dt (cycles):
 * φ = fract(t/T + σ + dt), ping-pong remap when asked, s = p(φ). For crossfade profiles this is the first
 * phase; crossfadePhases() gives both and the weight.
 */
double progressAt(const Profile& profile, double t, double dt);
/** The two phases a crossfade profile blends at one time and place, and the first one's weight. */
struct CrossfadePhases {
  double s1 = 0.0; ///< progress of the first phase
  double s2 = 0.0; ///< progress of the second phase (half a cycle later)
  double w = 1.0;  ///< weight of the first phase (the second gets 1 − w)
};
/** The crossfade phases of `profile` at time t (seconds) for phase offset dt (cycles). */
CrossfadePhases crossfadePhases(const Profile& profile, double t, double dt);
/** Applies playback overrides to the profiles (what both renderers then evaluate). */
std::vector<Profile> applyPlayback(std::vector<Profile> profiles, const PlaybackOptions& playback);

/**
 * The CPU reference renderer: frame at time t (seconds) of the whole atlas, RGBA8, exactly the equations of
 * docs/folding.md (the GLSL renderer evaluates the same ones). Bilinear reads of the colour atlas with the
 * read point clamped to the atlas shrunk by ½ texel (gutters hold edge pixels). Single-threaded unless
 * `threads` > 1.
 */
Image renderFrame(const Textures& textures, const std::vector<Profile>& profiles,
                  const std::vector<double>& jumpLayers, double t, unsigned threads = 1);

/** The longest profile period, seconds: one full cycle of the slowest zone (1 when there is none). */
double longestPeriod(const std::vector<Profile>& profiles);

/** The period after which every profile is back where it started (see loopPeriod). */
struct LoopPeriod {
  double seconds = 1.0; ///< the common period; the longest period when there is none within the limits
  bool seamless = true; ///< false: some profile is mid-cycle at `seconds`, so a loop of it jumps
};

/** Longest common period searched: at most this many cycles of the slowest profile, and at most kMaxLoopS. */
inline constexpr int kMaxLoopCycles = 16;
/** Longest common period searched, seconds. */
inline constexpr double kMaxLoopS = 60.0;

/**
 * The shortest time, seconds, at which every profile completes a whole number of cycles: the least common
 * multiple of the periods (3 s and 4 s: 12 s), found among the first kMaxLoopCycles multiples of the longest
 * period up to kMaxLoopS (the longest itself always), to 1e-6 relative. Where there is none (3 s and 4.1 s),
 * the longest period and seamless = false. One period: that period; no profiles: 1 s.
 */
LoopPeriod loopPeriod(const std::vector<Profile>& profiles);

/** The part of an atlas-sized frame that shows image `entry` (its crop). */
Image cropToEntry(const Image& frame, const AtlasEntry& entry);

/**
 * `count` frames made by `frame(i)` (i = 0 … count − 1) with a "rendering frames" progress line; Ctrl-C
 * cancels with a sylva::Error "`label`: rendering cancelled". The CPU and GL renders of `sylva fold render`
 * both run through it.
 */
std::vector<Image> renderFrames(int count, const std::string& label, const std::function<Image(int)>& frame);

} // namespace sylva::folding
