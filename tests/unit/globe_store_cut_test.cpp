// The globe reference's cut of a global store (lod/globe/globe_store_cut.hpp) and the tile
// surfaces it draws (readGlobalTileSurface), on the synthetic Earth store (a 0.5-degree planet
// to depth 4, a 0.005-degree area over 10..14 E, 40..44 N to depth 10).
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "support/globe_fixtures.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/lod/globe/globe_store_cut.hpp"

namespace tellus {
namespace {

ViewSetup viewFrom(const GeoCamera& camera, int width, int height) {
  return geoViewSetup(camera, chooseGeoClipRange(camera, 0.0, 2000.0), width, height);
}

globe::GlobeStoreCutView cutViewOf(const ViewSetup& view) {
  globe::GlobeStoreCutView cutView;
  cutView.eyeEcef = view.camera.position;
  cutView.frustum = Frustum::fromMatrix(view.relativeViewProjection());
  cutView.focalPx = view.projection[1][1] * 0.5 * double(view.height);
  return cutView;
}

globe::GlobeStoreCut cutFor(const ViewSetup& view, double tolerancePx, std::size_t maxTiles = 6000) {
  globe::GlobeStoreCutOptions options;
  options.tolerancePx = tolerancePx;
  options.maxTiles = maxTiles;
  return globe::cutGlobeStore(*test::syntheticEarth(), cutViewOf(view), options);
}

// No tile of the cut lies inside another, and every ground point the view shows within
// `reachM` of the eye lies in exactly one tile of it.
void expectDisjointAndCovering(const globe::GlobeStoreCut& cut, const ViewSetup& view,
                               double reachM) {
  const std::set<GeoTileKey> tiles(cut.tiles.begin(), cut.tiles.end());
  ASSERT_EQ(tiles.size(), cut.tiles.size()) << "a tile twice";
  for (const GeoTileKey key : cut.tiles) {
    for (GeoTileKey up = key; up.depth > 0;) {
      up = GlobalTiling::parent(up);
      ASSERT_FALSE(tiles.count(up)) << GlobalStore::describe(key) << " lies in "
                                    << GlobalStore::describe(up);
    }
  }
  int covered = 0;
  for (int y = 0; y < view.height; y += 4) {
    for (int x = 0; x < view.width; x += 4) {
      const std::optional<glm::dvec2> ground = ellipsoidUnderPixel(view, {x + 0.5, y + 0.5});
      if (!ground) continue;
      const glm::dvec3 point =
          wgs84::geodeticToEcef({ground->x * wgs84::kDegree, ground->y * wgs84::kDegree, 0.0});
      if (glm::distance(point, view.camera.position) > reachM) continue;
      int holding = 0;
      for (int depth = 0; depth <= 10; ++depth) {
        holding += int(tiles.count(GlobalTiling::tileAt(depth, ground->x, ground->y)));
      }
      EXPECT_EQ(holding, 1) << "pixel " << x << ", " << y << " at " << ground->x << ", " << ground->y;
      ++covered;
    }
  }
  EXPECT_GT(covered, 100);
}

TEST(GlobeStoreCut, NearTheGroundTheStoresFinestTilesAreDrawnAndTheCutHoldsItsTolerance) {
  const ViewSetup view = viewFrom({41.5, 11.5, 3000.0, 30.0, -12.0, 60.0}, 240, 160);
  const globe::GlobeStoreCut cut = cutFor(view, 0.25);
  EXPECT_EQ(cut.capped, 0u);
  EXPECT_LE(cut.worstErrorPx, 0.25);
  expectDisjointAndCovering(cut, view, 60'000.0);
  // Under the camera: the fine area's deepest tile.
  const GeoTileKey under = GlobalTiling::tileAt(10, 41.5, 11.5);
  EXPECT_NE(std::find(cut.tiles.begin(), cut.tiles.end(), under), cut.tiles.end());
  // Far tiles are shallower: the cut is not the whole view at depth 10.
  int shallow = 0;
  for (const GeoTileKey key : cut.tiles) shallow += key.depth < 10 ? 1 : 0;
  EXPECT_GT(shallow, 0);

  // A looser tolerance draws fewer tiles; a tighter one more, and more of them deep.
  const globe::GlobeStoreCut loose = cutFor(view, 2.0), tight = cutFor(view, 0.05);
  EXPECT_LT(loose.tiles.size(), cut.tiles.size());
  EXPECT_GT(tight.tiles.size(), cut.tiles.size());
  EXPECT_LE(loose.worstErrorPx, 2.0);
  expectDisjointAndCovering(loose, view, 60'000.0);
}

TEST(GlobeStoreCut, FromOrbitTheCutIsShallowAndSmall) {
  const ViewSetup view = viewFrom({30.0, 20.0, 20'000'000.0, 0.0, -90.0, 40.0}, 200, 200);
  const globe::GlobeStoreCut cut = cutFor(view, 0.25);
  EXPECT_LE(cut.tiles.size(), 200u);
  for (const GeoTileKey key : cut.tiles) EXPECT_LE(key.depth, 4) << GlobalStore::describe(key);
  expectDisjointAndCovering(cut, view, 1e9);
}

TEST(GlobeStoreCut, TheTileCapStopsRefiningAndSaysSo) {
  const ViewSetup view = viewFrom({41.5, 11.5, 3000.0, 30.0, -12.0, 60.0}, 240, 160);
  const std::size_t whole = cutFor(view, 0.25).tiles.size();
  const std::size_t cap = whole / 2;
  const globe::GlobeStoreCut capped = cutFor(view, 0.25, cap);
  EXPECT_LE(capped.tiles.size(), cap);
  EXPECT_GT(capped.capped, 0u);
  EXPECT_GT(capped.worstErrorPx, 0.25) << "a capped cut cannot hold the tolerance everywhere";
  expectDisjointAndCovering(capped, view, 60'000.0);
}

TEST(GlobeStoreCut, ATilesBoundsHoldEveryPointOfIt) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const GeoTileKey key : {GeoTileKey{0, 1, 0}, GeoTileKey{3, 9, 2}, GeoTileKey{10, 1092, 273}}) {
    const Aabb box = globe::globeTileEcefBounds(key, -500.0, 4000.0);
    const GeoBounds b = GlobalTiling::bounds(key);
    for (int i = 0; i < 2000; ++i) {
      const double lat = b.southDeg + (b.northDeg - b.southDeg) * unit(random);
      const double lon = b.westDeg + (b.eastDeg - b.westDeg) * unit(random);
      const double h = -500.0 + 4500.0 * unit(random);
      const glm::dvec3 p = wgs84::geodeticToEcef({lat * wgs84::kDegree, lon * wgs84::kDegree, h});
      ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, box.min)) &&
                  glm::all(glm::lessThanEqual(p, box.max)))
          << GlobalStore::describe(key) << " at " << lat << ", " << lon << ", " << h;
    }
  }
}

// Each sample of a tile surface is the store's surface there (storeSampleSource's rule), so two
// neighbours share their edge exactly, also where one is stored and the other is its ancestor's
// interpolation (the fine area's eastern border).
TEST(GlobalTileSurface, NeighboursShareTheirEdgesAsTheStoreRuleSays) {
  const std::shared_ptr<const GlobalStore> store = test::syntheticEarth();
  const int n = store->tileCells();
  int border = -1;
  for (int x = 1090; x < 1120 && border < 0; ++x) {
    if (store->find({10, x, 273}) && !store->find({10, x + 1, 273})) border = x;
  }
  ASSERT_GT(border, 0) << "the fine area ends somewhere east of 12 E";
  for (const int x : {1092, border}) {
    const GeoTileKey west{10, x, 273}, east{10, x + 1, 273};
    Result<HeightGrid> a = readGlobalTileSurface(*store, west);
    Result<HeightGrid> b = readGlobalTileSurface(*store, east);
    ASSERT_TRUE(a && b);
    ASSERT_EQ(a->width, n + 1);
    for (int row = 0; row <= n; ++row) {
      ASSERT_EQ(a->at(n, row), b->at(0, row)) << "tile x " << x << " row " << row;
      // The same value the harness's truth reads there.
      const StoreSampleSource at = storeSampleSource(*store, east, 0, row);
      std::vector<float> heights(store->tileShape().sampleCount());
      ASSERT_TRUE(store->readTileMetres(at.source, heights));
      EXPECT_EQ(b->at(0, row), float(tileSurfaceAt(heights, n, at.u, at.v)));
    }
    // Georeferenced on the tile's samples.
    const GeoBounds bounds = GlobalTiling::bounds(west);
    EXPECT_NEAR(a->georef.geoTransform[0] + 0.5 * a->georef.geoTransform[1], bounds.westDeg, 1e-12);
    EXPECT_NEAR(a->georef.geoTransform[3] + 0.5 * a->georef.geoTransform[5], bounds.northDeg, 1e-12);
  }
  EXPECT_FALSE(readGlobalTileSurface(*store, {2, 99, 0})) << "a key outside the tiling";
}

}  // namespace
}  // namespace tellus
