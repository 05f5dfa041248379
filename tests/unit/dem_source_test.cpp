// DemSource: streaming reads equal the whole-grid loader, void filling on disk (the path
// large inputs take) gives the same heights as in memory, leaving no scratch files behind, and
// filling on read (the pyramid builder's way) equals filling block by block after a scan, or
// gives up where that cannot work.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include "support/test_support.hpp"
#include "tellus/dem/dem_loader.hpp"
#include "tellus/dem/dem_source.hpp"
#include "tellus/tiles/pyramid_builder.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

std::vector<float> readAll(DemSource& source, int rowsPerRead) {
  const DemSourceInfo& info = source.info();
  std::vector<float> all(std::size_t(info.width) * std::size_t(info.height));
  for (int row = 0; row < info.height; row += rowsPerRead) {
    const int count = std::min(rowsPerRead, info.height - row);
    std::span<float> rows(all.data() + std::size_t(row) * std::size_t(info.width),
                          std::size_t(count) * std::size_t(info.width));
    EXPECT_TRUE(source.readRows(row, count, rows));
  }
  return all;
}

TEST(DemSource, FillsVoidsOnDiskLikeInMemory) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path hgt = data / "srtm3-hgt-east-asia/N37E127.hgt";  // 5 voids
  Result<HeightGrid> loaded = loadDem({hgt});
  ASSERT_TRUE(loaded);
  const fs::path scratch = test::freshTestDir();
  Result<std::unique_ptr<DemSource>> source = DemSource::open({hgt});
  ASSERT_TRUE(source);
  EXPECT_EQ(source.value()->info().heightStepM, 1.0);
  Result<std::size_t> voids = source.value()->fillVoids(scratch, /*inMemorySamples=*/0);
  ASSERT_TRUE(voids) << voids.error().message;
  EXPECT_EQ(voids.value(), loaded->filledVoidCount);
  EXPECT_FALSE(fs::is_empty(scratch)) << "the scratch copy should be on disk";
  const std::vector<float> streamed = readAll(*source.value(), 97);
  ASSERT_EQ(streamed.size(), loaded->heights.size());
  for (std::size_t i = 0; i < streamed.size(); ++i) {
    ASSERT_NEAR(streamed[i], loaded->heights[i], 1e-3f) << "sample " << i;
  }
  EXPECT_FALSE(source.value()->readRows(1200, 2, std::span<float>()));  // outside the grid
  source.value().reset();
  EXPECT_TRUE(fs::is_empty(scratch)) << "scratch files left behind";
}

// A float GeoTIFF of width x height samples, 30 m apart (EPSG:32652), NaN where `isVoid`.
fs::path writeFloatDem(const fs::path& path, int width, int height,
                       const std::function<bool(int col, int row)>& isVoid) {
  GDALAllRegister();
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = gtiff->Create(path.c_str(), width, height, 1, GDT_Float32, nullptr);
  EXPECT_NE(ds, nullptr);
  std::array<double, 6> gt{300000.0, 30.0, 0.0, 4000000.0, 0.0, -30.0};
  ds->SetGeoTransform(gt.data());
  OGRSpatialReference utm;
  utm.importFromEPSG(32652);
  ds->SetSpatialRef(&utm);
  std::vector<float> values(std::size_t(width) * std::size_t(height));
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      values[std::size_t(row) * std::size_t(width) + std::size_t(col)] =
          isVoid(col, row) ? std::numeric_limits<float>::quiet_NaN()
                           : float(100.0 + 0.25 * col + 0.5 * row + 20.0 * std::sin(col * 0.05));
    }
  }
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, width, height, values.data(), width,
                                           height, GDT_Float32, 0, 0),
            CE_None);
  GDALClose(ds);
  return path;
}

// Reads every row, `rowsPerRead` at a time; false as soon as a read fails.
bool readAllOrFail(DemSource& source, int rowsPerRead) {
  const DemSourceInfo& info = source.info();
  std::vector<float> rows;
  for (int row = 0; row < info.height; row += rowsPerRead) {
    const int count = std::min(rowsPerRead, info.height - row);
    rows.resize(std::size_t(count) * std::size_t(info.width));
    if (!source.readRows(row, count, rows)) return false;
  }
  return true;
}

TEST(DemSource, FillsVoidsOnReadLikeBlockByBlockAfterAScan) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path hgt = data / "srtm3-hgt-east-asia/N37E127.hgt";  // 5 voids
  Result<std::unique_ptr<DemSource>> scanned = DemSource::open({hgt});
  Result<std::unique_ptr<DemSource>> onRead = DemSource::open({hgt});
  ASSERT_TRUE(scanned && onRead);
  Result<std::size_t> voids = scanned.value()->fillVoids(test::freshTestDir());
  ASSERT_TRUE(voids) << voids.error().message;
  EXPECT_EQ(voids.value(), 5u);
  onRead.value()->fillVoidsOnRead();
  // Rows read in bands that share their edge rows, as the pyramid builder reads them.
  const std::vector<float> expected = readAll(*scanned.value(), 97);
  const DemSourceInfo& info = onRead.value()->info();
  std::vector<float> got(expected.size());
  for (int row = 0; row + 1 < info.height; row += 64) {
    const int count = std::min(65, info.height - row);
    std::span<float> rows(got.data() + std::size_t(row) * std::size_t(info.width),
                          std::size_t(count) * std::size_t(info.width));
    ASSERT_TRUE(onRead.value()->readRows(row, count, rows));
  }
  for (std::size_t i = 0; i < got.size(); ++i) {
    ASSERT_FALSE(std::isnan(got[i])) << "sample " << i;
    ASSERT_EQ(got[i], expected[i]) << "sample " << i;
  }
  EXPECT_EQ(onRead.value()->filledVoidCount(), 5u);
  EXPECT_FALSE(onRead.value()->voidFillingOnReadGaveUp());
}

TEST(DemSource, FillOnReadGivesUpOnAVoidOutOfReach) {
  // A void of 780 x 600 samples along the north edge: block (2, 0) and its 256-sample margin,
  // columns [256, 1024) and rows [0, 512), see no data at all.
  const fs::path file =
      writeFloatDem(test::freshTestDir() / "lake.tif", 1100, 800,
                    [](int c, int r) { return c >= 250 && c < 1030 && r < 600; });
  Result<std::unique_ptr<DemSource>> source = DemSource::open({file});
  ASSERT_TRUE(source);
  source.value()->fillVoidsOnRead();
  EXPECT_FALSE(readAllOrFail(*source.value(), 64));
  EXPECT_TRUE(source.value()->voidFillingOnReadGaveUp());
}

TEST(DemSource, FillOnReadGivesUpOnTooManyVoids) {
  // Every other sample void: half the grid, more than the quarter filled block by block.
  const fs::path file = writeFloatDem(test::freshTestDir() / "sieve.tif", 300, 300,
                                      [](int c, int r) { return (c + r) % 2 == 1; });
  Result<std::unique_ptr<DemSource>> source = DemSource::open({file});
  ASSERT_TRUE(source);
  source.value()->fillVoidsOnRead();
  EXPECT_FALSE(readAllOrFail(*source.value(), 300));
  EXPECT_TRUE(source.value()->voidFillingOnReadGaveUp());
}

TEST(DemSource, TheBuilderStartsAgainWithTheWholeFillWhenFillOnReadGivesUp) {
  const fs::path dir = test::freshTestDir();
  const fs::path file = writeFloatDem(dir / "sieve.tif", 300, 300,
                                      [](int c, int r) { return (c + r) % 2 == 1; });
  Result<BuildReport> built = buildPyramid({file}, dir / "sieve.tstore", {});
  ASSERT_TRUE(built) << built.error().message;
  EXPECT_EQ(built->metadata.filledVoidCount, 300u * 300u / 2u);
  Result<std::shared_ptr<TileStore>> store = TileStore::open(dir / "sieve.tstore");
  ASSERT_TRUE(store) << store.error().message;
  EXPECT_EQ(store.value()->metadata().filledVoidCount, 300u * 300u / 2u);
  // The filled heights lie within the data's range (a plane, a ramp and a sine).
  EXPECT_GE(store.value()->metadata().minHeightM, 79.9);
  EXPECT_LE(store.value()->metadata().maxHeightM, 345.1);
  // Nothing of the abandoned first attempt is left beside the store.
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path().filename());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<fs::path>{"sieve.tif", "sieve.tstore"}));
}

}  // namespace
}  // namespace tellus

namespace tellus {
namespace {

// A float GeoTIFF of 1201 x 1201 samples with geotransform `gt` and no CRS at all.
fs::path writeDemWithoutCrs(const fs::path& path, const std::array<double, 6>& gt) {
  GDALAllRegister();
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = gtiff->Create(path.c_str(), 1201, 1201, 1, GDT_Float32, nullptr);
  EXPECT_NE(ds, nullptr);
  ds->SetGeoTransform(const_cast<double*>(gt.data()));
  std::vector<float> values(1201 * 1201, 250.0f);
  EXPECT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 1201, 1201, values.data(), 1201, 1201,
                                           GDT_Float32, 0, 0),
            CE_None);
  GDALClose(ds);
  return path;
}

// SRTM's BIL tiles come without a .prj: a grid of sub-degree cells within the globe's degrees
// is WGS 84 latitude/longitude, placed at its true ground size (3 arc-seconds: about 92 m
// east-west at 16.5 N), never 1201 samples 0.00083 "metres" apart.
TEST(DemSource, AGridInDegreesWithoutACrsIsTakenAsWgs84) {
  const fs::path dir = test::freshTestDir();
  const double step = 1.0 / 1200.0;
  const fs::path degrees = writeDemWithoutCrs(dir / "degrees.tif",
                                              {-62.0 - step / 2, step, 0.0, 17.0 + step / 2, 0.0, -step});
  auto source = DemSource::open({degrees});
  ASSERT_TRUE(source) << source.error().message;
  const DemSourceInfo& info = source.value()->info();
  EXPECT_TRUE(info.georef.isGeographic);
  EXPECT_NE(info.georef.crsName.find("WGS 84"), std::string::npos) << info.georef.crsName;
  EXPECT_NEAR(info.spacingXM, 88.9, 0.5);  // 111.32 km * cos(16.5 deg) / 1200
  EXPECT_NEAR(info.spacingYM, 92.3, 0.5);

  // Cells of 30 (metres, surely): still the pixel size as metres, as before.
  const fs::path metres = writeDemWithoutCrs(dir / "metres.tif", {0.0, 30.0, 0.0, 36030.0, 0.0, -30.0});
  auto inMetres = DemSource::open({metres});
  ASSERT_TRUE(inMetres) << inMetres.error().message;
  EXPECT_FALSE(inMetres.value()->info().georef.isGeographic);
  EXPECT_DOUBLE_EQ(inMetres.value()->info().spacingXM, 30.0);
}

TEST(DemSource, TheSrtmBilTilesOfGuadeloupeHaveTheirTrueGroundSize) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  const fs::path bil = data / "srtm3-bil-guadeloupe/n16_w062_3arc_v2.bil";
  auto source = DemSource::open({bil});
  ASSERT_TRUE(source) << source.error().message;
  const DemSourceInfo& info = source.value()->info();
  EXPECT_TRUE(info.georef.isGeographic);
  EXPECT_GT(info.spacingXM, 85.0);
  EXPECT_LT(info.spacingXM, 95.0);
  EXPECT_GT(info.spacingYM, 90.0);
  EXPECT_LT(info.spacingYM, 95.0);
}

}  // namespace
}  // namespace tellus
