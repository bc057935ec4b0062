#pragma once
// The few whole-context operations a window or a benchmark needs besides the object wrappers: waiting for
// the GPU, the window's framebuffer (name 0), the viewport, clears and the depth test. Apps call these
// instead of raw GL, so every GL call stays in the engine.

#include <sylva/gl/Framebuffer.hpp>

#include <glm/glm.hpp>

namespace sylva::gl {

/** Waits until the GPU has finished all submitted work (glFinish): before reading a timer or a clock. */
void finish();

/** Binds the window's framebuffer (name 0) for drawing and reading. */
void bindWindowFramebuffer();

/** Sets the viewport: `origin` and `size` in pixels, from the lower-left corner. */
void setViewport(glm::ivec2 origin, glm::ivec2 size);

/** Clears the bound framebuffer's colour to `colour` and, with `depth`, its depth to 1. */
void clear(const glm::vec4& colour, bool depth = false);

/** Turns the depth test on (less) or off for the draws that follow. */
void setDepthTest(bool on);

/** Copies the colour of `source` (`size` pixels from its origin) into the window's framebuffer, 1:1. */
void blitToWindow(const Framebuffer& source, glm::ivec2 size);
/** Copies `source`'s colour (`sourceSize` pixels) over the whole window framebuffer (`size` pixels), scaled
 * with linear filtering when the sizes differ (frames drawn at a lower resolution). */
void blitToWindow(const Framebuffer& source, glm::ivec2 sourceSize, glm::ivec2 size);

} // namespace sylva::gl
