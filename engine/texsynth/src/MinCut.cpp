#include <sylva/texsynth/MinCut.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::texsynth {

ErrorSurface ErrorSurface::transposed() const {
  ErrorSurface t;
  t.rows = cols;
  t.cols = rows;
  t.values.resize(values.size());
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      t.values[static_cast<std::size_t>(c) * rows + r] = at(r, c);
    }
  }
  return t;
}

Cut verticalCut(const ErrorSurface& errors) {
  const int rows = errors.rows;
  const int cols = errors.cols;
  if (rows < 1 || cols < 1 || errors.values.size() != static_cast<std::size_t>(rows) * cols) {
    fail("minimum-error cut: the error surface is empty or malformed ({}x{})", cols, rows);
  }
  // Cumulative errors, accumulated from row 0 so that a path's total is summed in row order.
  std::vector<double> cumulative(errors.values.size());
  for (int c = 0; c < cols; ++c) {
    cumulative[static_cast<std::size_t>(c)] = errors.at(0, c);
  }
  const auto at = [&](int r, int c) -> double& { return cumulative[static_cast<std::size_t>(r) * cols + c]; };
  // The predecessor of (r, c) in row r − 1: straight first, then left, then right, so ties are stable.
  const auto bestBefore = [&](int r, int c) {
    int best = c;
    if (c > 0 && at(r - 1, c - 1) < at(r - 1, best)) {
      best = c - 1;
    }
    if (c + 1 < cols && at(r - 1, c + 1) < at(r - 1, best)) {
      best = c + 1;
    }
    return best;
  };
  for (int r = 1; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      at(r, c) = at(r - 1, bestBefore(r, c)) + errors.at(r, c);
    }
  }
  Cut cut;
  cut.path.resize(static_cast<std::size_t>(rows));
  int c = 0;
  for (int k = 1; k < cols; ++k) {
    if (at(rows - 1, k) < at(rows - 1, c)) {
      c = k;
    }
  }
  cut.cost = at(rows - 1, c);
  for (int r = rows - 1; r >= 0; --r) {
    cut.path[static_cast<std::size_t>(r)] = c;
    if (r > 0) {
      c = bestBefore(r, c);
    }
  }
  return cut;
}

Cut horizontalCut(const ErrorSurface& errors) {
  return verticalCut(errors.transposed());
}

std::vector<std::uint8_t> overlapMask(const ErrorSurface& errors, int leftOverlap, int lowOverlap,
                                      Cut* vertical, Cut* horizontal) {
  const int rows = errors.rows;
  const int cols = errors.cols;
  if (leftOverlap < 0 || leftOverlap > cols || lowOverlap < 0 || lowOverlap > rows) {
    fail("minimum-error cut: overlaps {}, {} do not fit a {}x{} block", leftOverlap, lowOverlap, cols, rows);
  }
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(rows) * cols, 0);
  if (leftOverlap > 0) {
    ErrorSurface strip{rows, leftOverlap, {}};
    strip.values.reserve(static_cast<std::size_t>(rows) * leftOverlap);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < leftOverlap; ++c) {
        strip.values.push_back(errors.at(r, c));
      }
    }
    const Cut cut = verticalCut(strip);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cut.path[static_cast<std::size_t>(r)]; ++c) {
        mask[static_cast<std::size_t>(r) * cols + c] = 1;
      }
    }
    if (vertical != nullptr) {
      *vertical = cut;
    }
  }
  if (lowOverlap > 0) {
    ErrorSurface strip{lowOverlap, cols, {}};
    strip.values.assign(errors.values.begin(),
                        errors.values.begin() + static_cast<std::ptrdiff_t>(lowOverlap) * cols);
    const Cut cut = horizontalCut(strip);
    for (int c = 0; c < cols; ++c) {
      for (int r = 0; r < cut.path[static_cast<std::size_t>(c)]; ++r) {
        mask[static_cast<std::size_t>(r) * cols + c] = 1;
      }
    }
    if (horizontal != nullptr) {
      *horizontal = cut;
    }
  }
  return mask;
}

std::size_t chooseCandidate(std::span<const double> errors, double tolerance, Rng& rng) {
  if (errors.empty()) {
    fail("block choice: no candidates");
  }
  if (!std::isfinite(tolerance) || tolerance < 0.0) {
    fail("tolerance: expected a finite number ≥ 0, got {}", tolerance);
  }
  double least = std::numeric_limits<double>::infinity();
  for (const double e : errors) {
    if (!std::isfinite(e)) {
      fail("block choice: a candidate's error is not finite");
    }
    least = std::min(least, e);
  }
  const double limit = (1.0 + tolerance) * least;
  std::vector<std::size_t> within;
  for (std::size_t i = 0; i < errors.size(); ++i) {
    if (errors[i] <= limit) {
      within.push_back(i);
    }
  }
  return within[rng.below(static_cast<std::uint32_t>(within.size()))];
}

} // namespace sylva::texsynth
