// `sylva scene check FILE...`: every error of scene files in one run, without a GPU and without rendering
// (docs/scenes.md "Checking a scene").
#include "Commands.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/scene/SceneCheck.hpp>

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace sylva::app {

void registerScene(CLI::App& app) {
  CLI::App* scene =
      app.add_subcommand("scene", "Work with scene files without rendering them (docs/scenes.md)");
  scene->require_subcommand(1);
  CLI::App* check = scene->add_subcommand(
      "check",
      "Check scene files and everything they name (terrain, blade models, species, folding projects) "
      "and list every error, one line each, without a GPU; exit 0 when all are valid");
  auto files = std::make_shared<std::vector<std::string>>();
  check->add_option("files", *files, "Scene files (.json)")->required();
  check->footer("Example:\n  sylva scene check data/scenes/meadow.json   # ok, or one line per error\n");
  check->callback([files] {
    std::size_t errors = 0;
    std::size_t bad = 0;
    for (const std::string& file : *files) {
      const scene::SceneCheck result = scene::checkScene(file);
      if (result.errors.empty()) {
        std::printf("%s: ok (terrain %dx%d, %zu camera%s, %zu grass layer%s, %zu forest%s, %zu water)\n",
                    file.c_str(), result.terrainWidth, result.terrainHeight, result.cameras,
                    result.cameras == 1 ? "" : "s", result.grass, result.grass == 1 ? "" : "s",
                    result.forests, result.forests == 1 ? "" : "s", result.water);
        continue;
      }
      ++bad;
      for (const std::string& error : result.errors) {
        std::fprintf(stderr, "sylva: error: %s\n", error.c_str());
      }
      errors += result.errors.size();
    }
    if (errors > 0) {
      fail("{} error{} in {} of {} scene file{}", errors, errors == 1 ? "" : "s", bad, files->size(),
           files->size() == 1 ? "" : "s");
    }
  });
}

} // namespace sylva::app
