#pragma once
// The frames of a planned sequence (scene::planSequence), drawn: how does `sylva render SCENE.json` turn a
// plan into PNG frames?

#include <sylva/scene/Sequence.hpp>

#include <string>

namespace sylva::scene {

/**
 * Builds the plan's world and draws every frame of `plan.todo` at full quality (each frame is then a pure
 * function of (scene, frame), whatever was drawn before: shards and resumed runs rely on it), writing each
 * through a temporary file and a rename; a "render <name>" progress line on a terminal, and Ctrl-C stops it
 * between frames with a one-line sylva::Error saying how to resume. Needs a current GL 4.5 context;
 * `shaderDir` empty: the embedded shaders.
 */
void renderPlannedFrames(const SequencePlan& plan, const std::string& shaderDir);

} // namespace sylva::scene
