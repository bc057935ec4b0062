#pragma once
// What grass and forests read of a drawn terrain: the same facts for scene files and the command line.

#include <sylva/scene/SceneGrass.hpp>
#include <sylva/terrain/gpu/TerrainScene.hpp>
#include <sylva/trees/ForestLook.hpp>

namespace sylva::scene {

/** The ground grass grows on: `terrain`'s drawn heights, exaggeration, sea level and splat layers. */
GrassGround grassGround(const terrain::TerrainScene& terrain);

/** The ground a far field stands on: `terrain`'s drawn heights, no tree below half a metre above its sea. */
trees::FarGround farGround(const terrain::TerrainScene& terrain);

} // namespace sylva::scene
