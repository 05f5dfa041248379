// The tile cache: serves a store much larger than its budget, evicts least recently used
// unpinned tiles, never evicts pinned ones, loads asynchronously, and is safe under
// concurrency (this suite also runs under ThreadSanitizer: make tsan).
#include <mutex>
#include <random>
#include <thread>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "support/test_support.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/tiles/tile_cache.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// One store shared by the tests of this file: N36E137 (Japan Alps), 64-cell tiles, zstd.
std::shared_ptr<TileStore> japanStore(const fs::path& data) {
  static std::shared_ptr<TileStore> store = [&data] {
    const fs::path path = test::processFixtureDir("cache-test") / "n36e137.tstore";
    BuildOptions options;
    options.tileSize = 64;
    // Built on one thread: ThreadSanitizer cannot see oneTBB's (uninstrumented) pipeline
    // hand-offs and would report them; the cache below is what this suite checks.
    tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
    Result<BuildReport> built =
        buildPyramid({data / "srtm3-hgt-east-asia/N36E137.hgt"}, path, options);
    EXPECT_TRUE(built) << built.error().message;
    Result<std::shared_ptr<TileStore>> opened = TileStore::open(path);
    EXPECT_TRUE(opened);
    return opened ? opened.value() : nullptr;
  }();
  return store;
}

TileCacheOptions cacheOptions(std::size_t budgetBytes, int maxConcurrentLoads) {
  TileCacheOptions options;
  options.budgetBytes = budgetBytes;
  options.maxConcurrentLoads = maxConcurrentLoads;
  return options;
}

std::size_t decodedBytes(const TileStore& store) {
  return store.layout().tileCount() * store.layout().tileShape().sampleCount() * sizeof(float);
}

TEST(TileCache, ServesAStoreHundredTimesLargerThanItsBudgetFromManyThreads) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  std::shared_ptr<TileStore> store = japanStore(data);
  ASSERT_TRUE(store);
  const std::size_t budget = decodedBytes(*store) / 100;  // 1% of the decoded data
  TileCache cache(store, cacheOptions(budget, 2));
  const std::span<const TileRecord> records = store->records();
  std::atomic<int> mismatches{0}, failures{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      std::mt19937 random{unsigned(t)};
      std::vector<float> expected(store->layout().tileShape().sampleCount());
      for (int i = 0; i < 300; ++i) {
        const TileKey key = records[random() % records.size()].key;
        if (i % 3 == 0) cache.prefetch(records[random() % records.size()].key, float(i));
        Result<TileHandle> tile = cache.get(key);
        if (!tile) {
          ++failures;
          continue;
        }
        if (!store->readTileMetres(key, expected) || tile.value()->heightsM != expected ||
            tile.value()->key != key) {
          ++mismatches;
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  cache.waitIdle();
  const TileCacheStats stats = cache.stats();
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(stats.evictions, 0u);
  EXPECT_GT(stats.misses, 0u);
  EXPECT_LE(stats.residentBytes, budget);  // nothing pinned any more
  EXPECT_GT(stats.bytesRead, 0u);
  EXPECT_EQ(stats.failures, 0u);
}

TEST(TileCache, EvictsTheLeastRecentlyUsedAndNeverAPinnedTile) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  std::shared_ptr<TileStore> store = japanStore(data);
  ASSERT_TRUE(store);
  const std::size_t tileBytes = store->layout().tileShape().sampleCount() * sizeof(float);
  TileCache cache(store, cacheOptions(3 * tileBytes, 1));
  Result<TileHandle> pinned = cache.get({0, 0, 0});  // held for the whole test
  ASSERT_TRUE(pinned);
  ASSERT_TRUE(cache.get({0, 1, 0}));
  ASSERT_TRUE(cache.get({0, 2, 0}));
  ASSERT_TRUE(cache.get({0, 1, 0}));  // now 2/0 is the least recently used unpinned tile
  ASSERT_TRUE(cache.get({0, 3, 0}));
  EXPECT_TRUE(cache.resident({0, 0, 0}));
  EXPECT_TRUE(cache.resident({0, 1, 0}));
  EXPECT_FALSE(cache.resident({0, 2, 0}));
  EXPECT_TRUE(cache.resident({0, 3, 0}));
  // Pin everything resident: a further load exceeds the budget rather than evict a pin.
  Result<TileHandle> a = cache.get({0, 1, 0}), b = cache.get({0, 3, 0});
  ASSERT_TRUE(cache.get({0, 4, 0}));
  EXPECT_TRUE(cache.resident({0, 0, 0}) && cache.resident({0, 1, 0}) && cache.resident({0, 3, 0}));
  EXPECT_EQ(cache.stats().residentBytes, 4 * tileBytes);
  // The next load evicts the one unpinned tile, 4/0, and keeps the pins.
  ASSERT_TRUE(cache.get({0, 5, 0}));
  EXPECT_FALSE(cache.resident({0, 4, 0}));
  EXPECT_TRUE(cache.resident({0, 0, 0}) && cache.resident({0, 1, 0}) && cache.resident({0, 3, 0}));
  const TileCacheStats stats = cache.stats();
  EXPECT_EQ(stats.hits, 3u);
  EXPECT_EQ(stats.loads, 6u);
}

TEST(TileCache, TryGetQueuesAnAsynchronousLoad) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  std::shared_ptr<TileStore> store = japanStore(data);
  ASSERT_TRUE(store);
  TileCache cache(store, cacheOptions(decodedBytes(*store), 2));
  const TileKey key{1, 3, 2};
  EXPECT_EQ(cache.tryGet(key, 1.0f), nullptr);
  for (int x = 0; x < store->layout().tilesX(0); ++x) cache.prefetch({0, x, 5}, float(x));
  cache.waitIdle();
  TileHandle tile = cache.tryGet(key, 1.0f);
  ASSERT_NE(tile, nullptr);
  EXPECT_EQ(tile->key, key);
  EXPECT_TRUE(cache.resident({0, 0, 5}));
  const TileCacheStats stats = cache.stats();
  EXPECT_EQ(stats.prefetchLoads, std::uint64_t(store->layout().tilesX(0)) + 1);
  EXPECT_EQ(stats.hits, 1u);
  EXPECT_EQ(stats.misses, 1u);
  EXPECT_EQ(stats.queued, 0u);
}

TEST(TileCache, PrefetchesLoadHighestPriorityFirst) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  std::shared_ptr<TileStore> store = japanStore(data);
  ASSERT_TRUE(store);
  std::mutex orderMutex;
  std::vector<TileKey> order;
  TileCacheOptions options = cacheOptions(decodedBytes(*store), 1);
  options.onPrefetched = [&](const TileHandle& tile) {
    std::lock_guard lock(orderMutex);
    order.push_back(tile->key);
  };
  TileCache cache(store, options);
  cache.pausePrefetching(true);
  // Tile x of level-0 row 3 gets priority (x * 7) % 13: a scrambled order.
  const int tiles = store->layout().tilesX(0);
  for (int x = 0; x < tiles; ++x) cache.prefetch({0, x, 3}, float((x * 7) % 13));
  cache.prefetch({0, 0, 3}, 100.0f);  // asking again raises the priority
  cache.waitIdle();
  EXPECT_TRUE(order.empty()) << "paused prefetching loaded tiles";
  cache.pausePrefetching(false);
  cache.waitIdle();
  ASSERT_EQ(order.size(), std::size_t(tiles));
  EXPECT_EQ(order.front(), (TileKey{0, 0, 3}));
  for (std::size_t i = 2; i < order.size(); ++i) {
    EXPECT_GE((order[i - 1].x * 7) % 13, (order[i].x * 7) % 13) << "load " << i;
  }
}

TEST(TileCache, CancelledPrefetchesDoNotLoad) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  std::shared_ptr<TileStore> store = japanStore(data);
  ASSERT_TRUE(store);
  TileCache cache(store, cacheOptions(decodedBytes(*store), 1));
  for (const TileRecord& r : store->records()) cache.prefetch(r.key, 0.0f);
  cache.cancelPrefetches();
  cache.waitIdle();
  EXPECT_LT(cache.stats().loads, store->records().size());
}

}  // namespace
}  // namespace tellus
