// The global store's latitude/longitude quadtree: addressing, shared edge samples, neighbours
// across the antimeridian and the poles, parents and children, covering a box.
#include <gtest/gtest.h>

#include "tellus/tiles/global_tiling.hpp"

namespace tellus {
namespace {

TEST(GlobalTiling, TwoRootTilesThenAQuadtree) {
  EXPECT_EQ(GlobalTiling::tilesX(0), 2);
  EXPECT_EQ(GlobalTiling::tilesY(0), 1);
  EXPECT_EQ(GlobalTiling::tilesX(3), 16);
  EXPECT_EQ(GlobalTiling::tilesY(3), 8);
  const GeoBounds west = GlobalTiling::bounds({0, 0, 0});
  EXPECT_EQ(west.westDeg, -180.0);
  EXPECT_EQ(west.eastDeg, 0.0);
  EXPECT_EQ(west.northDeg, 90.0);
  EXPECT_EQ(west.southDeg, -90.0);
  // Jirisan (35.34 N, 127.73 E) at depth 8: tiles of 0.703125 degrees.
  const GeoTileKey jirisan = GlobalTiling::tileAt(8, 35.337, 127.731);
  const GeoBounds b = GlobalTiling::bounds(jirisan);
  EXPECT_LE(b.westDeg, 127.731);
  EXPECT_GT(b.eastDeg, 127.731);
  EXPECT_LE(b.southDeg, 35.337);
  EXPECT_GT(b.northDeg, 35.337);
  EXPECT_DOUBLE_EQ(b.eastDeg - b.westDeg, 0.703125);
  EXPECT_TRUE(GlobalTiling::contains(jirisan));
  EXPECT_FALSE(GlobalTiling::contains({2, 8, 0}));
  EXPECT_FALSE(GlobalTiling::contains({GlobalTiling::kMaxDepth + 1, 0, 0}));
  // Longitudes wrap; edges belong east and south, the last edges to the last tiles.
  EXPECT_EQ(GlobalTiling::tileAt(2, 10.0, 190.0), GlobalTiling::tileAt(2, 10.0, -170.0));
  EXPECT_EQ(GlobalTiling::tileAt(2, 10.0, 0.0).x, 4);
  EXPECT_EQ(GlobalTiling::tileAt(2, 10.0, 180.0).x, 7);
  EXPECT_EQ(GlobalTiling::tileAt(2, 10.0, -180.0).x, 0);
  EXPECT_EQ(GlobalTiling::tileAt(2, 90.0, 0.0).y, 0);
  EXPECT_EQ(GlobalTiling::tileAt(2, -90.0, 0.0).y, 3);
}

TEST(GlobalTiling, NeighboursShareTheirEdgeSamplesExactly) {
  const int cells = 256;
  for (int depth : {0, 1, 5, 12}) {
    for (const GeoTileKey key : {GeoTileKey{depth, 0, 0},
                                 GeoTileKey{depth, GlobalTiling::tilesX(depth) - 1,
                                            GlobalTiling::tilesY(depth) - 1},
                                 GeoTileKey{depth, GlobalTiling::tilesX(depth) / 3,
                                            GlobalTiling::tilesY(depth) / 2}}) {
      const GeoNeighbour east = GlobalTiling::neighbour(key, GeoSide::East);
      EXPECT_FALSE(east.acrossPole);
      for (int j = 0; j <= cells; j += 17) {
        EXPECT_EQ(GlobalTiling::sampleLatDeg(key, cells, j),
                  GlobalTiling::sampleLatDeg(east.key, cells, j));
      }
      // The eastern column is the neighbour's western one (modulo 360 across the antimeridian).
      const double myEast = GlobalTiling::sampleLonDeg(key, cells, cells);
      const double itsWest = GlobalTiling::sampleLonDeg(east.key, cells, 0);
      EXPECT_EQ(std::fmod(myEast - itsWest + 720.0, 360.0), 0.0) << depth;
      const GeoNeighbour west = GlobalTiling::neighbour(east.key, GeoSide::West);
      EXPECT_EQ(west.key, key);
      if (key.y + 1 < GlobalTiling::tilesY(depth)) {
        const GeoNeighbour south = GlobalTiling::neighbour(key, GeoSide::South);
        EXPECT_FALSE(south.acrossPole);
        EXPECT_EQ(GlobalTiling::sampleLatDeg(key, cells, cells),
                  GlobalTiling::sampleLatDeg(south.key, cells, 0));
        for (int i = 0; i <= cells; i += 31) {
          EXPECT_EQ(GlobalTiling::sampleLonDeg(key, cells, i),
                    GlobalTiling::sampleLonDeg(south.key, cells, i));
        }
      }
    }
  }
}

TEST(GlobalTiling, AcrossThePoleLiesTheTileHalfWayRound) {
  // Depth 2: 8 x 4 tiles of 45 degrees. North of tile x = 1 (-135..-90) is x = 5 (45..90).
  const GeoNeighbour north = GlobalTiling::neighbour({2, 1, 0}, GeoSide::North);
  EXPECT_TRUE(north.acrossPole);
  EXPECT_EQ(north.key, (GeoTileKey{2, 5, 0}));
  EXPECT_EQ(GlobalTiling::neighbour(north.key, GeoSide::North).key, (GeoTileKey{2, 1, 0}));
  const GeoNeighbour south = GlobalTiling::neighbour({2, 6, 3}, GeoSide::South);
  EXPECT_TRUE(south.acrossPole);
  EXPECT_EQ(south.key, (GeoTileKey{2, 2, 3}));
  // Depth 0: the two root tiles are each other's neighbours across both poles and both
  // meridians.
  EXPECT_EQ(GlobalTiling::neighbour({0, 0, 0}, GeoSide::North).key, (GeoTileKey{0, 1, 0}));
  EXPECT_EQ(GlobalTiling::neighbour({0, 0, 0}, GeoSide::East).key, (GeoTileKey{0, 1, 0}));
  EXPECT_EQ(GlobalTiling::neighbour({0, 0, 0}, GeoSide::West).key, (GeoTileKey{0, 1, 0}));
  // The pole row is the pole: every sample of a top tile's northern row is at 90 N.
  EXPECT_EQ(GlobalTiling::sampleLatDeg({4, 9, 0}, 64, 0), 90.0);
  EXPECT_EQ(GlobalTiling::sampleLatDeg({4, 9, 15}, 64, 64), -90.0);
}

TEST(GlobalTiling, ParentsAndChildren) {
  const GeoTileKey key{5, 41, 13};
  for (const GeoTileKey& child : GlobalTiling::children(key)) {
    EXPECT_EQ(GlobalTiling::parent(child), key);
    const GeoBounds c = GlobalTiling::bounds(child), p = GlobalTiling::bounds(key);
    EXPECT_GE(c.westDeg, p.westDeg);
    EXPECT_LE(c.eastDeg, p.eastDeg);
    EXPECT_GE(c.southDeg, p.southDeg);
    EXPECT_LE(c.northDeg, p.northDeg);
  }
  EXPECT_EQ(GlobalTiling::parent({0, 1, 0}), (GeoTileKey{0, 1, 0}));
}

TEST(GlobalTiling, TilesCoveringABox) {
  // The Korea mosaic (34..38 N, 126..130 E) at depth 6 (2.8125-degree tiles): 2 x 3 tiles.
  Result<std::vector<GeoTileKey>> korea = GlobalTiling::tilesCovering(6, {126.0, 34.0, 130.0, 38.0});
  ASSERT_TRUE(korea);
  EXPECT_EQ(korea->size(), 6u);
  // A box edge on a tile edge does not take the next tile: 0..90 E at depth 1 is 2 columns.
  Result<std::vector<GeoTileKey>> quarter = GlobalTiling::tilesCovering(1, {0.0, 0.0, 90.0, 90.0});
  ASSERT_TRUE(quarter);
  EXPECT_EQ(quarter->size(), 1u);
  EXPECT_EQ(quarter->front(), (GeoTileKey{1, 2, 0}));
  // Across the antimeridian (170 E to 170 W): the last and the first column.
  Result<std::vector<GeoTileKey>> pacific = GlobalTiling::tilesCovering(2, {170.0, 0.0, -170.0, 10.0});
  ASSERT_TRUE(pacific);
  ASSERT_EQ(pacific->size(), 2u);
  EXPECT_EQ((*pacific)[0].x, 7);
  EXPECT_EQ((*pacific)[1].x, 0);
  // The whole globe at depth 3: every tile once.
  Result<std::vector<GeoTileKey>> all = GlobalTiling::tilesCovering(3, {-180.0, -90.0, 180.0, 90.0});
  ASSERT_TRUE(all);
  EXPECT_EQ(all->size(), 128u);
  // Nonsense is refused.
  EXPECT_FALSE(GlobalTiling::tilesCovering(40, {0.0, 0.0, 1.0, 1.0}));
  EXPECT_FALSE(GlobalTiling::tilesCovering(3, {0.0, 10.0, 1.0, 5.0}));
  EXPECT_FALSE(GlobalTiling::tilesCovering(20, {-180.0, -90.0, 180.0, 90.0}, 1000));
}

}  // namespace
}  // namespace tellus
