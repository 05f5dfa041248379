// Imagery pyramids (dem/imagery_pyramid.hpp): tiles hold the source's texels, each level the
// mean of the one below, masked texels are transparent, texels map to where the source says
// (any CRS), the cache is rebuilt when its source changes, and broken files are refused.
#include <cmath>
#include <cstring>
#include <numbers>
#include <fstream>

#include <gtest/gtest.h>

#include "support/imagery_fixtures.hpp"
#include "support/test_support.hpp"
#include "tellus/dem/imagery_pyramid.hpp"

namespace tellus {
namespace {

std::array<int, 4> texelOf(const ImageryPyramid& p, int level, int x, int y) {
  const int t = p.tileSize();
  const std::byte* tile = p.tile(level, x / t, y / t).data();
  const std::byte* at = tile + (std::size_t(y % t) * t + std::size_t(x % t)) * 4;
  return {int(at[0]), int(at[1]), int(at[2]), int(at[3])};
}

TEST(ImageryPyramid, HoldsTheSourceTexelsAndTheirMeansLevelByLevel) {
  const std::filesystem::path dir = test::freshTestDir();
  test::TestImage image{300, 200, 10.0, 45.0, 0.001, 4326, [](int x, int y) {
                          auto t = test::testPattern(x, y);
                          if (x < 10 && y < 10) t[3] = 0;  // a masked corner
                          return t;
                        }};
  test::writeTestImage(image, dir / "image.tif");
  ASSERT_TRUE(buildImageryPyramid(dir / "image.tif", dir / "image.timagery", {.tileSize = 64}));
  Result<ImageryPyramid> opened = ImageryPyramid::open(dir / "image.timagery");
  ASSERT_TRUE(opened) << opened.error().message;
  const ImageryPyramid& p = opened.value();
  EXPECT_EQ(p.width(), 300);
  EXPECT_EQ(p.height(), 200);
  EXPECT_EQ(p.levels(), 4);  // 300, 150, 75, 38 texels across: the last fits one tile
  EXPECT_EQ(p.tilesX(0), 5);
  EXPECT_EQ(p.tilesY(0), 4);
  EXPECT_EQ(p.tilesX(3), 1);
  EXPECT_EQ(p.levelWidth(2), 75);
  // Level 0: the source (premultiplied: valid texels as they are).
  for (auto [x, y] : {std::pair{20, 30}, {299, 199}, {64, 64}, {150, 17}}) {
    const auto s = test::testPattern(x, y);
    EXPECT_EQ(texelOf(p, 0, x, y), (std::array<int, 4>{s[0], s[1], s[2], 255})) << x << "," << y;
  }
  // Masked texels are transparent black, and so is what lies beyond the image in edge tiles.
  EXPECT_EQ(texelOf(p, 0, 3, 4), (std::array<int, 4>{0, 0, 0, 0}));
  EXPECT_EQ(texelOf(p, 0, 310, 5)[3], 0);
  // Level 1: the mean of the four below (rounded).
  for (auto [x, y] : {std::pair{40, 40}, {100, 60}}) {
    int sum = 0;
    for (int k = 0; k < 4; ++k) sum += test::testPattern(2 * x + k % 2, 2 * y + k / 2)[0];
    EXPECT_NEAR(texelOf(p, 1, x, y)[0], sum / 4.0, 0.6);
    EXPECT_EQ(texelOf(p, 1, x, y)[3], 255);
  }
  // At the image's odd edge (75 texels of level 2 from 150): half the texels beyond it.
  EXPECT_NEAR(texelOf(p, 3, 37, 10)[3], 128, 1);
  // Where texels lie: the geotransform, in degrees.
  Result<ImageryPyramid::LatLon> corner = p.latLonAt(0.0, 0.0);
  ASSERT_TRUE(corner);
  EXPECT_NEAR(corner->latDeg, 45.0, 1e-9);
  EXPECT_NEAR(corner->lonDeg, 10.0, 1e-9);
  Result<ImageryPyramid::LatLon> far = p.latLonAt(300.0, 200.0);
  ASSERT_TRUE(far);
  EXPECT_NEAR(far->latDeg, 44.8, 1e-9);
  EXPECT_NEAR(far->lonDeg, 10.3, 1e-9);
}

TEST(ImageryPyramid, WebMercatorTexelsLieWhereTheProjectionPutsThem) {
  const std::filesystem::path dir = test::freshTestDir();
  // Tokyo's z12 tile column 3637, row 1612: west edge 139.658 E, north edge 35.746 N.
  const double size = 38.21851414258813, west = -20037508.342789244 + 3637 * 256 * size,
               north = 20037508.342789244 - 1612 * 256 * size;
  test::writeTestImage({64, 64, west, north, size * 4, 3857, test::testPattern}, dir / "m.tif");
  ASSERT_TRUE(buildImageryPyramid(dir / "m.tif", dir / "m.timagery", {.tileSize = 64}));
  Result<ImageryPyramid> p = ImageryPyramid::open(dir / "m.timagery");
  ASSERT_TRUE(p) << p.error().message;
  Result<ImageryPyramid::LatLon> nw = p->latLonAt(0.0, 0.0);
  ASSERT_TRUE(nw);
  EXPECT_NEAR(nw->lonDeg, 3637.0 / 4096.0 * 360.0 - 180.0, 1e-9);
  const double n = std::numbers::pi * (1.0 - 2.0 * 1612.0 / 4096.0);
  EXPECT_NEAR(nw->latDeg, std::atan(std::sinh(n)) * 180.0 / std::numbers::pi, 1e-9);
}

TEST(ImageryPyramid, TheCacheIsBuiltOnceAndRebuiltWhenTheSourceChanges) {
  const std::filesystem::path dir = test::freshTestDir();
  test::TestImage image{100, 80, 10.0, 45.0, 0.001, 4326, test::testPattern};
  test::writeTestImage(image, dir / "a.tif");
  Result<ImageryPyramid> first = openCachedImageryPyramid(dir / "a.tif", dir / "cache");
  ASSERT_TRUE(first) << first.error().message;
  const auto built = std::filesystem::last_write_time(dir / "cache" / "a.timagery");
  Result<ImageryPyramid> again = openCachedImageryPyramid(dir / "a.tif", dir / "cache");
  ASSERT_TRUE(again);
  EXPECT_EQ(std::filesystem::last_write_time(dir / "cache" / "a.timagery"), built);
  image.width = 120;  // another source of the same name
  test::writeTestImage(image, dir / "a.tif");
  Result<ImageryPyramid> rebuilt = openCachedImageryPyramid(dir / "a.tif", dir / "cache");
  ASSERT_TRUE(rebuilt) << rebuilt.error().message;
  EXPECT_EQ(rebuilt->width(), 120);
}

TEST(ImageryPyramid, RefusesBrokenFilesAndSourcesThatAreNotImagery) {
  const std::filesystem::path dir = test::freshTestDir();
  test::writeTestImage({100, 80, 10.0, 45.0, 0.001, 4326, test::testPattern}, dir / "a.tif");
  ASSERT_TRUE(buildImageryPyramid(dir / "a.tif", dir / "a.timagery"));
  // Truncated.
  std::filesystem::copy_file(dir / "a.timagery", dir / "short.timagery");
  std::filesystem::resize_file(dir / "short.timagery", std::filesystem::file_size(dir / "a.timagery") - 100);
  Result<ImageryPyramid> shortFile = ImageryPyramid::open(dir / "short.timagery");
  ASSERT_FALSE(shortFile);
  EXPECT_NE(shortFile.error().message.find("truncated"), std::string::npos) << shortFile.error().message;
  // Not a pyramid at all.
  std::ofstream(dir / "text.timagery") << "hello, this is not imagery";
  Result<ImageryPyramid> text = ImageryPyramid::open(dir / "text.timagery");
  ASSERT_FALSE(text);
  EXPECT_NE(text.error().message.find("not a Tellus imagery pyramid"), std::string::npos);
  EXPECT_FALSE(ImageryPyramid::open(dir / "missing.timagery"));
  // Sources: missing, not RGB, no georeferencing, a tile size that is not a power of two.
  EXPECT_FALSE(buildImageryPyramid(dir / "missing.tif", dir / "x.timagery"));
  Status badTile = buildImageryPyramid(dir / "a.tif", dir / "x.timagery", {.tileSize = 100});
  ASSERT_FALSE(badTile);
  EXPECT_NE(badTile.error().message.find("power of two"), std::string::npos);
  std::ofstream(dir / "notes.txt") << "not a raster";
  EXPECT_FALSE(buildImageryPyramid(dir / "notes.txt", dir / "x.timagery"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.timagery"));
}

// Draped on a store of another CRS: a Web Mercator image onto a latitude/longitude grid covers
// the part of the grid its footprint covers, at its own resolution there, snapped to the grid's
// corner; its pyramid holds the image's texels where they land.
TEST(ImageryPyramid, WarpsOntoAStoreInAnotherCrs) {
  const std::filesystem::path dir = test::freshTestDir();
  // 127.0 E .. 127.5 E, about 37.0 N .. 37.4 N in Web Mercator, 300 m texels; left half red.
  test::TestImage image{.width = 185, .height = 189, .west = 14137575.0, .north = 4494810.0, .texelSize = 300.0,
                        .epsg = 3857, .texel = [](int x, int) {
                          return x < 92 ? std::array<std::uint8_t, 4>{250, 0, 0, 255}
                                        : std::array<std::uint8_t, 4>{0, 0, 250, 255};
                        }};
  test::writeTestImage(image, dir / "mercator.tif");
  // A store over 126.5 E .. 128 E, 36.5 N .. 38 N: 1801 samples a side of 3 arc-seconds.
  GeoReference store;
  store.crsWkt = R"(GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563]],PRIMEM["Greenwich",0],UNIT["degree",0.0174532925199433]])";
  store.hasGeoTransform = true;
  store.isGeographic = true;
  const double step = 1.0 / 1200.0;
  store.geoTransform = {126.5 - step / 2, step, 0.0, 38.0 + step / 2, 0.0, -step};
  Result<ImageryWarpGrid> grid = imageryGridOnStore(dir / "mercator.tif", store, 1801, 1801);
  ASSERT_TRUE(grid) << grid.error().message;
  const auto& g = grid->geoTransform;
  // The footprint: 127.0 .. 127.5 E, within a texel.
  EXPECT_NEAR(g[0], 127.0, g[1]);
  EXPECT_NEAR(g[0] + grid->width * g[1], 127.5, g[1]);
  EXPECT_NEAR(g[3], 37.4, 2 * -g[5]);
  // Snapped to texels counted from the store's corner.
  EXPECT_NEAR(std::remainder((g[0] - store.geoTransform[0]) / g[1], 1.0), 0.0, 1e-6);
  ImageryBuildOptions options{.tileSize = 64, .warp = grid.value()};
  Result<ImageryPyramid> pyramid = openCachedImageryPyramid(dir / "mercator.tif", dir / "cache", options);
  ASSERT_TRUE(pyramid) << pyramid.error().message;
  EXPECT_EQ(pyramid->width(), grid->width);
  // West of 127.25 E red, east of it blue (a texel's margin for the bilinear warp).
  const int middle = grid->width / 2, row = grid->height / 2;
  EXPECT_GT(texelOf(pyramid.value(), 0, middle - 3, row)[0], 200);
  EXPECT_GT(texelOf(pyramid.value(), 0, middle + 3, row)[2], 200);
  EXPECT_EQ(texelOf(pyramid.value(), 0, middle - 3, row)[3], 255);
  // Far from the image: nothing to drape.
  store.geoTransform = {100.0, step, 0.0, 10.0, 0.0, -step};
  Result<ImageryWarpGrid> none = imageryGridOnStore(dir / "mercator.tif", store, 1801, 1801);
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("does not overlap"), std::string::npos) << none.error().message;
}

// On the globe: Blue Marble (a JPEG with a world file, no CRS) keeps its own grid, 8192 x 4096
// texels round the whole globe.
TEST(ImageryPyramid, BlueMarbleOnTheGlobeKeepsItsGrid) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<ImageryWarpGrid> grid = imageryGridOnGlobe(data / "bluemarble8k-global/BlueMarbleAlbedo.jpg");
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->width, 8192);
  EXPECT_EQ(grid->height, 4096);
  EXPECT_NEAR(grid->geoTransform[0], -180.0, 1e-9);
  EXPECT_NEAR(grid->geoTransform[3], 90.0, 1e-9);
  EXPECT_NEAR(grid->geoTransform[1], 360.0 / 8192, 1e-12);
}

}  // namespace
}  // namespace tellus
