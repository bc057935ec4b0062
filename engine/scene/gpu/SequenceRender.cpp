#include <sylva/scene/gpu/SequenceRender.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Progress.hpp>
#include <sylva/render/gpu/RenderTarget.hpp>
#include <sylva/scene/gpu/SceneWorld.hpp>
#include <sylva/shader/Library.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace sylva::scene {

void renderPlannedFrames(const SequencePlan& plan, const std::string& shaderDir) {
  if (plan.todo.empty()) {
    return;
  }
  shader::Library library(shaderDir);
  SceneWorld world(library, plan.desc);
  // Offline frames take the full path; the real-time paths keep far shadow cascades.
  SceneDrawOptions draw = world.drawOptions();
  draw.fullQuality = true;
  world.setDrawOptions(draw);
  render::RenderTarget target(plan.width, plan.height);
  Progress progress(fmt::format("render {}", plan.desc.name), plan.todo.size());
  const std::vector<int> faults = faultFrames();
  for (int f : plan.todo) {
    if (std::find(faults.begin(), faults.end(), f) != faults.end()) {
      fail("frame {}: failed on purpose (SYLVA_FAULT_FRAMES, the render farm's test hook): {} of {} frames "
           "written",
           f, progress.done(), plan.todo.size());
    }
    if (progress.cancelled()) {
      fail("interrupted: {} of {} frames written; run the same command again to resume", progress.done(),
           plan.todo.size());
    }
    world.advanceToFrame(f);
    const double time = world.frameTime(f);
    const render::Camera camera = world.camera(plan.camera, time, target.aspect());
    target.begin(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    world.draw(camera, plan.width, plan.height, time, &target.depth(), nullptr);
    writeFrameAtomically(plan.framePath(f), target.readColor());
    progress.advance(1);
  }
}

} // namespace sylva::scene
