#pragma once

#include <vector>

namespace sylva::texsynth::detail {

/** Squared colour difference of two texels (their first three channels). */
inline double colourError(const float* a, const float* b) {
  const double dr = a[0] - b[0];
  const double dg = a[1] - b[1];
  const double db = a[2] - b[2];
  return dr * dr + dg * dg + db * db;
}

/** Top-left (lowest row, lowest column) texel of a candidate block in a source. */
struct Position {
  int x = 0;
  int y = 0;
};

/**
 * Every position where a blockW × blockH block fits in a sourceW × sourceH source, on a regular grid whose
 * step (the same along both axes) is the smallest that keeps the count at most maxCandidates. The last
 * position along each axis is always included, so the far edge of the source is reachable.
 */
inline std::vector<Position> candidateGrid(int sourceW, int sourceH, int blockW, int blockH,
                                           int maxCandidates) {
  const int spanX = sourceW - blockW + 1;
  const int spanY = sourceH - blockH + 1;
  std::vector<Position> positions;
  if (spanX < 1 || spanY < 1) {
    return positions;
  }
  const auto axis = [](int span, int step) {
    std::vector<int> values;
    for (int v = 0; v < span; v += step) {
      values.push_back(v);
    }
    if (values.back() != span - 1) {
      values.push_back(span - 1);
    }
    return values;
  };
  int step = 1;
  while (true) {
    const std::vector<int> xs = axis(spanX, step);
    const std::vector<int> ys = axis(spanY, step);
    if (static_cast<long long>(xs.size()) * static_cast<long long>(ys.size()) <= maxCandidates ||
        (xs.size() <= 2 && ys.size() <= 2)) {
      for (const int y : ys) {
        for (const int x : xs) {
          positions.push_back({x, y});
        }
      }
      return positions;
    }
    ++step;
  }
}

} // namespace sylva::texsynth::detail
