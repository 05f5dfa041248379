#include "tellus/tiles/tile_cache.hpp"

#include <tbb/info.h>

#include <chrono>

#include "tellus/core/stopwatch.hpp"
#include "tellus/core/thread_cpu_clock.hpp"
#include "tellus/tiles/fractal_format.hpp"
#include "tellus/tiles/tsan_support.hpp"

namespace tellus {

TileCache::TileCache(std::shared_ptr<const TileStore> store, TileCacheOptions options)
    : store_(std::move(store)), options_(options) {
  maxWorkers_ = options_.maxConcurrentLoads > 0 ? options_.maxConcurrentLoads
                                                : std::max(1, tbb::info::default_concurrency());
}

std::size_t DecodedTile::bytes() const {
  std::size_t total = heightsM.size() * sizeof(float);
  if (fractalCode) {
    total += fractalCode->ranges.size() * sizeof(fractal::RangeBlock) +
             fractalCode->residual.size() * sizeof(std::int32_t);
  }
  return total;
}

TileCache::~TileCache() {
  cancelPrefetches();
  tasks_.wait();
}

Result<TileHandle> TileCache::load(TileKey key) {
  const TileRecord* record = store_->find(key);
  if (!record)
    return makeError("'{}' has no {}", store_->path().string(), TileStore::describe(key));
  const Stopwatch start;
  auto tile = std::make_shared<DecodedTile>();
  tile->key = key;
  tile->stats = record->stats;
  Status status;
  if (options_.fractalCodes && store_->codec().id() == CodecId::Fractal) {
    std::vector<std::byte> payload;
    status = store_->readPayload(*record, payload);
    if (status) {
      Result<fractal::FractalCode> code = fractal::read(payload, store_->layout().tileShape());
      if (code) {
        tile->fractalCode = std::make_shared<const fractal::FractalCode>(std::move(code.value()));
      } else {
        status = makeError("'{}': {} is corrupt: {}", store_->path().string(),
                           TileStore::describe(key), code.error().message);
      }
    }
  } else {
    tile->heightsM.resize(store_->layout().tileShape().sampleCount());
    status = store_->readTileMetres(key, tile->heightsM);
  }
  const double seconds =
      start.elapsedS();
  std::lock_guard lock(mutex_);
  stats_.loadSeconds += seconds;
  stats_.bytesRead += record->payloadBytes;
  if (!status) {
    ++stats_.failures;
    lastError_ = status.error();
    return status.error();
  }
  ++stats_.loads;
  return TileHandle(std::move(tile));
}

TileHandle TileCache::findLocked(TileKey key) {
  auto it = entries_.find(key);
  if (it == entries_.end()) return nullptr;
  lru_.splice(lru_.begin(), lru_, it->second.lruPosition);
  return it->second.tile;
}

void TileCache::insertLocked(const TileHandle& tile) {
  if (entries_.count(tile->key)) return;
  lru_.push_front(tile->key);
  entries_.emplace(tile->key, Entry{tile, lru_.begin()});
  residentBytes_ += tile->bytes();
  stats_.peakResidentBytes = std::max(stats_.peakResidentBytes, residentBytes_);
  evictLocked();
}

void TileCache::evictLocked() {
  auto it = lru_.end();
  while (residentBytes_ > options_.budgetBytes && it != lru_.begin()) {
    --it;
    auto entry = entries_.find(*it);
    // use_count() > 1: someone outside the cache holds a handle (pinned).
    if (entry->second.tile.use_count() > 1) continue;
    residentBytes_ -= entry->second.tile->bytes();
    entries_.erase(entry);
    it = lru_.erase(it);
    ++stats_.evictions;
  }
}

Result<TileHandle> TileCache::get(TileKey key) {
  {
    std::unique_lock lock(mutex_);
    if (TileHandle tile = findLocked(key)) {
      ++stats_.hits;
      return tile;
    }
    ++stats_.misses;
    // Another thread is loading it: wait for that load instead of repeating it.
    while (inFlight_.count(key)) {
      changed_.wait(lock);
      if (TileHandle tile = findLocked(key)) return tile;
    }
    inFlight_.insert(key);
    if (auto q = queuedPriority_.find(key); q != queuedPriority_.end()) {
      queue_.erase({q->second, key});
      queuedPriority_.erase(q);
    }
  }
  Result<TileHandle> loaded = load(key);
  std::lock_guard lock(mutex_);
  inFlight_.erase(key);
  if (loaded) insertLocked(loaded.value());
  changed_.notify_all();
  return loaded;
}

TileHandle TileCache::tryGet(TileKey key, float priority) {
  std::lock_guard lock(mutex_);
  if (TileHandle tile = findLocked(key)) {
    ++stats_.hits;
    return tile;
  }
  ++stats_.misses;
  queueLocked(key, priority);
  return nullptr;
}

void TileCache::prefetch(TileKey key, float priority) {
  std::lock_guard lock(mutex_);
  if (entries_.count(key)) return;
  queueLocked(key, priority);
}

void TileCache::queueLocked(TileKey key, float priority) {
  if (inFlight_.count(key) || !store_->layout().contains(key)) return;
  if (auto q = queuedPriority_.find(key); q != queuedPriority_.end()) {
    queue_.erase({q->second, key});
    q->second = priority;
  } else {
    queuedPriority_.emplace(key, priority);
  }
  queue_.insert({priority, key});
  startWorkersLocked();
}

void TileCache::pausePrefetching(bool paused) {
  std::lock_guard lock(mutex_);
  paused_ = paused;
  if (!paused_) startWorkersLocked();
}

void TileCache::startWorkersLocked() {
  while (!paused_ && workers_ < maxWorkers_ && workers_ < int(queue_.size())) {
    ++workers_;
    tsanHandOff(this);  // see tsan_support.hpp
    [[maybe_unused]] const TsanIgnoreWrites tbbInternals;
    tasks_.run([this] {
      tsanTakeOver(this);
      workerLoop();
    });
  }
}

void TileCache::workerLoop() {
  std::unique_lock lock(mutex_);
  while (!queue_.empty() && !paused_) {
    const TileKey key = std::prev(queue_.end())->second;
    queue_.erase(std::prev(queue_.end()));
    queuedPriority_.erase(key);
    if (entries_.count(key) || inFlight_.count(key)) continue;
    inFlight_.insert(key);
    lock.unlock();
    const double cpuStart = threadCpuSeconds();
    Result<TileHandle> loaded = load(key);
    lock.lock();
    inFlight_.erase(key);
    if (loaded) {
      ++stats_.prefetchLoads;
      insertLocked(loaded.value());
      if (options_.onPrefetched) {
        lock.unlock();
        options_.onPrefetched(loaded.value());
        lock.lock();
      }
    }
    stats_.workerCpuSeconds += threadCpuSeconds() - cpuStart;
    changed_.notify_all();
  }
  --workers_;
  changed_.notify_all();
}

void TileCache::cancelPrefetches() {
  std::lock_guard lock(mutex_);
  queue_.clear();
  queuedPriority_.clear();
  changed_.notify_all();
}

void TileCache::waitIdle() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return (queue_.empty() || paused_) && workers_ == 0; });
}

bool TileCache::resident(TileKey key) const {
  std::lock_guard lock(mutex_);
  return entries_.count(key) != 0;
}

TileCacheStats TileCache::stats() const {
  std::lock_guard lock(mutex_);
  TileCacheStats s = stats_;
  s.residentTiles = entries_.size();
  s.residentBytes = residentBytes_;
  s.queued = queue_.size();
  s.inFlight = inFlight_.size();
  return s;
}

std::optional<Error> TileCache::lastError() const {
  std::lock_guard lock(mutex_);
  return lastError_;
}

}  // namespace tellus
