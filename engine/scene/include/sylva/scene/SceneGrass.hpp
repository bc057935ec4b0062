#pragma once
// A grass layer (scene::GrassLayer, what a scene file's "grass" entry holds) made into a grass field: the
// engine composes, so scene files, `sylva render --grass` and the viewer build their fields here from one
// description (docs/scenes.md, "Grass"). CPU only: the field's blades, tiles and baked density; the renderer
// is the caller's.

#include <sylva/core/FieldName.hpp>
#include <sylva/grass/Cull.hpp>
#include <sylva/grass/GrassField.hpp>
#include <sylva/scene/SceneFile.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/terrain/TerrainMaps.hpp>

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::scene {

/** The ground a grass layer grows on: the facts of a terrain its density rules read. */
struct GrassGround {
  /** Heights as drawn (exaggerated), world metres. Not owned; must outlive the call. */
  const terrain::HeightField* field = nullptr;
  /** Vertical exaggeration of `field` (drawn height = true height × this, > 0). */
  float exaggeration = 1.0f;
  /** Sea level in true metres: grass grows from 0.3 m above it (fading in over 1 m). */
  std::optional<float> seaLevel;
  /** The terrain's splat layers (rules in true metres and degrees), for GrassLayer::layer. */
  std::span<const terrain::SplatLayer> layers;
};

/**
 * Names a layer's field in an error message, from the field's scene-file name ("paint", "layer", "blades",
 * "max_slope", …): "meadow.json: /grass/0/paint" for a scene file (sceneGrassFieldName), "--grass-paint" for
 * the command line.
 */
using GrassFieldName = FieldName;

/** "<file>: /grass/<index>/<field>": the names of scene file `file`'s grass layer `index`. */
GrassFieldName sceneGrassFieldName(const std::filesystem::path& file, std::size_t index);

/**
 * The field settings of `layer` on `ground`: patch (blades, tile side, blades per tile), density multiplier
 * (not clamped: the density map clamps density × noise to [0, 1], so a multiplier above 1 fills the thin
 * parts), coverage, seeds (the patch's; the density map's is seed + 1), max_slope (true degrees, turned into
 * the drawn slope for the ground's exaggeration), the sea level, the paint map stretched over the terrain's
 * footprint (at least 2 × 2 pixels, its aspect within 2 % of the footprint's; loaded here) and the splat
 * layer by name ("none": everywhere). Throws sylva::Error naming the field through `name`, before any field
 * is built.
 */
grass::FieldSettings grassFieldSettings(const GrassLayer& layer, const GrassGround& ground,
                                        const GrassFieldName& name);

/** The blade types of `layer`: every blade of its blade-model files in order, or the procedural set when it
 * names none. Throws sylva::Error naming the field ("blades") for a file without blades. */
/**
 * The grass layer of `scene` that is simulated (its physics world also moves the bodies and drops), or −1 for
 * none. Throws naming the field when two layers ask for simulation, or when bodies or drops have none.
 */
int simulatedGrassLayer(const SceneDesc& scene);

/** The blade types of a grass layer: its blade-model files, or the procedural blade; errors name the layer's
 * field. */
std::vector<grass::BladeType> grassBladeTypes(const GrassLayer& layer, const GrassFieldName& name);

/**
 * How far `layer`'s grass is drawn: to its distance, with the LOD bands at 20 % and 55 % of it (the defaults
 * 12 and 35 m suit 60 m) and the fades shortened to fit, so every distance in a scene file is valid (or the
 * layer's own `cull`, fades shortened the same way). Throws naming the field ("distance").
 */
grass::CullSettings grassCullSettings(const GrassLayer& layer, const GrassFieldName& name);

/** The field of `layer` over ground.field: grassBladeTypes and grassFieldSettings. */
std::shared_ptr<const grass::GrassField> buildGrassField(const GrassLayer& layer, const GrassGround& ground,
                                                         const GrassFieldName& name);

} // namespace sylva::scene
