#pragma once

// `sylva fold view`: a project played live in a window, with sliders for speed, shift, position function and
// time, and an image canvas (zoom, pan, pixel grid) from engine/ui. Keys: Space pause, Home fit, +/- zoom,
// 1 one texel per pixel; Tab hides the panel (the shell's).

#include <string>

namespace sylva::folding_ui {

/** What the viewer opens and how its window runs (the options of `sylva fold view`). */
struct ViewerOptions {
  std::string project;    ///< the project file (.json)
  std::string image;      ///< id of the image shown first (empty: the project's canvas)
  std::string shaderDir;  ///< read shaders from here instead of the embedded ones (empty: embedded)
  int frames = 0;         ///< quit after this many frames (0: when the window closes)
  std::string screenshot; ///< save the last frame here (PNG)
  double fixedStep = 0.0; ///< advance the clock this many seconds a frame (0: wall time)
  bool noUi = false;      ///< start with the panel hidden
  double zoom = 0.0;      ///< screen pixels per image pixel at start (0: fit the window)
};

/**
 * Loads and synthesises the project (errors name the file and field, thrown as sylva::Error before the window
 * opens), opens a window at the image's size and plays it until the window closes.
 */
void runViewer(const ViewerOptions& options);

} // namespace sylva::folding_ui
