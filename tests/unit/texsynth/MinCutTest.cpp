// Minimum-error boundary cuts against brute force on small random error surfaces (vertical, horizontal,
// L-shaped), and the block choice's tolerance rule.
#include <sylva/core/Error.hpp>
#include <sylva/core/Random.hpp>
#include <sylva/texsynth/MinCut.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace sylva::texsynth {
namespace {

ErrorSurface randomSurface(int rows, int cols, Rng& rng) {
  ErrorSurface s{rows, cols, {}};
  for (int i = 0; i < rows * cols; ++i) {
    s.values.push_back(rng.uniform(0.0f, 10.0f));
  }
  return s;
}

/** Every path with one column per row moving at most one column per row; returns the cheapest. */
Cut bruteForceVertical(const ErrorSurface& s) {
  Cut best;
  best.cost = std::numeric_limits<double>::infinity();
  std::vector<int> path(static_cast<std::size_t>(s.rows), 0);
  const auto visit = [&](auto&& self, int row) -> void {
    if (row == s.rows) {
      double cost = 0.0;
      for (int r = 0; r < s.rows; ++r) {
        cost += s.at(r, path[static_cast<std::size_t>(r)]);
      }
      if (cost < best.cost) {
        best.cost = cost;
        best.path = path;
      }
      return;
    }
    for (int c = 0; c < s.cols; ++c) {
      if (row > 0 && std::abs(c - path[static_cast<std::size_t>(row - 1)]) > 1) {
        continue;
      }
      path[static_cast<std::size_t>(row)] = c;
      self(self, row + 1);
    }
  };
  visit(visit, 0);
  return best;
}

/** The brute-force horizontal cut: one row per column, enumerated directly (not through a transpose). */
Cut bruteForceHorizontal(const ErrorSurface& s) {
  Cut best;
  best.cost = std::numeric_limits<double>::infinity();
  std::vector<int> path(static_cast<std::size_t>(s.cols), 0);
  const auto visit = [&](auto&& self, int col) -> void {
    if (col == s.cols) {
      double cost = 0.0;
      for (int c = 0; c < s.cols; ++c) {
        cost += s.at(path[static_cast<std::size_t>(c)], c);
      }
      if (cost < best.cost) {
        best.cost = cost;
        best.path = path;
      }
      return;
    }
    for (int r = 0; r < s.rows; ++r) {
      if (col > 0 && std::abs(r - path[static_cast<std::size_t>(col - 1)]) > 1) {
        continue;
      }
      path[static_cast<std::size_t>(col)] = r;
      self(self, col + 1);
    }
  };
  visit(visit, 0);
  return best;
}

double pathCost(const ErrorSurface& s, const Cut& cut, bool vertical) {
  double cost = 0.0;
  for (std::size_t i = 0; i < cut.path.size(); ++i) {
    cost += vertical ? s.at(static_cast<int>(i), cut.path[i]) : s.at(cut.path[i], static_cast<int>(i));
  }
  return cost;
}

void expectConnected(const Cut& cut, int limit) {
  for (std::size_t i = 0; i < cut.path.size(); ++i) {
    EXPECT_GE(cut.path[i], 0);
    EXPECT_LT(cut.path[i], limit);
    if (i > 0) {
      EXPECT_LE(std::abs(cut.path[i] - cut.path[i - 1]), 1);
    }
  }
}

TEST(MinCut, VerticalCutEqualsBruteForce) {
  Rng rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + static_cast<int>(rng.below(7));
    const int cols = 1 + static_cast<int>(rng.below(5));
    const ErrorSurface s = randomSurface(rows, cols, rng);
    const Cut cut = verticalCut(s);
    const Cut best = bruteForceVertical(s);
    ASSERT_EQ(cut.path.size(), static_cast<std::size_t>(rows));
    expectConnected(cut, cols);
    EXPECT_NEAR(cut.cost, best.cost, 1e-9) << rows << "x" << cols;
    EXPECT_NEAR(pathCost(s, cut, true), cut.cost, 1e-9);
    EXPECT_EQ(cut.path, best.path) << "random errors have a unique optimum";
  }
}

TEST(MinCut, HorizontalCutEqualsBruteForce) {
  Rng rng(12);
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = 1 + static_cast<int>(rng.below(5));
    const int cols = 1 + static_cast<int>(rng.below(7));
    const ErrorSurface s = randomSurface(rows, cols, rng);
    const Cut cut = horizontalCut(s);
    const Cut best = bruteForceHorizontal(s);
    ASSERT_EQ(cut.path.size(), static_cast<std::size_t>(cols));
    expectConnected(cut, rows);
    EXPECT_NEAR(cut.cost, best.cost, 1e-9);
    EXPECT_NEAR(pathCost(s, cut, false), cut.cost, 1e-9);
    EXPECT_EQ(cut.path, best.path);
  }
}

TEST(MinCut, LShapedMaskIsTheUnionOfOptimalCuts) {
  Rng rng(13);
  for (int trial = 0; trial < 60; ++trial) {
    const int size = 4 + static_cast<int>(rng.below(4));
    const int left = static_cast<int>(rng.below(4));
    const int low = static_cast<int>(rng.below(4));
    const ErrorSurface s = randomSurface(size, size, rng);
    Cut vertical;
    Cut horizontal;
    const std::vector<std::uint8_t> mask = overlapMask(s, left, low, &vertical, &horizontal);
    std::vector<int> vPath(static_cast<std::size_t>(size), 0);
    std::vector<int> hPath(static_cast<std::size_t>(size), 0);
    if (left > 0) {
      ErrorSurface strip{size, left, {}};
      for (int r = 0; r < size; ++r) {
        for (int c = 0; c < left; ++c) {
          strip.values.push_back(s.at(r, c));
        }
      }
      const Cut best = bruteForceVertical(strip);
      EXPECT_NEAR(vertical.cost, best.cost, 1e-9);
      vPath = best.path;
    }
    if (low > 0) {
      ErrorSurface strip{low, size, {}};
      for (int r = 0; r < low; ++r) {
        for (int c = 0; c < size; ++c) {
          strip.values.push_back(s.at(r, c));
        }
      }
      const Cut best = bruteForceHorizontal(strip);
      EXPECT_NEAR(horizontal.cost, best.cost, 1e-9);
      hPath = best.path;
    }
    for (int r = 0; r < size; ++r) {
      for (int c = 0; c < size; ++c) {
        const bool old = c < vPath[static_cast<std::size_t>(r)] || r < hPath[static_cast<std::size_t>(c)];
        EXPECT_EQ(mask[static_cast<std::size_t>(r) * size + c] != 0, old)
            << "texel " << c << "," << r << " overlaps " << left << "," << low;
      }
    }
  }
}

TEST(MinCut, MalformedSurfacesAreErrors) {
  EXPECT_THROW(verticalCut(ErrorSurface{}), Error);
  EXPECT_THROW(verticalCut(ErrorSurface{2, 2, {1.0}}), Error);
  EXPECT_THROW(overlapMask(ErrorSurface{2, 2, {1, 2, 3, 4}}, 3, 0), Error);
}

TEST(BlockChoice, ObeysTheTolerance) {
  const std::vector<double> errors{5.0, 1.0, 1.09, 1.11, 1.1, 3.0, 1.0001};
  const double tolerance = 0.1;
  std::set<std::size_t> chosen;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    Rng rng(seed);
    const std::size_t i = chooseCandidate(errors, tolerance, rng);
    ASSERT_LT(i, errors.size());
    EXPECT_LE(errors[i], (1.0 + tolerance) * 1.0) << "candidate " << i;
    chosen.insert(i);
  }
  // Every candidate within (1 + 0.1) · min is reachable, none outside.
  EXPECT_EQ(chosen, (std::set<std::size_t>{1, 2, 4, 6}));
  Rng rng(1);
  EXPECT_EQ(chooseCandidate(errors, 0.0, rng), 1u);
}

TEST(BlockChoice, BadInputsAreErrors) {
  Rng rng(1);
  const std::vector<double> errors{1.0, 2.0};
  EXPECT_THROW(chooseCandidate({}, 0.1, rng), Error);
  EXPECT_THROW(chooseCandidate(errors, std::nan(""), rng), Error);
  EXPECT_THROW(chooseCandidate(errors, -0.5, rng), Error);
  const std::vector<double> bad{1.0, std::nan("")};
  EXPECT_THROW(chooseCandidate(bad, 0.1, rng), Error);
}

} // namespace
} // namespace sylva::texsynth
