#pragma once
// A scene file's forest (scene::ForestDesc) as the trees module's descriptions: where the trees stand
// (trees::ForestSettings) and how they look (trees::ForestLook), the same descriptions `sylva render --trees`
// fills from its options (docs/scenes.md, "Forests"). CPU only.

#include <sylva/core/FieldName.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/trees/Forest.hpp>
#include <sylva/trees/ForestLook.hpp>

#include <cstddef>
#include <filesystem>
#include <optional>

namespace sylva::scene {

/** "<file>: /forests/<index>/<field>": the names of scene file `file`'s forest `index`. */
FieldName sceneForestFieldName(const std::filesystem::path& file, std::size_t index);

/**
 * Where the trees of `forest` stand on a terrain drawn `exaggeration` × its true heights (the field placement
 * reads holds drawn heights): species and weights (each resolved, or an error naming "species/<name>"),
 * count, seed, spacing, max slope, clustering, bare fraction, height band (default floor: half a metre above
 * `seaLevel`, true metres; default top: `treeLine`, true metres, the terrain's terrain::snowLine, when it
 * lies above the floor), the region (none: the whole terrain; regionAroundCentre: centred on the `footprint`,
 * world metres x × z) and the density map (loaded here). Throws sylva::Error naming the field through `name`
 * before any tree is placed.
 */
trees::ForestSettings forestSettings(const ForestDesc& forest, float exaggeration,
                                     std::optional<float> seaLevel, const FieldName& name,
                                     glm::vec2 footprint = glm::vec2(0.0f),
                                     std::optional<float> treeLine = std::nullopt);

/** How the trees of `forest` look: its `look` when given, else bark, foliage and far field (leaves "auto").
 * Checked (trees::check). */
trees::ForestLook forestLook(const ForestDesc& forest, const FieldName& name);

} // namespace sylva::scene
