#pragma once

// `sylva fold edit`: the folding-texture editor (docs/folding-editor.md; thesis FoldingGen, Fig. 28 layout).
// A menu bar, the workflow bar (zones → motion → profiles → synthesise → preview → export), the toolbox and
// the current tool's properties on the left, the canvas in the middle, the live GPU preview with its timeline
// and the zone / jump-path / profile panels on the right, and a status bar. One file per screen in
// engine/folding_ui/src/ (internal/Editor.hpp lists them). Every change goes through the GL-free model
// (sylva::folding::Session, EditHistory, Handles); the window loop and the canvas are engine/ui's
// (WindowShell, ImageCanvas over render::CanvasView), so these files only map input to edits and draw.

#include <string>
#include <vector>

namespace sylva::folding_ui {

/** What the editor opens and how its window runs (the options of `sylva fold edit`). */
struct EditorOptions {
  /** A project file (.json), or input images to start a new project from. Empty: the start screen. */
  std::vector<std::string> inputs;
  /** Where a new project is saved (default: `<first image stem>.fold.json` next to the first image). */
  std::string project;
  int width = 1600;              ///< window width, screen pixels
  int height = 900;              ///< window height, screen pixels
  std::string shaderDir;         ///< read shaders from this folder (live reload) instead of the embedded ones
  int frames = 0;                ///< scripted run: close after this many frames (0: run until closed)
  std::string screenshot;        ///< scripted run: PNG of the last frame
  double fixedStep = 0.0;        ///< seconds each frame advances the clock (0: real time)
  double autosaveSeconds = 30.0; ///< seconds between autosaves of unsaved work (0: never)
  bool noRecover = false;        ///< do not offer to recover an autosave newer than the project
  /** The recent-files list (default: $XDG_CONFIG_HOME/sylva/recent-folding.json). */
  std::string recentFile;
  /** Zoom of the canvas at start (0: fit the image). */
  double zoom = 0.0;
  /** Start with the preview paused at this time, seconds (negative: playing from 0). */
  double pausedAt = -1.0;
};

/**
 * Opens the editor window and runs until it is closed (or `frames` frames have been shown). Errors opening
 * the inputs are thrown as sylva::Error naming the file.
 */
void runEditor(const EditorOptions& options);

} // namespace sylva::folding_ui
