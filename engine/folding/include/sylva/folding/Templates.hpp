#pragma once

#include <sylva/folding/Edit.hpp>

#include <optional>
#include <string_view>
#include <vector>

namespace sylva::folding {

/**
 * Motion templates (the thesis's "common motion profile abstraction"): a parameterised set of tools, folding
 * region, interpolation and profile applied to one zone in one undoable edit. The user then refines the
 * result with the ordinary tools. Coordinates come from the zone's bounding box, so a template fits any zone
 * size.
 */
enum class MotionTemplate : std::uint8_t {
  Blink,        ///< the upper lid sweeps down onto the lower lid; the lid skin folds over the eye
  WaveSwash,    ///< water advances along `direction` over the rest of the zone and withdraws
  Breathing,    ///< the zone swells and relaxes about its centre (scale), fading to its border
  WoundOpening, ///< skin on both sides of the zone's long axis slides over a central band and back
  FlagRipple,   ///< a wave running downwind along the zone's long axis, growing from the hoist to the fly
};

/** Every template, in menu order. */
const std::vector<MotionTemplate>& motionTemplates();
/** Its name in files and on the command line ("blink", "wave_swash", ...). */
const char* motionTemplateName(MotionTemplate motion);
/** The template named `name`; nullopt for any other. */
std::optional<MotionTemplate> parseMotionTemplate(std::string_view name);

/** Knobs of a template; zero means "a size that suits the zone". */
struct TemplateParams {
  double strength = 0.0; ///< largest motion, pixels (0: a fraction of the zone's size; blink: at most closed)
  /** WaveSwash: the way the water advances (normalised here). FlagRipple: its sign along the zone's long
   * axis says which way the wind blows (from the hoist to the fly; + or 0: the hoist at the left or top). */
  Vec2 direction{0.0, 1.0};
  double periodS = 0.0; ///< profile period, seconds (0: the template's default)
};

/**
 * Replaces zone `zone`'s tools, folding, interpolation and profile with the template's; adds (or updates) a
 * profile named after the template. One edit: undo restores the zone as it was.
 */
void applyMotionTemplate(EditHistory& history, int zone, MotionTemplate motion,
                         const TemplateParams& params = {});

} // namespace sylva::folding
