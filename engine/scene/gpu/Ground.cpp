#include <sylva/scene/gpu/Ground.hpp>

namespace sylva::scene {

GrassGround grassGround(const terrain::TerrainScene& terrain) {
  return {&terrain.field(), terrain.exaggeration(), terrain.seaLevel(), terrain.renderer().layers()};
}

trees::FarGround farGround(const terrain::TerrainScene& terrain) {
  trees::FarGround g;
  g.field = &terrain.field();
  if (terrain.seaLevel()) {
    g.floor = (*terrain.seaLevel() + 0.5f) * terrain.exaggeration();
  }
  return g;
}

} // namespace sylva::scene
