#include <sylva/grass/GrassField.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/terrain/HeightSources.hpp>

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
  const terrain::HeightFieldInfo info = terrain::heightFieldInfo(mTerrain);
  if (info.validCount == 0) {
    fail("grass: the terrain has no valid height sample");
  }
  mHeightRange = {info.minHeight, info.maxHeight};
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

double GrassField::estimateBlades() const {
  double sum = 0.0;
  for (const float d : mDensity.values()) {
    sum += d;
  }
  const double mean = mDensity.values().empty() ? 0.0 : sum / static_cast<double>(mDensity.values().size());
  return mean * static_cast<double>(mLayout.tilesX) * static_cast<double>(mLayout.tilesZ) *
         std::min<double>(mLayout.bladesPerTile, static_cast<double>(mPatch.size()));
}

std::size_t GrassField::countBlades() const {
  return countFieldBlades(mLayout, mPatch, mTerrain, mDensity);
}

} // namespace sylva::grass
