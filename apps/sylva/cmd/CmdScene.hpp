#pragma once
// Scene files on the command line (docs/scenes.md): `sylva render SCENE.json` stills and sequences.

#include <sylva/platform/GlContext.hpp>
#include <sylva/scene/Sequence.hpp>

#include <CLI/CLI.hpp>

#include <string>

namespace sylva::app {

/** What `sylva render SCENE.json` was asked for: the job, and the GL context and shaders it draws with. */
struct SceneRenderOptions {
  scene::SequenceJob job;
  platform::ContextOptions context;
  std::string shaderDir; ///< empty: the embedded shaders
};

/** Adds --shard, --camera, --mp4, --overwrite (the options only a scene file uses) to `command`. */
void addSceneRenderOptions(CLI::App& command, SceneRenderOptions& options);

/**
 * Renders a still or a frame sequence of a scene file (scene::planSequence, renderPlannedFrames,
 * finishSequence) and prints the files written. Throws sylva::Error with one line naming the file/field.
 */
void renderSceneFile(const SceneRenderOptions& options);

} // namespace sylva::app
