// DEM loading on synthetic files whose every sample is known: byte order, voids, nodata
// conventions, scale/offset, CRS and ground spacing, encodings, mosaics, and bad input.
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include "support/test_support.hpp"
#include "tellus/core/geodesy.hpp"
#include "tellus/dem/dem_loader.hpp"

namespace tellus {
namespace {
namespace fs = std::filesystem;

constexpr int kHgtSize = 1201;

// An SRTM3 .hgt file: 1201x1201 big-endian int16, row 0 = north.
void writeHgt(const fs::path& path, const std::function<std::int16_t(int col, int row)>& value) {
  std::ofstream out(path, std::ios::binary);
  for (int row = 0; row < kHgtSize; ++row) {
    for (int col = 0; col < kHgtSize; ++col) {
      const auto v = std::uint16_t(value(col, row));
      const char bytes[2] = {char(v >> 8), char(v & 0xff)};
      out.write(bytes, 2);
    }
  }
}

struct RasterSpec {
  const char* driver = "GTiff";
  GDALDataType type = GDT_Float32;
  int width = 16, height = 16, bands = 1;
  int epsg = 0;  // 0 = no CRS
  std::array<double, 6> geoTransform{};
  bool hasGeoTransform = false;
  std::optional<double> noData;
  std::optional<double> scale, offset;
};

// Writes values (band-sequential doubles, converted to spec.type) through GDAL.
void writeRaster(const fs::path& path, const RasterSpec& spec, const std::vector<double>& values) {
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDataset* ds = mem->Create("", spec.width, spec.height, spec.bands, spec.type, nullptr);
  ASSERT_NE(ds, nullptr);
  if (spec.hasGeoTransform) {
    std::array<double, 6> gt = spec.geoTransform;
    ds->SetGeoTransform(gt.data());
  }
  if (spec.epsg) {
    OGRSpatialReference srs;
    srs.importFromEPSG(spec.epsg);
    ds->SetSpatialRef(&srs);
  }
  const size_t perBand = size_t(spec.width) * size_t(spec.height);
  for (int b = 0; b < spec.bands; ++b) {
    GDALRasterBand* band = ds->GetRasterBand(b + 1);
    if (spec.noData) band->SetNoDataValue(*spec.noData);
    if (spec.scale) band->SetScale(*spec.scale);
    if (spec.offset) band->SetOffset(*spec.offset);
    std::vector<double> bandValues(values.begin() + std::ptrdiff_t(perBand * size_t(b)),
                                   values.begin() + std::ptrdiff_t(perBand * size_t(b + 1)));
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, spec.width, spec.height, bandValues.data(), spec.width,
                             spec.height, GDT_Float64, 0, 0),
              CE_None);
  }
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(spec.driver);
  GDALDataset* copy = driver->CreateCopy(path.c_str(), ds, FALSE, nullptr, nullptr, nullptr);
  ASSERT_NE(copy, nullptr);
  GDALClose(copy);
  GDALClose(ds);
}

std::string loadError(const std::vector<fs::path>& inputs, const DemLoadOptions& options = {}) {
  Result<HeightGrid> grid = loadDem(inputs, options);
  return grid ? std::string("(loaded)") : grid.error().message;
}

TEST(DemLoader, ReadsSrtmHgtBigEndianAndFillsVoids) {
  const fs::path dir = test::freshTestDir();
  const fs::path file = dir / "N10E020.hgt";
  writeHgt(file, [](int col, int row) -> std::int16_t {
    if (col == 5 && row == 7) return 0x0102;  // 258 only if read big-endian (513 if not)
    if ((col == 100 && row == 100) || (col == 600 && row == 601)) return -32768;  // voids
    return std::int16_t(100 + (col + row) % 50);
  });
  Result<HeightGrid> grid = loadDem({file});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->width, kHgtSize);
  EXPECT_EQ(grid->height, kHgtSize);
  EXPECT_FLOAT_EQ(grid->at(5, 7), 258.0f);
  EXPECT_FLOAT_EQ(grid->at(0, 0), 100.0f);
  EXPECT_FLOAT_EQ(grid->at(3, 1), 104.0f);
  EXPECT_EQ(grid->filledVoidCount, 2u);
  // The void takes a value from its surroundings, not -32768.
  EXPECT_GE(grid->at(100, 100), 100.0f);
  EXPECT_LE(grid->at(100, 100), 149.0f);
  EXPECT_GE(grid->heightRange().minM, 100.0f);
  // Geographic CRS, 3 arc-seconds at about 10.5 N: ~92.2 m north-south, ~91.2 m east-west.
  EXPECT_TRUE(grid->georef.isGeographic);
  const double lat = 10.5 * M_PI / 180.0, step = (1.0 / 1200.0) * M_PI / 180.0;
  EXPECT_NEAR(grid->spacingYM, wgs84::northSouthMetres(lat, step), 0.05);
  EXPECT_NEAR(grid->spacingXM, wgs84::eastWestMetres(lat, step), 0.05);
  EXPECT_NEAR(grid->spacingYM, 92.2, 0.3);
  EXPECT_NEAR(grid->spacingXM, 91.2, 0.3);
}

TEST(DemLoader, MosaicsAdjacentTilesSharingAnEdge) {
  const fs::path dir = test::freshTestDir();
  writeHgt(dir / "N10E020.hgt",
           [](int col, int) { return std::int16_t(col == kHgtSize - 1 ? 7 : 1); });
  writeHgt(dir / "N10E021.hgt", [](int col, int) { return std::int16_t(col == 0 ? 7 : 2); });
  Result<HeightGrid> grid = loadDem({dir / "N10E020.hgt", dir / "N10E021.hgt"});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->width, 2 * kHgtSize - 1);  // the shared column appears once
  EXPECT_EQ(grid->height, kHgtSize);
  EXPECT_FLOAT_EQ(grid->at(0, 500), 1.0f);
  EXPECT_FLOAT_EQ(grid->at(kHgtSize - 1, 500), 7.0f);
  EXPECT_FLOAT_EQ(grid->at(kHgtSize, 500), 2.0f);
  EXPECT_FLOAT_EQ(grid->at(2 * kHgtSize - 2, 500), 2.0f);
}

TEST(DemLoader, GeoTiffInt16WithNodataInAProjectedCrsWithNonSquarePixels) {
  const fs::path file = test::freshTestDir() / "utm.tif";
  RasterSpec spec;
  spec.type = GDT_Int16;
  spec.epsg = 32633;  // UTM 33N; scale factor 0.9996 at the central meridian (500 000 E)
  spec.hasGeoTransform = true;
  spec.geoTransform = {499920.0, 10.0, 0.0, 5000000.0, 0.0, -20.0};
  spec.noData = -9999.0;
  std::vector<double> values(256);
  for (size_t i = 0; i < values.size(); ++i) values[i] = double(i);
  values[17] = -9999.0;
  values[200] = -9999.0;
  writeRaster(file, spec, values);
  Result<HeightGrid> grid = loadDem({file});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_FALSE(grid->georef.isGeographic);
  EXPECT_NE(grid->georef.crsName.find("UTM zone 33N"), std::string::npos);
  // Map distances are the ground distances times the scale factor (0.9996 on the meridian).
  EXPECT_NEAR(grid->spacingXM, 10.0 / 0.9996, 0.002);
  EXPECT_NEAR(grid->spacingYM, 20.0 / 0.9996, 0.004);
  EXPECT_EQ(grid->filledVoidCount, 2u);
  EXPECT_FLOAT_EQ(grid->at(3, 2), 35.0f);
  EXPECT_GT(grid->at(1, 1), 0.0f);  // filled from neighbours 1..34
  EXPECT_LT(grid->at(1, 1), 40.0f);
}

TEST(DemLoader, Float32NanAndImplausibleValuesAreVoids) {
  const fs::path file = test::freshTestDir() / "float.tif";
  RasterSpec spec;
  spec.epsg = 4326;
  spec.hasGeoTransform = true;
  spec.geoTransform = {10.0, 0.001, 0.0, 45.0, 0.0, -0.001};
  spec.noData = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> values(256, 500.25);
  values[40] = std::numeric_limits<double>::quiet_NaN();
  values[41] = -3.4e38;  // an undeclared "no data" some tools write
  writeRaster(file, spec, values);
  Result<HeightGrid> grid = loadDem({file});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_EQ(grid->filledVoidCount, 2u);
  EXPECT_FLOAT_EQ(grid->heightRange().minM, 500.25f);
  EXPECT_FLOAT_EQ(grid->heightRange().maxM, 500.25f);
}

TEST(DemLoader, AppliesScaleOffsetAndFeet) {
  const fs::path file = test::freshTestDir() / "scaled.tif";
  RasterSpec spec;
  spec.type = GDT_Int16;
  spec.scale = 0.5;
  spec.offset = 100.0;
  writeRaster(file, spec, std::vector<double>(256, 40.0));
  Result<HeightGrid> grid = loadDem({file});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_FLOAT_EQ(grid->at(4, 4), 120.0f);  // 40 * 0.5 + 100
}

TEST(DemLoader, Reads16BitPngAndHonoursSpacingOverride) {
  const fs::path file = test::freshTestDir() / "heights.png";
  RasterSpec spec;
  spec.driver = "PNG";
  spec.type = GDT_UInt16;
  std::vector<double> values(256);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 60000.0 - double(i) * 3.0;
  writeRaster(file, spec, values);
  Result<HeightGrid> grid = loadDem({file});
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_FLOAT_EQ(grid->at(0, 0), 60000.0f);
  EXPECT_FLOAT_EQ(grid->at(15, 15), 60000.0f - 255.0f * 3.0f);
  EXPECT_DOUBLE_EQ(grid->spacingXM, 1.0);  // no georeferencing
  DemLoadOptions options;
  options.spacingM = 25.0;
  grid = loadDem({file}, options);
  ASSERT_TRUE(grid);
  EXPECT_DOUBLE_EQ(grid->spacingXM, 25.0);
  EXPECT_DOUBLE_EQ(grid->spacingYM, 25.0);
}

TEST(DemLoader, DecodesTerrainRgbAndTerrariumPngs) {
  const fs::path dir = test::freshTestDir();
  RasterSpec spec;
  spec.driver = "PNG";
  spec.type = GDT_Byte;
  spec.bands = 3;
  std::vector<double> rgb(256 * 3);
  for (size_t i = 0; i < 256; ++i) {  // Terrain-RGB 0 m = (1, 134, 160); 305.7 m = (1, 146, 145)
    const bool high = i >= 128;
    rgb[i] = 1;
    rgb[256 + i] = high ? 146 : 134;
    rgb[512 + i] = high ? 145 : 160;
  }
  writeRaster(dir / "rgb.png", spec, rgb);
  DemLoadOptions options;
  options.encoding = HeightEncoding::TerrainRgb;
  Result<HeightGrid> grid = loadDem({dir / "rgb.png"}, options);
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_NEAR(grid->at(0, 0), 0.0f, 1e-3f);
  EXPECT_NEAR(grid->at(0, 15), 305.7f, 1e-3f);
  options.encoding =
      HeightEncoding::Terrarium;  // same pixels read as Terrarium: R*256+G+B/256-32768
  grid = loadDem({dir / "rgb.png"}, options);
  ASSERT_TRUE(grid) << grid.error().message;
  EXPECT_NEAR(grid->at(0, 0), 256.0 + 134.0 + 160.0 / 256.0 - 32768.0, 1e-2);
  // Without --encoding an 8-bit colour image is refused with a hint.
  EXPECT_NE(loadError({dir / "rgb.png"}).find("--encoding"), std::string::npos);
}

TEST(DemLoader, RejectsBadInputWithClearMessages) {
  const fs::path dir = test::freshTestDir();
  EXPECT_NE(loadError({dir / "missing.hgt"}).find("no such file"), std::string::npos);
  EXPECT_NE(loadError({dir}).find("folder"), std::string::npos);
  std::ofstream(dir / "garbage.tif") << "this is not a raster at all";
  const std::string garbage = loadError({dir / "garbage.tif"});
  EXPECT_NE(garbage.find("cannot read"), std::string::npos) << garbage;
  EXPECT_NE(garbage.find("garbage.tif"), std::string::npos) << garbage;
  EXPECT_NE(loadError({}).find("no input"), std::string::npos);

  RasterSpec voidSpec;
  voidSpec.noData = -1.0;
  writeRaster(dir / "void.tif", voidSpec, std::vector<double>(256, -1.0));
  EXPECT_NE(loadError({dir / "void.tif"}).find("no valid samples"), std::string::npos);

  DemLoadOptions badSpacing;
  badSpacing.spacingM = -3.0;
  EXPECT_NE(loadError({dir / "void.tif"}, badSpacing).find("--spacing"), std::string::npos);
}

TEST(DemLoader, TruncatedGeoTiffIsAnErrorNotACrash) {
  const fs::path dir = test::freshTestDir();
  RasterSpec spec;
  spec.width = spec.height = 256;
  writeRaster(dir / "whole.tif", spec, std::vector<double>(256 * 256, 42.0));
  const auto size = fs::file_size(dir / "whole.tif");
  for (const double fraction : {0.9, 0.5, 0.02}) {
    fs::copy_file(dir / "whole.tif", dir / "cut.tif", fs::copy_options::overwrite_existing);
    fs::resize_file(dir / "cut.tif", std::uintmax_t(double(size) * fraction));
    const std::string error = loadError({dir / "cut.tif"});
    EXPECT_NE(error, "(loaded)") << "a file cut to " << fraction << " of its size loaded";
    EXPECT_NE(error.find("cut.tif"), std::string::npos) << error;
  }
}

TEST(DemLoader, RefusesToMosaicIncompatibleInputs) {
  const fs::path dir = test::freshTestDir();
  RasterSpec geographic;
  geographic.epsg = 4326;
  geographic.hasGeoTransform = true;
  geographic.geoTransform = {10.0, 0.001, 0.0, 45.0, 0.0, -0.001};
  writeRaster(dir / "a.tif", geographic, std::vector<double>(256, 1.0));
  RasterSpec utm = geographic;
  utm.epsg = 32633;
  writeRaster(dir / "b.tif", utm, std::vector<double>(256, 1.0));
  RasterSpec plain;
  writeRaster(dir / "c.tif", plain, std::vector<double>(256, 1.0));
  RasterSpec coarser = geographic;
  coarser.geoTransform[1] = 0.002;
  writeRaster(dir / "d.tif", coarser, std::vector<double>(256, 1.0));
  EXPECT_NE(loadError({dir / "a.tif", dir / "b.tif"}).find("different coordinate reference"),
            std::string::npos);
  EXPECT_NE(loadError({dir / "c.tif", dir / "a.tif"}).find("no georeferencing"), std::string::npos);
  EXPECT_NE(loadError({dir / "a.tif", dir / "d.tif"}).find("different sample spacing"),
            std::string::npos);
}

}  // namespace
}  // namespace tellus
