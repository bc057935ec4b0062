#include <sylva/grass/GrassField.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>

#include <algorithm>

namespace sylva::grass {

GrassField::GrassField(terrain::HeightField terrain, std::vector<BladeType> types,
                       const FieldSettings& settings)
    : mTerrain(std::move(terrain)), mTypes(std::move(types)), mSettings(settings) {
  if (mTypes.empty()) {
    fail("grass: the field needs at least one blade type");
  }
  mPatch = makePatch(settings.patch, static_cast<int>(mTypes.size()));
  if (settings.bladesPerTile < 1 || settings.bladesPerTile > settings.patch.blades) {
    fail("grass: bladesPerTile must be in 1..{} (the patch size), got {}", settings.patch.blades,
         settings.bladesPerTile);
  }
  mLayout = layoutOver(mTerrain, settings.patch.tileSize, settings.bladesPerTile);
  mDensity = DensityGrid(DensityMap(settings.density), mTerrain, settings.densitySpacing);
  mTileRanges.resize(static_cast<std::size_t>(mLayout.tilesX) * static_cast<std::size_t>(mLayout.tilesZ));
  parallelFor(
      static_cast<std::size_t>(mLayout.tilesZ),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t tz = begin; tz < end; ++tz) {
          for (int tx = 0; tx < mLayout.tilesX; ++tx) {
            mTileRanges[tz * static_cast<std::size_t>(mLayout.tilesX) + static_cast<std::size_t>(tx)] =
                tileHeightRange(mLayout, mTerrain, tx, static_cast<int>(tz));
          }
        }
      },
      8);
  float tallest = 0.0f;
  for (const BladeType& t : mTypes) {
    mTypeLengths.push_back(t.length());
    tallest = std::max(tallest, t.length());
  }
  float maxScale = 0.0f;
  for (const gpu::GrassBlade& b : mPatch) {
    maxScale = std::max(maxScale, b.placement.w);
  }
  mBladeTop = tallest * maxScale;
}

void GrassField::forEachTileBlade(int tx, int tz, const std::function<void(const FieldBlade&)>& visit) const {
  grass::forEachTileBlade(mLayout, mPatch, mTerrain, mDensity, tx, tz, visit);
}

std::size_t GrassField::countBlades() const {
  return countFieldBlades(mLayout, mPatch, mTerrain, mDensity);
}

} // namespace sylva::grass
