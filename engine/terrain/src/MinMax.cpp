#include <sylva/terrain/MinMax.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Parallel.hpp>

#include <algorithm>
#include <bit>
#include <cmath>

namespace sylva::terrain {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// Internal "empty" range: unions with min/max need no NaN branches; converted to NaN at the public boundary.
constexpr HeightRange kEmpty{kInf, -kInf};
constexpr long long kMaxBlocks = 1LL << 26;

int floorLog2(int v) {
  return static_cast<int>(std::bit_width(static_cast<unsigned>(v))) - 1;
}

HeightRange normalised(const HeightRange& r) {
  return r.min <= r.max ? r : HeightRange::absent();
}

} // namespace

void HeightRange::include(float h) {
  if (std::isnan(h)) {
    return;
  }
  if (present()) {
    min = std::min(min, h);
    max = std::max(max, h);
  } else {
    min = h;
    max = h;
  }
}

void HeightRange::include(const HeightRange& other) {
  if (!other.present()) {
    return;
  }
  if (present()) {
    min = std::min(min, other.min);
    max = std::max(max, other.max);
  } else {
    *this = other;
  }
}

bool HeightRange::operator==(const HeightRange& other) const {
  if (!present() || !other.present()) {
    return present() == other.present();
  }
  return min == other.min && max == other.max;
}

HeightRange scanRange(const HeightField& field, int i0, int i1, int j0, int j1) {
  HeightRange r;
  i0 = std::max(i0, 0);
  j0 = std::max(j0, 0);
  i1 = std::min(i1, field.width() - 1);
  j1 = std::min(j1, field.height() - 1);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      r.include(field.at(i, j));
    }
  }
  return r;
}

// ---------------------------------------------------------------------------------------------------------------
// MinMaxRmq

std::size_t MinMaxRmq::requiredBytes(int width, int height) {
  if (width <= 0 || height <= 0) {
    return 0;
  }
  const auto sumOver = [](int n) {
    std::size_t sum = 0;
    for (int k = 0; (1LL << k) <= n; ++k) {
      sum += static_cast<std::size_t>(n - (1 << k) + 1);
    }
    return sum;
  };
  const std::size_t sx = sumOver(width);
  const std::size_t sz = sumOver(height);
  const std::size_t limit = std::numeric_limits<std::size_t>::max() / sizeof(Entry);
  if (sx != 0 && sz > limit / sx) {
    return std::numeric_limits<std::size_t>::max();
  }
  return sx * sz * sizeof(Entry);
}

MinMaxRmq::MinMaxRmq(const HeightField& field, std::size_t maxBytes) {
  const int w = field.width();
  const int h = field.height();
  if (w <= 0 || h <= 0) {
    fail("MinMaxRmq: empty height field ({}×{} samples)", w, h);
  }
  const std::size_t bytes = requiredBytes(w, h);
  if (bytes > maxBytes) {
    fail("MinMaxRmq: a {}×{} field needs {} MiB of sparse tables, above the limit of {} MiB; use "
         "MinMaxPyramid",
         w, h, bytes >> 20, maxBytes >> 20);
  }
  mWidth = w;
  mHeight = h;
  mLevelsX = floorLog2(w) + 1;
  mLevelsZ = floorLog2(h) + 1;
  mOffsets.resize(static_cast<std::size_t>(mLevelsX * mLevelsZ));
  std::size_t offset = 0;
  for (int kx = 0; kx < mLevelsX; ++kx) {
    for (int kz = 0; kz < mLevelsZ; ++kz) {
      mOffsets[static_cast<std::size_t>(kx * mLevelsZ + kz)] = offset;
      offset += static_cast<std::size_t>(w - (1 << kx) + 1) * static_cast<std::size_t>(h - (1 << kz) + 1);
    }
  }
  mData.resize(offset);

  // Table (0, 0): the samples themselves.
  const std::vector<float>& samples = field.samples();
  parallelFor(
      static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
          const float v = samples[k];
          mData[k] = std::isnan(v) ? Entry{kInf, -kInf} : Entry{v, v};
        }
      },
      4096);

  for (int kx = 0; kx < mLevelsX; ++kx) {
    for (int kz = 0; kz < mLevelsZ; ++kz) {
      if (kx == 0 && kz == 0) {
        continue;
      }
      const std::size_t tw = static_cast<std::size_t>(w - (1 << kx) + 1);
      const std::size_t th = static_cast<std::size_t>(h - (1 << kz) + 1);
      Entry* dst = mData.data() + mOffsets[static_cast<std::size_t>(kx * mLevelsZ + kz)];
      // Halve along z when possible (source shares the width), else along x.
      const bool alongZ = kz > 0;
      const int skx = alongZ ? kx : kx - 1;
      const int skz = alongZ ? kz - 1 : kz;
      const std::size_t sw = static_cast<std::size_t>(w - (1 << skx) + 1);
      const Entry* src = mData.data() + mOffsets[static_cast<std::size_t>(skx * mLevelsZ + skz)];
      const std::size_t step = alongZ ? sw * (std::size_t{1} << (kz - 1)) : (std::size_t{1} << (kx - 1));
      parallelFor(
          th,
          [&](std::size_t r0, std::size_t r1) {
            for (std::size_t r = r0; r < r1; ++r) {
              const Entry* a = src + r * sw;
              Entry* out = dst + r * tw;
              for (std::size_t c = 0; c < tw; ++c) {
                const Entry& e0 = a[c];
                const Entry& e1 = a[c + step];
                out[c] = Entry{std::min(e0.lo, e1.lo), std::max(e0.hi, e1.hi)};
              }
            }
          },
          16);
    }
  }
}

HeightRange MinMaxRmq::query(int i0, int i1, int j0, int j1) const {
  if (i0 < 0 || j0 < 0 || i1 >= mWidth || j1 >= mHeight || i0 > i1 || j0 > j1) {
    fail("MinMaxRmq::query: rectangle [{}, {}]×[{}, {}] is empty or outside the {}×{} field", i0, i1, j0, j1,
         mWidth, mHeight);
  }
  const int kx = floorLog2(i1 - i0 + 1);
  const int kz = floorLog2(j1 - j0 + 1);
  const std::size_t tw = static_cast<std::size_t>(mWidth - (1 << kx) + 1);
  const Entry* t = mData.data() + mOffsets[static_cast<std::size_t>(kx * mLevelsZ + kz)];
  const std::size_t ia = static_cast<std::size_t>(i0);
  const std::size_t ib = static_cast<std::size_t>(i1 - (1 << kx) + 1);
  const std::size_t ja = static_cast<std::size_t>(j0) * tw;
  const std::size_t jb = static_cast<std::size_t>(j1 - (1 << kz) + 1) * tw;
  const Entry& a = t[ja + ia];
  const Entry& b = t[ja + ib];
  const Entry& c = t[jb + ia];
  const Entry& d = t[jb + ib];
  const HeightRange r{std::min(std::min(a.lo, b.lo), std::min(c.lo, d.lo)),
                      std::max(std::max(a.hi, b.hi), std::max(c.hi, d.hi))};
  return normalised(r);
}

// ---------------------------------------------------------------------------------------------------------------
// MinMaxPyramid

MinMaxPyramid::MinMaxPyramid(const HeightField& field, int leafSize) {
  const int w = field.width();
  const int h = field.height();
  if (w <= 0 || h <= 0) {
    fail("MinMaxPyramid: empty height field ({}×{} samples)", w, h);
  }
  if (leafSize < 1) {
    fail("MinMaxPyramid: leafSize must be at least 1 sample interval, got {}", leafSize);
  }
  // Blocks cover [b·L, b·L + L]; enough of them to reach sample w − 1 (one block for a single column).
  const int bx = std::max(1, (w - 1 + leafSize - 1) / leafSize);
  const int bz = std::max(1, (h - 1 + leafSize - 1) / leafSize);
  *this = fromLeaves(
      bx, bz,
      [&](int x, int z) {
        return scanRange(field, x * leafSize, x * leafSize + leafSize, z * leafSize, z * leafSize + leafSize);
      },
      leafSize);
}

MinMaxPyramid MinMaxPyramid::fromLeaves(int blocksX, int blocksZ, const LeafFunction& leaf, int leafSize) {
  if (blocksX <= 0 || blocksZ <= 0 || static_cast<long long>(blocksX) * blocksZ > kMaxBlocks) {
    fail("MinMaxPyramid: leaf grid {}×{} is empty or larger than {} blocks", blocksX, blocksZ, kMaxBlocks);
  }
  if (leafSize < 0) {
    fail("MinMaxPyramid: leafSize must be ≥ 0, got {}", leafSize);
  }
  MinMaxPyramid p;
  p.mLeafSize = leafSize;
  Level base;
  base.width = blocksX;
  base.height = blocksZ;
  base.ranges.resize(static_cast<std::size_t>(blocksX) * static_cast<std::size_t>(blocksZ));
  parallelFor(
      static_cast<std::size_t>(blocksZ),
      [&](std::size_t z0, std::size_t z1) {
        for (std::size_t z = z0; z < z1; ++z) {
          for (int x = 0; x < blocksX; ++x) {
            const HeightRange r = leaf(x, static_cast<int>(z));
            base.ranges[z * static_cast<std::size_t>(blocksX) + static_cast<std::size_t>(x)] =
                r.present() ? r : kEmpty;
          }
        }
      },
      1);
  p.mLevels.push_back(std::move(base));
  p.buildUpperLevels();
  return p;
}

void MinMaxPyramid::buildUpperLevels() {
  while (mLevels.back().width > 1 || mLevels.back().height > 1) {
    const Level& child = mLevels.back();
    Level parent;
    parent.width = (child.width + 1) / 2;
    parent.height = (child.height + 1) / 2;
    parent.ranges.assign(static_cast<std::size_t>(parent.width) * static_cast<std::size_t>(parent.height),
                         kEmpty);
    for (int z = 0; z < child.height; ++z) {
      for (int x = 0; x < child.width; ++x) {
        const HeightRange& c =
            child.ranges[static_cast<std::size_t>(z) * static_cast<std::size_t>(child.width) +
                         static_cast<std::size_t>(x)];
        HeightRange& p =
            parent.ranges[static_cast<std::size_t>(z / 2) * static_cast<std::size_t>(parent.width) +
                          static_cast<std::size_t>(x / 2)];
        p.min = std::min(p.min, c.min);
        p.max = std::max(p.max, c.max);
      }
    }
    mLevels.push_back(std::move(parent));
  }
}

HeightRange MinMaxPyramid::bound(int i0, int i1, int j0, int j1) const {
  if (mLeafSize <= 0 || mLevels.empty()) {
    fail("MinMaxPyramid::bound: needs a pyramid with a known leaf size in samples");
  }
  if (i0 > i1 || j0 > j1) {
    fail("MinMaxPyramid::bound: empty rectangle [{}, {}]×[{}, {}]", i0, i1, j0, j1);
  }
  i0 = std::max(i0, 0);
  j0 = std::max(j0, 0);
  i1 = std::max(i1, i0);
  j1 = std::max(j1, j0);
  const long long span = std::max(i1 - i0, j1 - j0);
  // Smallest level whose block (L·2^k samples) is at least the span: there the rectangle touches ≤ 2 blocks
  // per axis. One level finer sometimes does too and is tighter.
  int k = 0;
  while (static_cast<long long>(mLeafSize) << k < span) {
    ++k;
  }
  // Blocks b0..b1 of `level` that cover samples [a0, a1] along an axis with `count` blocks. A sample on the
  // far border of the last block (the last sample) belongs to that block, not to a block beyond the grid.
  const auto blocks = [&](int level, int count, int a0, int a1, int& b0, int& b1) {
    const long long size = static_cast<long long>(mLeafSize) << level;
    b0 = static_cast<int>(std::min<long long>(a0 / size, count - 1));
    b1 = static_cast<int>(std::clamp<long long>((a1 + size - 1) / size - 1, b0, count - 1));
    return b1 - b0 <= 1;
  };
  const auto fits = [&](int level, int& bx0, int& bx1, int& bz0, int& bz1) {
    if (level >= levelCount()) {
      return false;
    }
    const bool x = blocks(level, blocksX(level), i0, i1, bx0, bx1);
    const bool z = blocks(level, blocksZ(level), j0, j1, bz0, bz1);
    return x && z;
  };
  int bx0 = 0, bx1 = 0, bz0 = 0, bz1 = 0;
  if (k > 0 && fits(k - 1, bx0, bx1, bz0, bz1)) {
    --k;
  } else if (!fits(k, bx0, bx1, bz0, bz1)) {
    // Larger than the whole pyramid: the root covers everything.
    return node(levelCount() - 1, 0, 0);
  }
  HeightRange r;
  for (int bz = bz0; bz <= bz1; ++bz) {
    for (int bx = bx0; bx <= bx1; ++bx) {
      r.include(node(k, bx, bz));
    }
  }
  return r;
}

std::size_t MinMaxPyramid::memoryBytes() const {
  std::size_t bytes = 0;
  for (const Level& l : mLevels) {
    bytes += l.ranges.size() * sizeof(HeightRange);
  }
  return bytes;
}

} // namespace sylva::terrain
