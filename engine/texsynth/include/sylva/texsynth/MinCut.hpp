#pragma once

#include <sylva/core/Random.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace sylva::texsynth {

/**
 * Overlap errors of two blocks, row-major: `rows` × `cols` values ≥ 0, e(r, c) = values[r * cols + c],
 * usually e = ‖B1 − B2‖² over the colour channels of the overlapping texels.
 */
struct ErrorSurface {
  int rows = 0;               ///< rows of the overlap region
  int cols = 0;               ///< columns of the overlap region
  std::vector<double> values; ///< rows × cols errors, row-major

  /** e(row, col); no bounds checks. */
  double at(int row, int col) const { return values[static_cast<std::size_t>(row) * cols + col]; }
  /** The transpose (rows and columns swapped). */
  ErrorSurface transposed() const;
};

/** A minimum-error boundary cut and its total error. */
struct Cut {
  /** Vertical cut: the column of the cut in each row. Horizontal cut: the row of the cut in each column. */
  std::vector<int> path;
  /** Sum of the errors along the cut. */
  double cost = 0.0;
};

/**
 * Vertical minimum-error boundary cut (Efros & Freeman 2001) by dynamic programming: E(0, c) = e(0, c),
 * E(r, c) = e(r, c) + min(E(r−1, c−1), E(r−1, c), E(r−1, c+1)), backtracked from the minimum of the last row.
 * The path moves at most one column per row and minimises Σ e(r, path[r]). Convention: texels left of the
 * path (c < path[r]) keep the old (left) block; the path texel and those right of it take the new block.
 * Ties prefer the straight step, then the left one. Throws sylva::Error for an empty surface.
 */
Cut verticalCut(const ErrorSurface& errors);

/**
 * Horizontal cut: the vertical cut of the transposed surface; path[c] is a row. Texels with r < path[c]
 * keep the old (lower-row) block.
 */
Cut horizontalCut(const ErrorSurface& errors);

/**
 * L-shaped overlap of a new block over old texels: `errors` covers the whole block (rows × cols). The left
 * overlap (columns < leftOverlap, every row) gets a vertical cut, the low-row overlap (rows < lowOverlap,
 * every column) a horizontal cut; the two are joined at the corner by union: a texel keeps the old value when
 * it is on the old side of either cut. Returns the mask (1 = keep old, 0 = take new), row-major; with a zero
 * overlap that cut is absent. `vertical` / `horizontal` receive the cuts when not null.
 */
std::vector<std::uint8_t> overlapMask(const ErrorSurface& errors, int leftOverlap, int lowOverlap,
                                      Cut* vertical = nullptr, Cut* horizontal = nullptr);

/**
 * Block choice (Efros & Freeman): picks uniformly at random among the candidates whose error is at most
 * (1 + tolerance) · min. Deterministic for a given generator state. Throws sylva::Error for no candidates,
 * a negative or non-finite tolerance, or a non-finite error.
 */
std::size_t chooseCandidate(std::span<const double> errors, double tolerance, Rng& rng);

} // namespace sylva::texsynth
