#pragma once

#include <sylva/terrain/TileSource.hpp>

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

namespace sylva::terrain {

/** Default RAM budget of streamed tiles, bytes (`--ram-budget` in MB). */
inline constexpr std::size_t kDefaultRamBudget = std::size_t{512} << 20;

/** Counters of a TileStreamer since it started. */
struct StreamerStats {
  std::uint64_t loaded = 0;      ///< tiles loaded (read or generated) by the loader threads
  std::uint64_t evicted = 0;     ///< tiles dropped from RAM to stay within the budget
  std::uint64_t failed = 0;      ///< loads that threw (the message is logged once per tile)
  std::size_t residentBytes = 0; ///< bytes of the tiles held now
  std::size_t peakBytes = 0;     ///< most bytes ever held
  std::size_t residentTiles = 0; ///< tiles held now
  std::size_t queued = 0;        ///< requests waiting for a loader
  double loadSeconds = 0.0;      ///< time the loaders spent loading, summed over threads
};

/**
 * Tiles in RAM within a fixed budget, loaded by background threads in the order the frame asks for them.
 *
 * Each frame: request() what the view wants (lower priority values first; the frame's requests replace the
 * previous frame's queue when beginFrame() is called), then get() what is there. The coarsest levels (at
 * most `pinnedTiles` tiles, whole levels from the top) are loaded at construction and never dropped, so a
 * coarser stand-in always exists. Least recently used tiles are dropped first; a tile that is `pin()`ned
 * (e.g. resident on the GPU) is never dropped, so the budget must exceed what is pinned (the renderer's GPU
 * budget). Thread-safe.
 */
class TileStreamer {
public:
  /** Starts `loaders` background threads (≥ 1) and loads the pinned top levels (blocking). Throws
   * sylva::Error when `ramBudget` holds fewer than 64 tiles. */
  TileStreamer(std::shared_ptr<const TileSource> source, std::size_t ramBudget = kDefaultRamBudget,
               int loaders = 1, std::size_t pinnedTiles = 85);
  ~TileStreamer();
  TileStreamer(const TileStreamer&) = delete;
  TileStreamer& operator=(const TileStreamer&) = delete;

  /** The source. */
  const TileSource& source() const { return *mSource; }
  /** Levels from the top that are always resident: levels ≥ pinnedLevel(). */
  int pinnedLevel() const { return mPinnedLevel; }

  /** Starts a frame: requests not renewed since the last beginFrame() are dropped from the queue. */
  void beginFrame();
  /** Asks for `key` (lower priority first); no effect if held or being loaded. */
  void request(const TileKey& key, float priority);
  /** The tile if it is in RAM (marks it used), else null. */
  std::shared_ptr<const TileData> get(const TileKey& key);
  /** Whether the tile is in RAM (does not mark it used). */
  bool holds(const TileKey& key) const;
  /** Keeps `key` in RAM until unpin() (counted: pins nest). */
  void pin(const TileKey& key);
  /** Undoes one pin(). */
  void unpin(const TileKey& key);
  /** Blocks until the queue is empty and no load is running (tests, deterministic renders). */
  void waitIdle();
  /** Counters. */
  StreamerStats stats() const;
  /** The RAM budget, bytes. */
  std::size_t budget() const { return mBudget; }

private:
  struct Entry {
    std::shared_ptr<const TileData> tile;
    std::list<TileKey>::iterator order;
    int pins = 0;
  };
  void loaderLoop();
  void insert(const TileKey& key, std::shared_ptr<const TileData> tile);
  std::size_t tileBytes() const;

  std::shared_ptr<const TileSource> mSource;
  std::size_t mBudget;
  int mPinnedLevel = 0;
  mutable std::mutex mMutex;
  std::condition_variable mWake;
  std::condition_variable mIdle;
  std::map<TileKey, Entry> mTiles;
  std::list<TileKey> mOrder;       ///< most recently used first
  std::map<TileKey, float> mQueue; ///< wanted this frame, by key
  std::set<TileKey> mRenewed;      ///< requested since beginFrame()
  std::set<TileKey> mLoading;      ///< being loaded now
  std::set<TileKey> mFailedKeys;   ///< loads that threw (not retried)
  StreamerStats mStats;
  bool mStop = false;
  std::vector<std::thread> mThreads;
};

} // namespace sylva::terrain
