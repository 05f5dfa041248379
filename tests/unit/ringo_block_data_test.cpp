// RINGO's block heights (seed 002): a block loaded at a level equals the same block loaded finer
// and coarsened (what a "D" block does when it moves outwards), where the store holds the tiles
// and where it is sparse; a level-0 block is the store's tile; blocks side by side, and a block
// beside its coarser neighbour, agree on their shared edge where the store's depth changes.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "support/terrain_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/lod/ringo/ringo_block_data.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

const GlobalStore& sparseStore() { return test::sparseGlobalStore(); }

TEST(RingoBlockData, CoarsenedBlocksEqualBlocksLoadedCoarser) {
  const GlobalStore& store = sparseStore();
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

// The heights of `block`'s edge facing (dx, dy) (one of them 0), west to east or north to south.
std::vector<float> edgeOf(const std::vector<float>& heights, int cells, int dx, int dy) {
  std::vector<float> edge;
  for (int k = 0; k <= cells; ++k) {
    const int i = dx == 0 ? k : (dx > 0 ? cells : 0);
    const int j = dy == 0 ? k : (dy > 0 ? cells : 0);
    edge.push_back(heights[std::size_t(j) * std::size_t(cells + 1) + std::size_t(i)]);
  }
  return edge;
}

// Where the store's depth changes from one tile to the next (the fine source's border), blocks
// read from different sources; their shared edge must still be one line of heights, or the
// mesh opens a crack there. Checked for every pair of neighbouring blocks around the fine area,
// at the same level and with the neighbour one level coarser (its samples are the finer block's
// even edge samples), at depths up to one beyond the store's deepest.
TEST(RingoBlockData, NeighbouringBlocksAgreeOnTheirSharedEdgeWhereTheStoreIsSparse) {
  const GlobalStore& store = sparseStore();
  const RingoLayout layout{.rings = 4, .tileCells = 16};
  int boundaries = 0;
  for (int depth = 5; depth <= 8; ++depth) {
    const GeoTileKey centre = GlobalTiling::tileAt(depth, 41.0, 11.0);
    const int reach = 1 << (depth - 4);  // tiles a side of the fine area, and a margin
    for (int y = centre.y - 2 * reach; y <= centre.y + 2 * reach; ++y) {
      for (int x = centre.x - 2 * reach; x <= centre.x + 2 * reach; ++x) {
        const GeoTileKey key{depth, x, y};
        for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
          const GeoTileKey next{depth, x + dx, y + dy};
          if (store.deepestStored(key).depth != store.deepestStored(next).depth) ++boundaries;
          for (int level = 0; level <= 2; ++level) {
            const int cells = layout.cellsAt(level);
            Result<std::vector<float>> a = loadRingoBlock(store, layout, {true, key, level});
            Result<std::vector<float>> b = loadRingoBlock(store, layout, {true, next, level});
            Result<std::vector<float>> bCoarser =
                loadRingoBlock(store, layout, {true, next, level + 1});
            Result<std::vector<float>> aCoarser =
                loadRingoBlock(store, layout, {true, key, level + 1});
            ASSERT_TRUE(a && b && aCoarser && bCoarser);
            const std::string where = GlobalStore::describe(key) + " level " + std::to_string(level) +
                                      (dx ? " east" : " south");
            const std::vector<float> aEdge = edgeOf(*a, cells, dx, dy);
            const std::vector<float> bEdge = edgeOf(*b, cells, -dx, -dy);
            ASSERT_EQ(aEdge, bEdge) << where << " " << GlobalStore::describe(store.deepestStored(key))
                                    << " " << GlobalStore::describe(store.deepestStored(next));
            // Beside a coarser neighbour: the finer edge's even samples are the coarser's.
            std::vector<float> aEven, bEven;
            for (int k = 0; k <= cells; k += 2) aEven.push_back(aEdge[std::size_t(k)]);
            for (int k = 0; k <= cells; k += 2) bEven.push_back(bEdge[std::size_t(k)]);
            ASSERT_EQ(aEven, edgeOf(*bCoarser, cells / 2, -dx, -dy)) << where << " coarser next";
            ASSERT_EQ(bEven, edgeOf(*aCoarser, cells / 2, dx, dy)) << where << " coarser this";
          }
        }
      }
    }
  }
  EXPECT_GT(boundaries, 20);  // the store's depth changes between many of those tiles
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
