#include "cli/hostile_support.hpp"

#include <fstream>
#include <iterator>

#include <fmt/format.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

namespace tellus {
namespace fs = std::filesystem;

// Runs tellus with a time limit: a hang is a failure (exit status 124), not a stuck suite.
RunResult runBounded(const std::string& arguments, int seconds) {
  return runShell(fmt::format("timeout -s KILL {} '{}' {}", seconds, TELLUS_EXECUTABLE,
                              arguments));
}

// A clean refusal: a status from 1 to 127 (128+ is a signal through the shell, 124/137 a
// timeout), the message part, one line of tellus' own or CLI11's two.
void expectRefused(const RunResult& result, const std::string& messagePart,
                   const std::string& what) {
  EXPECT_GE(result.exitCode, 1) << what << ":\n" << result.output;
  EXPECT_LT(result.exitCode, 124) << what << " ended by a signal or a timeout:\n"
                                  << result.output;
  EXPECT_NE(result.output.find(messagePart), std::string::npos)
      << what << ": expected '" << messagePart << "' in:\n"
      << result.output;
  EXPECT_EQ(result.output.find("terminate called"), std::string::npos) << what;
  EXPECT_EQ(result.output.find("Segmentation"), std::string::npos) << what;
}

std::vector<std::string> filesIn(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string contentOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeText(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

// A small Int16 GeoTIFF with the given geotransform in EPSG:4326 (or no CRS when epsg is 0).
void writeSmallGeoTiff(const fs::path& file, const std::array<double, 6>& gt, int epsg) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = driver->Create(file.c_str(), 33, 33, 1, GDT_Int16, nullptr);
  ASSERT_NE(ds, nullptr);
  std::array<double, 6> copy = gt;
  ds->SetGeoTransform(copy.data());
  if (epsg != 0) {
    OGRSpatialReference srs;
    srs.importFromEPSG(epsg);
    ds->SetSpatialRef(&srs);
  }
  std::vector<std::int16_t> heights(33 * 33);
  for (std::size_t i = 0; i < heights.size(); ++i) heights[i] = std::int16_t(100 + i % 97);
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 33, 33, heights.data(), 33, 33,
                                           GDT_Int16, 0, 0),
            CE_None);
  GDALClose(ds);
}

void writeSparseHugeGeoTiff(const fs::path& file) {
  GDALAllRegister();
  CPLStringList options;
  options.SetNameValue("SPARSE_OK", "YES");
  options.SetNameValue("TILED", "YES");
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(
      file.c_str(), 100000, 100000, 1, GDT_Int16, options.List());
  ASSERT_NE(ds, nullptr);
  std::array<double, 6> gt = {126.0, 1e-5, 0.0, 38.0, 0.0, -1e-5};
  ds->SetGeoTransform(gt.data());
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  ds->SetSpatialRef(&wgs84);
  GDALClose(ds);
}

SmallTerrain makeSmallTerrain(const fs::path& dir) {
  SmallTerrain t{dir / "t.tif", dir / "t.tstore"};
  EXPECT_EQ(runTellus(fmt::format("generate -o {} --size 129", quoted(t.dem))).exitCode, 0);
  EXPECT_EQ(runTellus(fmt::format("build {} -o {} --tile 32", quoted(t.dem), quoted(t.store)))
                .exitCode,
            0);
  return t;
}

}  // namespace tellus
