#pragma once
// A species sheet (docs/trees.md "Species"): one tree of each species side by side at the same scale, seen
// from the side, on a strip of ground, each with a person-sized marker (1.75 m) beside it. GL side: renders
// on the current context.

#include <sylva/core/Image.hpp>
#include <sylva/shader/Library.hpp>
#include <sylva/trees/ForestLook.hpp>
#include <sylva/trees/Species.hpp>

#include <cstdint>
#include <vector>

namespace sylva::trees {

/** Height of the person-sized marker beside each tree, metres. */
inline constexpr float kSheetMarkerHeight = 1.75f;

/** What renderSpeciesSheet() draws: one tree of each species in a row, with a person-sized marker. */
struct SpeciesSheetOptions {
  /** Seed of every tree (the same as `sylva tree generate --seed`). */
  std::uint64_t seed = 1;
  /** Image height, pixels (16 … 8192); the width follows from the row of trees (at most 16,384). */
  int height = 540;
  /** Metres between one tree's crown and the next one's marker. */
  float gap = 2.0f;
  /** Bark and foliage as a forest's (ForestLook: "auto" photos when fetched, else procedural). */
  ForestLook look;
};

/**
 * Renders one tree of each species (its rest pose, no wind) in a row along world x, left to right, at one
 * scale (pixels per metre the same for all), from far away along +z (almost orthographic), over a sky colour,
 * with a ground strip and a dark marker of kSheetMarkerHeight metres left of each tree. Needs a current GL
 * context. Throws sylva::Error for no species, a bad species or an image past 16,384 pixels wide.
 */
Image renderSpeciesSheet(const shader::Library& library, const std::vector<Species>& species,
                         const SpeciesSheetOptions& options);

} // namespace sylva::trees
