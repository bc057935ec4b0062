#pragma once

#include <sylva/texsynth/Texture.hpp>

#include <cstdint>

namespace sylva {
class Progress;
}

namespace sylva::texsynth {

/** Settings of image quilting. */
struct QuiltSettings {
  /** Block side, texels (4..1024; at most the source's smaller side). */
  int block = 48;
  /** Overlap between neighbouring blocks, texels; 0 picks block / 6 (at least 1). At most block / 2. */
  int overlap = 0;
  /** Candidates within (1 + tolerance) · the least overlap error are equally likely (0..10). */
  double tolerance = 0.1;
  /** Seed of the block choice; same inputs and seed give the same texture. */
  std::uint64_t seed = 1;
  /**
   * Most candidate positions searched per block (16..1,000,000): source positions on a regular grid whose
   * step grows until they fit.
   */
  int maxCandidates = 4096;

  /** The overlap in texels after the automatic choice. */
  int effectiveOverlap() const;
};

/**
 * Checks quilting settings against a source; throws a one-line sylva::Error naming the field ("block",
 * "overlap", "tolerance", "maxCandidates") or the source (too small for the block, empty).
 */
void validate(const QuiltSettings& settings, const Texture& source);

/** Number of blocks quilt() places for an output size (the total of its progress). */
int quiltBlockCount(int outWidth, int outHeight, const QuiltSettings& settings);

/**
 * Efros–Freeman image quilting: blocks placed in raster order (rows of blocks from row 0 up), each chosen by
 * SSD over its overlap with the texels already placed (colour channels) with the tolerance rule, and joined
 * by minimum-error cuts (vertical, horizontal or L-shaped). Every output texel is a copy of a source texel
 * (all channels). `outWidth`, `outHeight` in texels (1..16384). `progress` (may be null) advances once per
 * block; cancelling it throws sylva::Error("quilting cancelled").
 */
Texture quilt(const Texture& source, int outWidth, int outHeight, const QuiltSettings& settings,
              Progress* progress = nullptr);

} // namespace sylva::texsynth
