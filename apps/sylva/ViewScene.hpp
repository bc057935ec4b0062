#pragma once
// `sylva view SCENE.json`: a scene file in the interactive viewer (docs/scenes.md "Viewer").

#include <sylva/render/GpuTimers.hpp>

#include <string>

namespace sylva::app {

/** What `sylva view SCENE.json` was asked for. */
struct SceneViewOptions {
  std::string file;       ///< the scene file
  int width = 1280;       ///< window width, screen pixels
  int height = 720;       ///< window height, screen pixels
  std::string shaderDir;  ///< empty: embedded shaders (F5 reloads from the source tree)
  int frames = 0;         ///< > 0: quit after this many frames (scripted runs)
  std::string screenshot; ///< with frames: save the last frame here
  double fixedStep = 0.0; ///< > 0: scene seconds per frame (scripted runs repeat)
  bool noUi = false;      ///< start with the panel hidden
};

/**
 * Opens a window on the scene file: the file's output camera at its first frame's time to start, its other
 * cameras in a selector (path cameras play along scene time), fly (F) and walk (G) cameras, balls thrown
 * from the eye (B), a pause and a scene-time slider, a checkbox per pass (keys 1-8), per-pass CPU and GPU
 * timings. The scene is drawn into an offscreen target of the window's size (whose depth the sun flare
 * tests) and blitted to the window. Throws sylva::Error with one line naming the file/field.
 */
void runSceneViewer(const SceneViewOptions& options);

/** The per-pass CPU and GPU milliseconds of `timers`' last complete frame as an ImGui table (both viewers).
 */
void passTimingTable(const render::GpuTimers& timers);

} // namespace sylva::app
