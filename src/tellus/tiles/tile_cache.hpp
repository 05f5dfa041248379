#pragma once
// A thread-safe CPU cache of decoded tiles with a byte budget.
//
// - Tiles are decoded to metres (float, (tileSize + 1)^2 per tile) on first use.
// - A TileHandle (shared pointer) pins its tile: pinned tiles are never evicted. When the
//   resident tiles exceed the budget, the least recently used unpinned tiles are evicted; if
//   everything left is pinned the cache stays over budget until handles are released.
// - prefetch() queues loads that run asynchronously on oneTBB worker threads, highest priority
//   first; asking again for a queued tile updates its priority, and cancelPrefetches() drops
//   what has not started (e.g. when the viewer turned around).
// - get() returns a tile, loading it on the calling thread on a miss (or waiting for a load
//   already in flight). tryGet() never blocks: a resident tile or nullptr plus a queued load.
// - Loading errors (a corrupt tile) are returned by get() and counted; asynchronous failures are
//   kept in lastError().
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <unordered_map>
#include <vector>

#include <tbb/task_group.h>

#include "tellus/core/result.hpp"
#include "tellus/tiles/fractal_code.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct DecodedTile {
  TileKey key;
  TileStats stats;
  std::vector<float> heightsM;  // (tileSize + 1)^2, row-major, row 0 = north
  // With TileCacheOptions::fractalCodes on a fractal store: the parsed code, for decoding on
  // the GPU; heightsM is then empty.
  std::shared_ptr<const fractal::FractalCode> fractalCode;
  std::size_t bytes() const;
};
using TileHandle = std::shared_ptr<const DecodedTile>;

struct TileCacheOptions {
  std::size_t budgetBytes = std::size_t(256) << 20;
  int maxConcurrentLoads = 0;  // 0: as many as the machine has cores
  // Called on the loading thread after a prefetched tile became resident (e.g. to schedule its
  // GPU upload). Must be thread-safe and must not call back into the cache.
  std::function<void(const TileHandle&)> onPrefetched;
  // Fractal stores: keep each tile's parsed fractal code instead of decoding it on the CPU.
  bool fractalCodes = false;
};

struct TileCacheStats {
  std::uint64_t hits = 0;           // get/tryGet found the tile resident
  std::uint64_t misses = 0;         // get/tryGet did not
  std::uint64_t loads = 0;          // tiles read and decoded
  std::uint64_t prefetchLoads = 0;  // of which asynchronously
  std::uint64_t evictions = 0;
  std::uint64_t failures = 0;   // loads that failed (corrupt tile, I/O error)
  std::uint64_t bytesRead = 0;  // encoded payload bytes read from the store
  double loadSeconds = 0.0;     // read + checksum + decode, summed over loads
  double workerCpuSeconds = 0.0;  // CPU time of the prefetch workers (loads and onPrefetched)
  std::size_t residentTiles = 0;
  std::size_t residentBytes = 0;
  std::size_t peakResidentBytes = 0;
  std::size_t queued = 0;    // prefetch requests waiting
  std::size_t inFlight = 0;  // loads running
};

class TileCache {
 public:
  TileCache(std::shared_ptr<const TileStore> store, TileCacheOptions options = {});
  ~TileCache();  // drops queued prefetches and waits for running loads
  TileCache(const TileCache&) = delete;
  TileCache& operator=(const TileCache&) = delete;

  const TileStore& store() const { return *store_; }
  Result<TileHandle> get(TileKey key);
  TileHandle tryGet(TileKey key, float priority);
  void prefetch(TileKey key, float priority);
  void cancelPrefetches();
  // While paused, prefetch requests queue up but none starts: a renderer can post all of a
  // frame's requests and resume, so that the highest priorities load first.
  void pausePrefetching(bool paused);
  // Blocks until no prefetch is queued or running.
  void waitIdle();
  bool resident(TileKey key) const;
  TileCacheStats stats() const;
  std::optional<Error> lastError() const;

 private:
  struct Entry {
    TileHandle tile;
    std::list<TileKey>::iterator lruPosition;
  };

  Result<TileHandle> load(TileKey key);  // without the lock
  // With the lock held:
  TileHandle findLocked(TileKey key);
  void insertLocked(const TileHandle& tile);
  void evictLocked();
  void queueLocked(TileKey key, float priority);
  void startWorkersLocked();
  void workerLoop();

  std::shared_ptr<const TileStore> store_;
  TileCacheOptions options_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;  // a load finished or the queue emptied
  std::unordered_map<TileKey, Entry, TileKeyHash> entries_;
  std::list<TileKey> lru_;  // front = most recently used
  std::size_t residentBytes_ = 0;
  std::set<TileKey> inFlight_;
  std::map<TileKey, float> queuedPriority_;
  std::set<std::pair<float, TileKey>> queue_;  // highest priority at the end
  int workers_ = 0;
  bool paused_ = false;
  int maxWorkers_ = 1;
  TileCacheStats stats_;
  std::optional<Error> lastError_;
  tbb::task_group tasks_;
};

}  // namespace tellus
