// RINGO's block heights (seed 002): a block loaded at a level equals the same block loaded finer
// and coarsened (what a "D" block does when it moves outwards), where the store holds the tiles
// and where it is sparse; a level-0 block is the store's tile.
#include <gtest/gtest.h>

#include <cmath>

#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/geotiff_writer.hpp"
#include "tellus/lod/ringo/ringo_block_data.hpp"
#include "tellus/tiles/global_store_builder.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

// A lat/lon GeoTIFF of `heights` at pixel centres from (north, west) in `step`s.

double relief(double lat, double lon) {
  return 2000.0 * std::sin(3.0 * lat * 0.01745) * std::cos(2.0 * lon * 0.01745) +
         300.0 * std::sin(40.0 * lat * 0.01745) * std::sin(50.0 * lon * 0.01745);
}

TEST(RingoBlockData, CoarsenedBlocksEqualBlocksLoadedCoarser) {
  const fs::path dir = test::freshTestDir();
  // A whole-globe source feeding depth 3 (16-cell tiles) and a fine one over 10..12 E,
  // 40..42 N feeding depth 7: deeper tiles exist only there.
  const fs::path coarse =
      test::writeLatLonTerrain(dir / "coarse.tif", -180.0, 90.0, 1.0, 360, 181, relief);
  const fs::path fine = test::writeLatLonTerrain(dir / "fine.tif", 10.0, 42.0, 0.04, 51, 51, relief);
  GlobalBuildOptions options;
  options.tileCells = 16;
  ASSERT_TRUE(buildGlobalStore({coarse, fine}, dir / "store.tstore", options));
  Result<std::shared_ptr<GlobalStore>> opened = GlobalStore::open(dir / "store.tstore");
  ASSERT_TRUE(opened);
  const GlobalStore& store = *opened.value();
  const RingoLayout layout{.rings = 4, .tileCells = 16};
  const int depth = 7;
  // Blocks over the fine source (stored at depth 7) and far from it (sparse: depth 3 upsampled).
  const GeoTileKey inside = GlobalTiling::tileAt(depth, 41.0, 11.0);
  const GeoTileKey outside{depth, inside.x + 40, inside.y + 9};
  ASSERT_NE(store.find(inside), nullptr);
  ASSERT_EQ(store.find(outside), nullptr);
  EXPECT_EQ(store.deepestStored(outside).depth, 4);
  for (const GeoTileKey& key : {inside, outside}) {
    for (int level = 0; level <= 3; ++level) {
      Result<std::vector<float>> finer = loadRingoBlock(store, layout, {true, key, level});
      ASSERT_TRUE(finer) << finer.error().message;
      ASSERT_EQ(finer->size(), std::size_t(layout.cellsAt(level) + 1) * (layout.cellsAt(level) + 1));
      for (int k = 1; level + k <= 4; ++k) {
        Result<std::vector<float>> coarser = loadRingoBlock(store, layout, {true, key, level + k});
        ASSERT_TRUE(coarser);
        EXPECT_EQ(coarsenRingoBlock(*finer, layout.cellsAt(level), k), coarser.value())
            << GlobalStore::describe(key) << " level " << level << " + " << k;
      }
    }
  }
  // A level-0 block over a stored tile is that tile.
  std::vector<float> tile(store.tileShape().sampleCount());
  ASSERT_TRUE(store.readTileMetres(inside, tile));
  Result<std::vector<float>> block = loadRingoBlock(store, layout, {true, inside, 0});
  ASSERT_TRUE(block);
  EXPECT_EQ(block.value(), tile);
  EXPECT_FALSE(loadRingoBlock(store, layout, {}));  // beyond a pole
}

TEST(RingoBlockData, DrawnHeightFollowsTheMeshTrianglesNotTheBilinearSurface) {
  // One saddle cell (2 cells a side): NW 0, NE 0, SW 0, SE 4 in the first cell.
  const std::vector<float> h = {0, 0, 1,  //
                                0, 4, 2,  //
                                3, 5, 6};
  EXPECT_DOUBLE_EQ(ringoDrawnHeight(h, 2, 0.0, 0.0), 0.0);  // vertices are the samples
  EXPECT_DOUBLE_EQ(ringoDrawnHeight(h, 2, 1.0, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(ringoDrawnHeight(h, 2, 2.0, 2.0), 6.0);
  // The cell's centre lies on the north-east to south-west diagonal: 0 there (bilinear: 1).
  EXPECT_DOUBLE_EQ(ringoDrawnHeight(h, 2, 0.5, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(tileSurfaceAt(h, 2, 0.5, 0.5), 1.0);
  // Inside the south-east triangle (NE, SE, SW): linear between them.
  EXPECT_DOUBLE_EQ(ringoDrawnHeight(h, 2, 0.75, 0.75), 0.5 * 4.0);
  // Clamped outside.
  EXPECT_DOUBLE_EQ(ringoDrawnHeight(h, 2, -1.0, 3.0), 3.0);
}

}  // namespace
}  // namespace tellus
