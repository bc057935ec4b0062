#pragma once
// How a forest looks beyond where its trees stand: bark, foliage and the far field (docs/trees.md). One
// description that the command line (`--trees-bark`, `--trees-far`, …) and scene files (a forest's "bark",
// "foliage", "far_*") both fill; ForestScene::applyLook puts it on a forest. CPU here.

#include <sylva/core/FieldName.hpp>
#include <sylva/terrain/HeightField.hpp>
#include <sylva/trees/Bark.hpp>
#include <sylva/trees/FarField.hpp>
#include <sylva/trees/Forest.hpp>

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sylva::trees {

/** Bark, foliage and far field of a forest. */
struct ForestLook {
  /** "auto" (species photos when fetched, else procedural), "procedural", "none" (flat colours) or a tile-set
   * directory (`sylva texsynth tiles`). */
  std::string bark = "auto";
  /** Where "auto" looks for the species' bark photos; empty: the data folder's (BarkSources::photoDir, used
   * when scripts/fetch-sample-data.sh fetched them). A directory named here must exist (check()). */
  std::filesystem::path barkPhotos;
  /** Synthesised tile side, texels, and tiles per class and edge colouring. */
  int barkTile = BarkSources::defaultBarkTiles().tileSize;
  /** Tiles per class and edge colouring of synthesised bark. */
  int barkVariants = BarkSources{}.variants;
  /** Leaf-cloud impostors at the branch tips. */
  bool foliage = true;
  /** A leaf image with alpha, "auto" (ez-tree's oak leaf when fetched, else procedural) or "procedural". */
  std::string leaves = "auto";
  /** A leaf-cloud model (Assimp); empty: procedural cards. */
  std::filesystem::path leafModel;
  /** Trees farther than this become octahedral impostors, metres (0: never), dissolving over farBand metres;
   * farCount impostor-only trees are added around the forest out to the terrain's edge. */
  float farDistance = 0.0f;
  /** Width of the near/far dissolve band, metres. */
  float farBand = 25.0f;
  /** Impostor-only trees added around the forest. */
  int farCount = 0;
};

/** Where ez-tree's oak leaf lies after scripts/fetch-sample-data.sh (the "auto" leaves), in the data folder.
 */
inline const std::filesystem::path kAutoLeafImage = dataPath("external/ez-tree/leaves/oak_color.png");

/**
 * Throws sylva::Error naming the field through `name` ("bark", "leaves", "leaf_model", "far_distance",
 * "far_band", "far_count") when a value is malformed or a file is missing, before any work.
 */
void check(const ForestLook& look, const FieldName& name = {});

/** Where the bark tiles come from (synthesised sets cached per user under $XDG_CACHE_HOME/sylva/bark or
 * ~/.cache/sylva/bark); nullopt for "none". */
std::optional<BarkSources> barkSources(const ForestLook& look);

/** The ground the far field stands on. */
struct FarGround {
  /** Heights as drawn (already exaggerated), world metres. Not owned; must outlive the call. */
  const terrain::HeightField* field = nullptr;
  /** Drawn height below which no tree stands (the sea); nullopt: none. */
  std::optional<float> floor;
};

/**
 * The impostor-only trees of `look.farCount` around `forest`: an annulus from the forest's region radius to
 * the terrain's corners, crowns as tall as the forest's (`centres`: TreeRenderer::treeCentres, w = crown
 * height), kept only above the floor, inside the placement's height band (without a top: no higher than the
 * forest's highest tree, so they do not climb onto snow) and on ground no steeper than the placement's max
 * slope. Deterministic in the placement's seed. Empty for farCount 0.
 */
std::vector<FarTree> farFieldTrees(const ForestLook& look, const ForestSettings& placement,
                                   const Forest& forest, std::span<const glm::vec4> centres,
                                   const FarGround& ground);

} // namespace sylva::trees
