#pragma once
// `sylva view`: the one interactive viewer (docs/cli.md, docs/scenes.md "Viewer"). A scene file or the world
// the terrain/grass/trees options describe is built by the engine (scene::SceneWorld) and drawn by its frame
// path exactly as `sylva render` draws it, into an offscreen target of the window's size (whose depth the sun
// flare tests), then blitted under the ImGui panel.

#include "flags/WorldFlags.hpp"

#include <sylva/render/Camera.hpp>
#include <sylva/terrain/TileSource.hpp>
#include <sylva/terrain/gpu/StreamedTerrain.hpp>

#include <memory>

#include <string>

namespace sylva::app {

/** The window and scripted-run options of `sylva view`. */
struct ViewerOptions {
  int width = 1280;       ///< window width, screen pixels
  int height = 720;       ///< window height, screen pixels
  std::string shaderDir;  ///< empty: embedded shaders (F5 reloads from the source tree)
  int frames = 0;         ///< > 0: quit after this many frames (scripted runs)
  std::string screenshot; ///< with frames: save the last frame here
  double fixedStep = 0.0; ///< > 0: scene seconds per frame (scripted runs repeat)
  bool noUi = false;      ///< start with the panel hidden
  /** "auto" (the quality governor), "full", or a step of scene::qualityLadder() ("0".."7"); empty: auto,
   * but full for runs with a fixed step or a screenshot (their frames repeat). */
  std::string quality;
  double targetFps = 10.0; ///< what auto quality keeps frames at or above
};

/**
 * Opens a window on the scene file: its output camera at its first frame's time to start, its other cameras
 * in a selector (path cameras play along scene time), orbit, fly (F) and walk (G) cameras, balls thrown from
 * the eye (B), a pause and a scene-time slider, a checkbox per pass (keys 1-8), per-pass CPU and GPU timings,
 * and the terrain, grass, simulation and trees sections. Throws sylva::Error with one line naming the
 * file/field.
 */
void viewSceneFile(const std::string& file, const ViewerOptions& options);

/**
 * Opens a window on the world `flags` describe (as `sylva render` with the same options draws it), at the
 * same first camera, orbiting it; the sections start open for what the options turned on.
 */
void viewWorld(const WorldFlags& flags, const ViewerOptions& options);

/**
 * Opens a window on streamed terrain (docs/terrain-data.md, "Streaming"): flying (W/A/S/D/Q/E, drag to look,
 * G walks), the panel shows tiles, budgets and loads; L toggles level colours.
 */
void viewStreamed(std::shared_ptr<const terrain::TileSource> source,
                  const terrain::StreamedTerrainOptions& streamOptions, const ViewerOptions& options);

/**
 * The first camera on a streamed source: over the procedural world's middle, 250 m up looking ahead and down;
 * a pyramid whole from the south-west.
 */
render::Camera streamStartCamera(const terrain::TileSource& source, float fovY);
/** How deep (metres) views of a streamed source are, for the haze: 30 km over the procedural world, five
 * times a pyramid's extent. */
double streamViewDepth(const terrain::TileSource& source);

/** Opens a window on the small built-in pipeline test scene (render::DemoScene), orbiting it. */
void viewDemo(const ViewerOptions& options);

} // namespace sylva::app
