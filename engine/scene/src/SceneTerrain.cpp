#include <sylva/scene/SceneTerrain.hpp>

#include <fmt/format.h>

namespace sylva::scene {

terrain::TerrainSetup terrainSetup(const TerrainDesc& t) {
  if (t.setup) {
    return *t.setup;
  }
  terrain::TerrainSetup s;
  if (!t.dem.empty()) {
    s.source.dem = t.dem;
    if (t.spacingSet) {
      s.source.load.spacing = t.spacing;
    }
  } else {
    s.source.procedural = terrain::TerrainSource::defaultProcedural();
    s.source.procedural.seed = t.seed;
    s.source.procedural.heightScale = t.relief;
    s.source.proceduralSize = t.size;
    s.source.proceduralSpacing = t.spacing;
  }
  s.exaggeration = t.exaggeration;
  if (t.seaLevel) {
    s.seaLevel.kind = terrain::SeaLevelRule::Kind::Metres;
    s.seaLevel.metres = *t.seaLevel;
  } else {
    s.seaLevel.kind = terrain::SeaLevelRule::Kind::None;
  }
  s.geomorph = t.geomorph;
  s.quadtree.patchTessLevel = t.tessLevel;
  s.quadtree.lodDistanceFactor = t.lodFactor;
  s.quadtree.lodErrorPixels = t.lodError;
  if (t.maxDepth >= 0) {
    s.maxDepth = t.maxDepth;
  }
  return s;
}

terrain::TerrainFieldName sceneTerrainFieldName(const std::filesystem::path& file) {
  return
      [file = file.string()](std::string_view field) { return fmt::format("{}: /terrain/{}", file, field); };
}

} // namespace sylva::scene
