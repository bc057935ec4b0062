#pragma once
// Scene files on the command line (docs/scenes.md): `sylva render SCENE.json` stills and sequences.

#include <sylva/platform/GlContext.hpp>

#include <CLI/CLI.hpp>

#include <string>

namespace sylva::app {

/** What `sylva render SCENE.json` was asked for. */
struct SceneRenderOptions {
  std::string file;          ///< the scene file
  std::string frames;        ///< "A-B[,C-D...]"; empty: a still of the output's first frame
  std::string shard = "0/1"; ///< i/n
  std::string camera;        ///< empty: the file's output camera
  std::string out;           ///< a PNG (still) or a directory (sequence); empty: out/<name>[.png]
  std::string gif;           ///< also write the sequence as an animated GIF here
  std::string mp4;           ///< also encode the sequence as MP4 here (ffmpeg)
  int width = 0;             ///< 0: the file's output width
  int height = 0;            ///< 0: the file's output height
  bool overwrite = false;    ///< render complete frames again
  platform::ContextOptions context;
  std::string shaderDir;
};

/** Adds --shard, --camera, --mp4, --overwrite (the options only a scene file uses) to `command`. */
void addSceneRenderOptions(CLI::App& command, SceneRenderOptions& options);

/**
 * Renders a still or a frame sequence of a scene file: frame f is a pure function of (scene, f); frames are
 * written as DIR/frame_NNNNN.png through a temporary file and a rename, frames already complete are skipped,
 * `--shard i/n` renders every n-th frame of the range. Throws sylva::Error with one line naming the
 * file/field.
 */
void renderSceneFile(const SceneRenderOptions& options);

} // namespace sylva::app
