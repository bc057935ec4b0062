#pragma once

#include <sylva/core/Image.hpp>

#include <cstdint>

namespace sylva::folding {

/**
 * The procedural input images of the shipped examples (data/folding/). They are committed as PNGs; these
 * functions are their provenance, and a test checks the committed files still match them. Deterministic: the
 * same size and seed give the same pixels on every machine. All RGBA8, row 0 at the top.
 */

/** A beach seen from above: deep water at the top, a foam band, wet and dry sand with shells below. */
Image beachImage(int width, int height, std::uint64_t seed);
/** A meadow under a sky with hills, the background of the flying-over example. */
Image meadowImage(int width, int height, std::uint64_t seed);
/** A bird seen from the side with wings up, on a transparent background (alpha = silhouette). */
Image birdImage(int width, int height);

/** The shoreline's y (pixels) at column x of beachImage(width, height, ·): where water meets sand. */
double beachShoreline(double x, int width, int height);

} // namespace sylva::folding
