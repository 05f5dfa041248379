// A flat store's tiles agree with their neighbours and parents (tellus/tiles/store_consistency.hpp):
// every good store passes, whatever its codec; tiles moved, swapped or forged with every
// checksum and index statistic recomputed do not.
#include <algorithm>

#include <gtest/gtest.h>

#include "support/store_surgery.hpp"
#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/tiles/store_consistency.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// Every problem StoreConsistency finds in `store`, having decoded every tile.
std::vector<std::string> problemsOf(const TileStore& store) {
  StoreConsistency consistency(store);
  std::vector<std::int32_t> samples(store.layout().tileShape().sampleCount());
  for (const TileRecord& record : store.records()) {
    EXPECT_TRUE(store.readTile(record.key, samples));
    consistency.addTile(record, samples);
  }
  return consistency.check(100);
}

// A 201 x 201 terrain: 200 cells, not a multiple of 32, so the last tiles are padded.
const fs::path& terrain() {
  static const fs::path dem = [] {
    const fs::path dir = test::processFixtureDir("store-consistency");
    TerrainParams params;
    params.size = 201;
    params.seed = 11;
    test::writeGeneratedTerrain(params, dir / "terrain.tif");
    return dir / "terrain.tif";
  }();
  return dem;
}

fs::path build(const std::string& name, const std::string& codec) {
  const fs::path out = test::freshTestDir() / (name + ".tstore");
  BuildOptions options;
  options.tileSize = 32;
  options.codec = codec;
  if (codec == "bounded" || codec == "lerc" || codec == "fractal") options.maxErrorM = 2.0;
  Result<BuildReport> built = buildPyramid({terrain()}, out, options);
  EXPECT_TRUE(built) << (built ? "" : built.error().message);
  return out;
}

TEST(StoreConsistency, GoodStoresOfEveryCodecPass) {
  for (const std::string codec : {"raw", "zstd", "bounded", "lerc", "fractal"}) {
    const fs::path path = build("good-" + codec, codec);
    std::shared_ptr<TileStore> store = TileStore::open(path).value();
    StoreConsistency consistency(*store);
    ASSERT_TRUE(consistency.toleranceSteps()) << codec << ": the bound is known, so it checks";
    EXPECT_EQ(*consistency.toleranceSteps(), store->codec().lossless() ? 0 : 2 * std::int64_t(store->metadata().maxErrorSteps))
        << codec;
    const std::vector<std::string> problems = problemsOf(*store);
    EXPECT_TRUE(problems.empty()) << codec << ": " << problems.front();
  }
}

TEST(StoreConsistency, SwappedTilesWithRecomputedChecksumsAreCaught) {
  const fs::path path = build("swap-source", "zstd");
  Result<test::StoreSections> sections = test::readStoreSections(path);
  ASSERT_TRUE(sections) << sections.error().message;
  // Two tiles of level 0 trade places, each with its key's checksum and its own min/max: every
  // check a reader can make on one tile passes.
  ASSERT_EQ(sections->index[1].level, sections->index[5].level);
  test::swapTilePayloads(sections.value(), 1, 5);
  const fs::path swapped = test::freshTestDir() / "swapped.tstore";
  ASSERT_TRUE(test::writeStoreSections(sections.value(), swapped, true));
  std::shared_ptr<TileStore> store = TileStore::open(swapped).value();
  const std::vector<std::string> problems = problemsOf(*store);
  ASSERT_FALSE(problems.empty());
  EXPECT_NE(problems.front().find("a tile out of place"), std::string::npos) << problems.front();
}

TEST(StoreConsistency, ATileFromAnotherLevelIsCaughtByItsParent) {
  // The single tile of the top level replaced by a level-0 tile: no neighbour to disagree
  // with, but its children's samples do not nest in it.
  const fs::path path = build("top-source", "zstd");
  Result<test::StoreSections> sections = test::readStoreSections(path);
  ASSERT_TRUE(sections);
  store_format::IndexRecord& top = sections->index.back();
  const store_format::IndexRecord& fine = sections->index.front();
  ASSERT_GT(top.level, fine.level);
  top.payloadOffset = fine.payloadOffset;
  top.payloadBytes = fine.payloadBytes;
  top.minHeightM = fine.minHeightM;
  top.maxHeightM = fine.maxHeightM;
  const fs::path forged = test::freshTestDir() / "forged.tstore";
  ASSERT_TRUE(test::writeStoreSections(sections.value(), forged, true));
  std::shared_ptr<TileStore> store = TileStore::open(forged).value();
  const std::vector<std::string> problems = problemsOf(*store);
  ASSERT_FALSE(problems.empty());
  EXPECT_NE(problems.front().find("its parent"), std::string::npos) << problems.front();
}

}  // namespace
}  // namespace tellus
