// Streamed terrain tiles on the CPU: tile sources (pyramids, the procedural world), the RAM cache with its
// loader threads, and the per-view tile selection (docs/terrain-data.md, "Streaming").
#include <sylva/terrain/TileSelection.hpp>
#include <sylva/terrain/TileSource.hpp>
#include <sylva/terrain/TileStreamer.hpp>

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

namespace sylva::terrain {
namespace {

constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

class PyramidSource final : public TileSource {
public:
  explicit PyramidSource(std::shared_ptr<TilePyramid> pyramid) : mPyramid(std::move(pyramid)) {}
  const PyramidInfo& layout() const override { return mPyramid->info(); }
  TileSummary tileSummary(const TileKey& key) const override { return mPyramid->summary(key); }
  std::shared_ptr<const TileData> loadTile(const TileKey& key) const override { return mPyramid->tile(key); }
  std::string describe() const override {
    const PyramidInfo& i = mPyramid->info();
    return fmt::format("pyramid {} ({}x{} samples at {:g} x {:g} m, {} levels of tiles of {})",
                       mPyramid->dir().string(), i.width, i.height, i.spacingX, i.spacingZ, i.levels,
                       i.tileSize);
  }

private:
  std::shared_ptr<TilePyramid> mPyramid;
};

bool isPowerOfTwo(int n) {
  return n > 0 && (n & (n - 1)) == 0;
}

} // namespace

std::shared_ptr<const TileSource> pyramidSource(const std::filesystem::path& dir) {
  // The pyramid's own cache only needs the tiles being loaded at once; the streamer holds the rest.
  auto pyramid = TilePyramid::open(dir, std::size_t{8} << 20);
  if (!isPowerOfTwo(pyramid->info().tileSize)) {
    fail("{}: tile size {} is not a power of two, which streaming needs (rebuild with --tile-size 64, 128, "
         "256, …)",
         (dir / "pyramid.json").string(), pyramid->info().tileSize);
  }
  return std::make_shared<PyramidSource>(std::move(pyramid));
}

// ---- the procedural world ----

ProceduralWorld::ProceduralWorld(const ProceduralSpec& spec, int side, float spacing, int tileSize)
    : mNoise(spec) {
  if (!isPowerOfTwo(tileSize)) {
    fail("procedural world: tile size {} is not a power of two", tileSize);
  }
  if (!(spacing > 0.0f) || !std::isfinite(spacing)) {
    fail("procedural world: spacing {} must be finite and > 0 metres", spacing);
  }
  mInfo = PyramidInfo::plan(side, side, spacing, spacing, tileSize);
  mInfo.minHeight = 0.0f;
  mInfo.maxHeight = spec.heightScale;
  mInfo.complete = true;
  mInfo.source = describe();
}

TileSummary ProceduralWorld::tileSummary(const TileKey& key) const {
  (void)mInfo.level(key.level);
  return {0.0f, mNoise.spec().heightScale, std::numeric_limits<float>::infinity()};
}

std::shared_ptr<const TileData> ProceduralWorld::loadTile(const TileKey& key) const {
  const PyramidLevel l = mInfo.level(key.level);
  if (key.x < 0 || key.y < 0 || key.x >= l.tilesX || key.y >= l.tilesY) {
    fail("procedural world: no tile {},{} at level {}", key.x, key.y, key.level);
  }
  const int T = mInfo.tileSize;
  auto tile = std::make_shared<TileData>();
  tile->key = key;
  tile->size = T;
  tile->heights.assign(static_cast<std::size_t>(T + 1) * static_cast<std::size_t>(T + 1), kNaNf);
  const double step = std::ldexp(1.0, key.level);
  for (int b = 0; b <= T; ++b) {
    const long long j = static_cast<long long>(key.y) * T + b;
    if (j >= l.height) {
      break;
    }
    // Level-0 index of the sample: min(2^L · j, height − 1), as decimation with clamping gives.
    const double z = static_cast<double>(std::min(static_cast<long long>(j * step),
                                                  static_cast<long long>(mInfo.height - 1))) *
                     mInfo.spacingZ;
    for (int a = 0; a <= T; ++a) {
      const long long i = static_cast<long long>(key.x) * T + a;
      if (i >= l.width) {
        break;
      }
      const double x = static_cast<double>(std::min(static_cast<long long>(i * step),
                                                    static_cast<long long>(mInfo.width - 1))) *
                       mInfo.spacingX;
      tile->heights[static_cast<std::size_t>(b) * (T + 1) + a] = mNoise.sample(x, z);
    }
  }
  tile->summary = tileSummary(key); // the noise's bound, as the selection saw it before the tile loaded
  return tile;
}

std::string ProceduralWorld::describe() const {
  return fmt::format("procedural world ({} seed {}, {}x{} samples at {:g} m, {} levels of tiles of {})",
                     procedureTypeName(mNoise.spec().type), mNoise.spec().seed, mInfo.width, mInfo.height,
                     mInfo.spacingX, mInfo.levels, mInfo.tileSize);
}

float ProceduralWorld::heightAt(double x, double z) const {
  const double gx = std::clamp(x / mInfo.spacingX, 0.0, static_cast<double>(mInfo.width - 1));
  const double gz = std::clamp(z / mInfo.spacingZ, 0.0, static_cast<double>(mInfo.height - 1));
  const double i = std::min(std::floor(gx), static_cast<double>(mInfo.width - 2));
  const double j = std::min(std::floor(gz), static_cast<double>(mInfo.height - 2));
  const double tx = gx - i;
  const double tz = gz - j;
  const auto h = [&](double a, double b) {
    return static_cast<double>(mNoise.sample(a * mInfo.spacingX, b * mInfo.spacingZ));
  };
  const double top = h(i, j) + tx * (h(i + 1, j) - h(i, j));
  const double bottom = h(i, j + 1) + tx * (h(i + 1, j + 1) - h(i, j + 1));
  return static_cast<float>(top + tz * (bottom - top));
}

// ---- the RAM cache ----

TileStreamer::TileStreamer(std::shared_ptr<const TileSource> source, std::size_t ramBudget, int loaders,
                           std::size_t pinnedTiles)
    : mSource(std::move(source)), mBudget(ramBudget) {
  const PyramidInfo& info = mSource->layout();
  if (mBudget < 64 * tileBytes()) {
    fail("RAM budget {:.2f} MB holds fewer than 64 tiles of {}x{} samples ({:.2f} MB); raise it",
         static_cast<double>(mBudget) / 1.0e6, info.tileSize + 1, info.tileSize + 1,
         static_cast<double>(64 * tileBytes()) / 1.0e6);
  }
  // Whole levels from the top while they fit in `pinnedTiles` and half the budget.
  mPinnedLevel = info.levels - 1;
  std::size_t count = 1;
  for (int level = info.levels - 2; level >= 0; --level) {
    const PyramidLevel l = info.level(level);
    const std::size_t more = static_cast<std::size_t>(l.tilesX) * static_cast<std::size_t>(l.tilesY);
    if (count + more > pinnedTiles || (count + more) * tileBytes() > mBudget / 2) {
      break;
    }
    count += more;
    mPinnedLevel = level;
  }
  if (count * tileBytes() > mBudget) {
    fail("RAM budget {:.1f} MB is smaller than the coarsest level's {} tiles ({:.1f} MB)", mBudget / 1.0e6,
         count, static_cast<double>(count * tileBytes()) / 1.0e6);
  }
  for (int level = info.levels - 1; level >= mPinnedLevel; --level) {
    const PyramidLevel l = info.level(level);
    for (int y = 0; y < l.tilesY; ++y) {
      for (int x = 0; x < l.tilesX; ++x) {
        const TileKey key{level, x, y};
        insert(key, mSource->loadTile(key));
        mTiles.at(key).pins = 1 << 20; // never dropped
        ++mStats.loaded;
      }
    }
  }
  for (int k = 0; k < std::max(loaders, 1); ++k) {
    mThreads.emplace_back([this] { loaderLoop(); });
  }
}

TileStreamer::~TileStreamer() {
  {
    const std::lock_guard lock(mMutex);
    mStop = true;
  }
  mWake.notify_all();
  for (std::thread& t : mThreads) {
    t.join();
  }
}

std::size_t TileStreamer::tileBytes() const {
  const auto n = static_cast<std::size_t>(mSource->layout().tileSize + 1);
  return n * n * sizeof(float) + sizeof(TileData);
}

void TileStreamer::beginFrame() {
  const std::lock_guard lock(mMutex);
  for (auto it = mQueue.begin(); it != mQueue.end();) {
    it = mRenewed.count(it->first) != 0 ? std::next(it) : mQueue.erase(it);
  }
  mRenewed.clear();
}

void TileStreamer::request(const TileKey& key, float priority) {
  {
    const std::lock_guard lock(mMutex);
    if (mTiles.count(key) != 0 || mLoading.count(key) != 0 || mFailedKeys.count(key) != 0) {
      return;
    }
    mRenewed.insert(key);
    auto [it, inserted] = mQueue.emplace(key, priority);
    if (!inserted) {
      it->second = std::min(it->second, priority);
    }
  }
  mWake.notify_one();
}

std::shared_ptr<const TileData> TileStreamer::get(const TileKey& key) {
  const std::lock_guard lock(mMutex);
  const auto it = mTiles.find(key);
  if (it == mTiles.end()) {
    return nullptr;
  }
  mOrder.splice(mOrder.begin(), mOrder, it->second.order);
  return it->second.tile;
}

bool TileStreamer::holds(const TileKey& key) const {
  const std::lock_guard lock(mMutex);
  return mTiles.count(key) != 0;
}

void TileStreamer::pin(const TileKey& key) {
  const std::lock_guard lock(mMutex);
  const auto it = mTiles.find(key);
  if (it == mTiles.end()) {
    fail("tile streamer: pin of tile {}/{}/{} that is not in RAM", key.level, key.y, key.x);
  }
  ++it->second.pins;
}

void TileStreamer::unpin(const TileKey& key) {
  const std::lock_guard lock(mMutex);
  const auto it = mTiles.find(key);
  if (it != mTiles.end() && it->second.pins > 0) {
    --it->second.pins;
  }
}

void TileStreamer::insert(const TileKey& key, std::shared_ptr<const TileData> tile) {
  // Caller holds the lock (or is the constructor).
  const std::size_t bytes = tileBytes();
  // Drop least recently used, unpinned tiles until the new one fits.
  for (auto it = mOrder.end(); mStats.residentBytes + bytes > mBudget && it != mOrder.begin();) {
    --it;
    const auto entry = mTiles.find(*it);
    if (entry->second.pins > 0) {
      continue;
    }
    it = mOrder.erase(it);
    mTiles.erase(entry);
    mStats.residentBytes -= bytes;
    ++mStats.evicted;
  }
  mOrder.push_front(key);
  mTiles.emplace(key, Entry{std::move(tile), mOrder.begin(), 0});
  mStats.residentBytes += bytes;
  mStats.peakBytes = std::max(mStats.peakBytes, mStats.residentBytes);
}

void TileStreamer::loaderLoop() {
  std::unique_lock lock(mMutex);
  while (true) {
    mWake.wait(lock, [this] { return mStop || !mQueue.empty(); });
    if (mStop) {
      return;
    }
    auto best = std::min_element(mQueue.begin(), mQueue.end(),
                                 [](const auto& a, const auto& b) { return a.second < b.second; });
    const TileKey key = best->first;
    mQueue.erase(best);
    mLoading.insert(key);
    lock.unlock();
    std::shared_ptr<const TileData> tile;
    const auto start = std::chrono::steady_clock::now();
    try {
      tile = mSource->loadTile(key);
    } catch (const Error& e) {
      log::error("{}", e.what());
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    lock.lock();
    mLoading.erase(key);
    mStats.loadSeconds += seconds;
    if (tile) {
      insert(key, std::move(tile));
      ++mStats.loaded;
    } else {
      mFailedKeys.insert(key);
      ++mStats.failed;
    }
    if (mQueue.empty() && mLoading.empty()) {
      mIdle.notify_all();
    }
  }
}

void TileStreamer::waitIdle() {
  std::unique_lock lock(mMutex);
  mIdle.wait(lock, [this] { return mQueue.empty() && mLoading.empty(); });
}

StreamerStats TileStreamer::stats() const {
  const std::lock_guard lock(mMutex);
  StreamerStats s = mStats;
  s.residentTiles = mTiles.size();
  s.queued = mQueue.size();
  return s;
}

// ---- selection ----

glm::dvec3 tileFootprint(const PyramidInfo& layout, const TileKey& key) {
  const double samples = std::ldexp(static_cast<double>(layout.tileSize), key.level);
  return {key.x * samples * layout.spacingX, key.y * samples * layout.spacingZ, samples * layout.spacingX};
}

namespace {

std::uint64_t packKey(int level, int x, int y) {
  return (static_cast<std::uint64_t>(level) << 56) |
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 28) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(y));
}

} // namespace

TileSelection selectTiles(const PyramidInfo& layout,
                          const std::function<TileSummary(const TileKey&)>& summary,
                          const std::function<bool(const TileKey&)>& resident, const glm::dvec3& camera,
                          const Frustum* frustum, const TileLodConfig& config) {
  if (!(config.lodDistanceFactor > 0.0f)) {
    fail("tile selection: LOD distance factor {} must be > 0", config.lodDistanceFactor);
  }
  TileSelection result;
  const int top = layout.levels - 1;
  if (!resident({top, 0, 0})) {
    fail("tile selection: the top tile is not resident");
  }
  const double spacingRatio = static_cast<double>(layout.spacingZ) / layout.spacingX;
  // Pass 1: the wanted splits, limited to resident children; culled tiles noted.
  std::unordered_set<std::uint64_t> split;
  std::unordered_set<std::uint64_t> culled;
  std::vector<TileKey> stack{{top, 0, 0}};
  std::vector<std::vector<TileKey>> splitByLevel(static_cast<std::size_t>(layout.levels));
  // Whether a tile has data and its box meets the frustum; its box (footprint × height range) in `lo`, `hi`.
  const auto visible = [&](const TileKey& key, glm::dvec3& lo, glm::dvec3& hi) {
    const glm::dvec3 f = tileFootprint(layout, key);
    const TileSummary s = summary(key);
    if (std::isnan(s.minHeight)) {
      return false; // nothing to draw
    }
    lo = glm::dvec3(f.x, s.minHeight, f.y);
    hi = glm::dvec3(f.x + f.z, s.maxHeight, f.y + f.z * spacingRatio);
    if (frustum != nullptr && config.frustumCull) {
      return frustum->intersects(Aabb{glm::vec3(lo - camera), glm::vec3(hi - camera)});
    }
    return true;
  };
  while (!stack.empty()) {
    const TileKey key = stack.back();
    stack.pop_back();
    glm::dvec3 lo;
    glm::dvec3 hi;
    if (!visible(key, lo, hi)) {
      culled.insert(packKey(key.level, key.x, key.y));
      ++result.culled;
      continue;
    }
    if (key.level <= config.finestLevel) {
      continue;
    }
    const glm::dvec3 nearest = glm::clamp(camera, lo, hi);
    const double distance = glm::length(camera - nearest);
    if (!(distance < config.lodDistanceFactor * std::max(hi.x - lo.x, hi.z - lo.z))) {
      continue;
    }
    // Split only into children that are all resident, except those that will be culled (never drawn).
    const PyramidLevel below = layout.level(key.level - 1);
    std::vector<TileKey> children;
    bool all = true;
    for (int cy = 2 * key.y; cy <= std::min(2 * key.y + 1, below.tilesY - 1); ++cy) {
      for (int cx = 2 * key.x; cx <= std::min(2 * key.x + 1, below.tilesX - 1); ++cx) {
        const TileKey child{key.level - 1, cx, cy};
        children.push_back(child);
        glm::dvec3 clo;
        glm::dvec3 chi;
        if (!resident(child) && visible(child, clo, chi)) {
          all = false;
          result.missing.push_back(child);
        }
      }
    }
    if (!all) {
      continue;
    }
    split.insert(packKey(key.level, key.x, key.y));
    splitByLevel[static_cast<std::size_t>(key.level)].push_back(key);
    for (const TileKey& c : children) {
      stack.push_back(c);
    }
  }

  // Pass 2, coarse to fine: a split tile whose same-level neighbour does not exist (its parent is drawn whole
  // and visible) would put tiles two levels apart side by side: undo the split (its subtree goes with it).
  const auto exists = [&](int level, int x, int y) {
    return level == top || split.count(packKey(level + 1, x >> 1, y >> 1)) != 0;
  };
  // Whether an ancestor of tile (level, x, y) was dropped (outside the frustum or without data): nothing is
  // drawn there, so no edge can meet it.
  const auto hiddenAbove = [&](int level, int x, int y) {
    for (int l = level + 1; l <= top; ++l) {
      x >>= 1;
      y >>= 1;
      if (culled.count(packKey(l, x, y)) != 0) {
        return true;
      }
    }
    return false;
  };
  for (int level = top - 1; level >= 1; --level) {
    const PyramidLevel l = layout.level(level);
    for (const TileKey& key : splitByLevel[static_cast<std::size_t>(level)]) {
      if (!exists(level, key.x, key.y)) {
        split.erase(packKey(level, key.x, key.y)); // its parent's split was undone
        continue;
      }
      bool keep = true;
      for (int dy = -1; dy <= 1 && keep; ++dy) {
        for (int dx = -1; dx <= 1 && keep; ++dx) {
          const int nx = key.x + dx;
          const int ny = key.y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= l.tilesX || ny >= l.tilesY) {
            continue;
          }
          if (!exists(level, nx, ny) && !hiddenAbove(level, nx, ny)) {
            keep = false;
          }
        }
      }
      if (!keep) {
        split.erase(packKey(level, key.x, key.y));
        ++result.coarsened;
      }
    }
  }

  // Pass 3: the leaves, with the edges that border a coarser drawn tile.
  stack.assign(1, {top, 0, 0});
  while (!stack.empty()) {
    const TileKey key = stack.back();
    stack.pop_back();
    if (culled.count(packKey(key.level, key.x, key.y)) != 0) {
      continue;
    }
    result.tree.push_back(key);
    if (split.count(packKey(key.level, key.x, key.y)) != 0) {
      const PyramidLevel below = layout.level(key.level - 1);
      for (int cy = std::min(2 * key.y + 1, below.tilesY - 1); cy >= 2 * key.y; --cy) {
        for (int cx = std::min(2 * key.x + 1, below.tilesX - 1); cx >= 2 * key.x; --cx) {
          stack.push_back({key.level - 1, cx, cy});
        }
      }
      continue;
    }
    SelectedTile tile{key, 0};
    if (key.level < top) {
      const PyramidLevel l = layout.level(key.level);
      const int nx[4] = {key.x - 1, key.x, key.x + 1, key.x};
      const int ny[4] = {key.y, key.y - 1, key.y, key.y + 1};
      for (int e = 0; e < 4; ++e) {
        if (nx[e] >= 0 && ny[e] >= 0 && nx[e] < l.tilesX && ny[e] < l.tilesY &&
            !exists(key.level, nx[e], ny[e])) {
          tile.coarserEdges |= 1u << e;
        }
      }
    }
    result.tiles.push_back(tile);
  }
  std::sort(result.missing.begin(), result.missing.end());
  result.missing.erase(std::unique(result.missing.begin(), result.missing.end()), result.missing.end());
  return result;
}

} // namespace sylva::terrain
