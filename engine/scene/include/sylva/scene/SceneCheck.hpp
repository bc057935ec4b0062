#pragma once
// `sylva scene check`: every error of a scene file in one run, without a GL context and without building the
// world: the file's own fields item by item, then what building would refuse (terrain source and quadtree,
// blade models and grass settings, forest species, rules and looks, folding projects of the water, the one
// simulated layer).

#include <filesystem>
#include <string>
#include <vector>

namespace sylva::scene {

/** What checkScene found and read. */
struct SceneCheck {
  /** One line each ("<file>: <json/path>: <what>"): the file's own errors in file order, then building's. */
  std::vector<std::string> errors;
  std::size_t cameras = 0; ///< cameras read
  std::size_t grass = 0;   ///< grass layers
  std::size_t forests = 0; ///< forests
  std::size_t water = 0;   ///< water bodies
  int terrainWidth = 0;    ///< samples of the terrain that loaded (0: it did not)
  /** Rows of the terrain that loaded (0: it did not). */
  int terrainHeight = 0;
};

/**
 * Checks the scene file `file` and everything it names, collecting every error instead of stopping at the
 * first: the same checks and messages as `sylva render FILE` before it draws, except those needing a GPU
 * (its largest texture). Loads the terrain's heights (a procedural field is generated) and each folding
 * project's images; places no trees, synthesises nothing. Never throws for a bad scene.
 */
SceneCheck checkScene(const std::filesystem::path& file);

} // namespace sylva::scene
