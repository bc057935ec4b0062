#pragma once
// A scene file's terrain (scene::TerrainDesc) as the terrain module's description (terrain::TerrainSetup):
// the engine composes, so scene files build their terrain with the same builder as `sylva render
// --dem/--seed` (TerrainScene::fromSetup), with errors that name the file and field (docs/scenes.md,
// "Terrain"). CPU only.

#include <sylva/scene/SceneFile.hpp>
#include <sylva/terrain/TerrainSetup.hpp>

#include <filesystem>

namespace sylva::scene {

/**
 * The terrain setup of `terrain`: a DEM (its own spacing unless the file sets one) or the demo landscape's
 * procedural spec with the file's seed, size, spacing and relief; exaggeration, sea level (none when the file
 * gives none), geomorphing, tessellation level, LOD factor and depth (automatic for -1); or the description's
 * own `setup` when code gave one. Pure.
 */
terrain::TerrainSetup terrainSetup(const TerrainDesc& terrain);

/** "<file>: /terrain/<field>": the names of scene file `file`'s terrain fields. */
terrain::TerrainFieldName sceneTerrainFieldName(const std::filesystem::path& file);

} // namespace sylva::scene
