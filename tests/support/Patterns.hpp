#pragma once
// Test pictures shared by the unit and GL tests.

#include <sylva/core/Image.hpp>

namespace sylva::test {

/**
 * An RGBA8 picture whose neighbouring pixels all differ (R = 7x + 3y, G = 13y + x, B = xy, each mod 256), so
 * a read one pixel off shows. Alpha is 255, or with `varyAlpha` 200 + (x + y) mod 56 (to check alpha passes
 * through).
 */
Image patternImage(int width, int height, bool varyAlpha = false);

} // namespace sylva::test
