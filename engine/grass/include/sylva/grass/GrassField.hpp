#pragma once
// Everything the grass field needs on the CPU, made once from the terrain and the blade types: the patch, the
// tile grid, the baked density grid and every tile's height range. The GPU side uploads exactly these, and
// the CPU references (culling, expansion) read them, so both see the same field.

#include <sylva/grass/BladeType.hpp>
#include <sylva/grass/Field.hpp>
#include <sylva/grass/Patch.hpp>
#include <sylva/terrain/HeightField.hpp>

#include <glm/vec2.hpp>

#include <functional>
#include <vector>

namespace sylva::grass {

/** How a field is made. */
struct FieldSettings {
  /** The patch every tile draws from. */
  PatchSettings patch;
  /** Blades a tile draws at density 1 (the paper's field: 64 per 2 m tile); at most patch.blades. */
  int bladesPerTile = 64;
  /** Where grass grows and how dense. */
  DensitySettings density;
  /** Largest spacing of the baked density grid, metres. */
  float densitySpacing = 2.0f;
};

/** The field's CPU data. Immutable after construction. */
class GrassField {
public:
  /**
   * Builds the field over `terrain` (heights as drawn, world metres) with `types` (at least one). Throws
   * sylva::Error naming the setting for bad values (see makePatch, layoutOver, DensityMap) and for no types.
   */
  GrassField(terrain::HeightField terrain, std::vector<BladeType> types, const FieldSettings& settings);

  /** The terrain the blades stand on. */
  const terrain::HeightField& terrain() const { return mTerrain; }
  /** The blade types. */
  const std::vector<BladeType>& types() const { return mTypes; }
  /** The patch's blades as the GPU reads them. */
  const std::vector<gpu::GrassBlade>& patch() const { return mPatch; }
  /** The grid of tiles. */
  const FieldLayout& layout() const { return mLayout; }
  /** The density baked over the terrain. */
  const DensityGrid& density() const { return mDensity; }
  /** The settings the field was made with. */
  const FieldSettings& settings() const { return mSettings; }
  /** Height range (min, max; min > max when the tile has no terrain) of tile (tx, tz), metres. */
  glm::vec2 tileRange(int tx, int tz) const {
    return tileHeightRange(mLayout, mTerrain, tx, tz, mHeightRange);
  }
  /** Range of the terrain's valid heights, metres. */
  glm::vec2 heightRange() const { return mHeightRange; }
  /** Height of the tallest blade the patch can hold (tallest type × largest scale), metres. */
  float bladeTop() const { return mBladeTop; }
  /** Length of each type's finest knot line, metres (index = type). */
  const std::vector<float>& typeLengths() const { return mTypeLengths; }

  /** The blades tile (tx, tz) draws (forEachTileBlade over this field). */
  void forEachTileBlade(int tx, int tz, const std::function<void(const FieldBlade&)>& visit) const;
  /** Blades of the whole field, exactly (visits every tile: small fields, tests). */
  std::size_t countBlades() const;
  /** Blades of the whole field estimated from the mean density (any size, fast). */
  double estimateBlades() const;

private:
  terrain::HeightField mTerrain;
  std::vector<BladeType> mTypes;
  FieldSettings mSettings;
  std::vector<gpu::GrassBlade> mPatch;
  FieldLayout mLayout;
  DensityGrid mDensity;
  glm::vec2 mHeightRange{0.0f};
  std::vector<float> mTypeLengths;
  float mBladeTop = 0.0f;
};

} // namespace sylva::grass
