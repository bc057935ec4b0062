#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/folding/Project.hpp>
#include <sylva/folding/Synthesis.hpp>

#include <optional>
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
struct CrossfadePhases {
  double s1 = 0.0, s2 = 0.0, w = 1.0;
};
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

/** The part of an atlas-sized frame that shows image `entry` (its crop). */
Image cropToEntry(const Image& frame, const AtlasEntry& entry);

} // namespace sylva::folding
