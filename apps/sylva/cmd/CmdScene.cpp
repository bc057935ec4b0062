// `sylva render SCENE.json`: stills and resumable, splittable, deterministic frame sequences of a scene file
// (docs/scenes.md "Rendering sequences").
#include "cmd/CmdScene.hpp"

#include <sylva/scene/Sequence.hpp>
#include <sylva/scene/gpu/SequenceRender.hpp>

#include <cstdio>

namespace sylva::app {

void addSceneRenderOptions(CLI::App& command, SceneRenderOptions& o) {
  command
      .add_option(
          "--shard", o.job.shard,
          "With a scene file: render only shard i of n (i/n) of --frames, so independent runs split a "
          "range (frame k of the range goes to shard k mod n)")
      ->capture_default_str();
  command.add_option("--camera", o.job.camera,
                     "With a scene file: the camera to render (default: the file's output)");
  command.add_option("--mp4", o.job.mp4, "With a scene file: also encode the sequence as H.264 MP4 (ffmpeg)");
  command.add_flag("--overwrite", o.job.overwrite,
                   "With a scene file: render frames again even when a complete frame file exists");
}

void renderSceneFile(const SceneRenderOptions& o) {
  const scene::SequencePlan plan = scene::planSequence(o.job);
  if (plan.sequence && plan.todo.size() < plan.frames.size()) {
    // Said on stderr whatever the log level: a resumed run should say what it is not redoing.
    std::fprintf(stderr, "%zu of %zu frames already complete in %s: skipped\n",
                 plan.frames.size() - plan.todo.size(), plan.frames.size(), plan.out.c_str());
  }
  if (!plan.todo.empty()) {
    auto context = platform::createHeadlessContext(o.context);
    scene::renderPlannedFrames(plan, o.shaderDir);
  }
  std::printf("%s\n", plan.out.c_str());
  for (const std::string& file : scene::finishSequence(plan)) {
    std::printf("%s\n", file.c_str());
  }
}

} // namespace sylva::app
