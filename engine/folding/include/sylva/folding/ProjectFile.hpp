#pragma once

// A folding project as the commands and the editor open it: how is a project file loaded with its images, and
// synthesised with a progress line, so that every error names the file? Which image does an `--image ID`
// option mean?

#include <sylva/core/Error.hpp>
#include <sylva/folding/Synthesis.hpp>

#include <nlohmann/json.hpp>

#include <string>

namespace sylva::folding {

/** A project file with its images, loaded and validated (errors name the file and the JSON path). */
struct LoadedProject {
  std::string file; ///< the project file as given
  /** The project, validated. */
  Project project;
  /** Its images and masks. */
  ProjectImages images;
};

/** Loads `file` (loadProject) and every image and mask it names (loadProjectImages). */
LoadedProject loadProjectFile(const std::string& file);

/**
 * Runs `work`, prefixing `file` to a sylva::Error that does not name it yet (the atlas packer reports
 * "zones[0].tools: ..." without knowing the file).
 */
template <typename F> auto namingFile(const std::string& file, F&& work) {
  try {
    return work();
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.rfind(file, 0) == 0) {
      throw;
    }
    fail("{}: {}", file, message);
  }
}

/**
 * synthesize() with a "synthesis" progress line on a terminal: Ctrl-C cancels it with a one-line error naming
 * the file, and stillZoneWarnings() are logged as warnings naming it. `stats` (optional) receives the
 * synthesis statistics.
 */
Textures synthesizeLoaded(const LoadedProject& loaded, SynthesisStats* stats = nullptr);

/**
 * Index of the project image `id` (empty: the canvas); throws naming `option` and listing the images when the
 * project has no such image.
 */
int imageIndexOption(const Project& project, const std::string& option, const std::string& id);

/** Index of the zone `id` of `project` (read from `file`); throws naming --zone, the file and its zones. */
int zoneIndexOption(const Project& project, const std::string& file, const std::string& id);

/**
 * What `sylva fold info` prints: the project's images with their sizes, crops and atlas places, its profiles,
 * jump layers and zones with their tools, in the file format's names; several lines, each ending in '\n'.
 * `atlas` from packAtlas() of the same project.
 */
std::string describeProject(const LoadedProject& loaded, const Atlas& atlas);
/**
 * What `sylva fold synth` prints after a synthesis that took `seconds`: the atlas size, images, zones, jump
 * layers and whether extra fold intervals are used, then anchors, zone texels, folded texels, texels with
 * several intervals and jumpMax; two lines ending in '\n'.
 */
std::string describeSynthesis(const LoadedProject& loaded, const Textures& textures,
                              const SynthesisStats& stats, double seconds);

/** The same as JSON: {"file", "project" (toJson), "atlas": {"size", "images": [{id, size, crop,
 * atlas_pos}]}}. */
nlohmann::json describeProjectJson(const LoadedProject& loaded, const Atlas& atlas);

} // namespace sylva::folding
