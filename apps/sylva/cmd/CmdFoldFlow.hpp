#pragma once

#include <CLI/CLI.hpp>

namespace sylva::app {

/**
 * `sylva fold flow VIDEO --project P --zone ID …`: optical flow between two frames of a reference video,
 * turned into suggested point anchors for one zone (docs/folding.md, "Motion from a reference video").
 * Registered under `fold` by registerFold.
 */
void registerFoldFlow(CLI::App& fold);

} // namespace sylva::app
