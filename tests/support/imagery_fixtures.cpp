#include "support/imagery_fixtures.hpp"

#include <vector>

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

namespace tellus::test {

void writeTestImage(const TestImage& image, const std::filesystem::path& path) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  ASSERT_NE(driver, nullptr);
  GDALDataset* dataset = driver->Create(path.c_str(), image.width, image.height, 4, GDT_Byte, nullptr);
  ASSERT_NE(dataset, nullptr) << path;
  double gt[6] = {image.west, image.texelSize, 0.0, image.north, 0.0, -image.texelSize};
  dataset->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(image.epsg);
  dataset->SetSpatialRef(&srs);
  dataset->GetRasterBand(4)->SetColorInterpretation(GCI_AlphaBand);
  std::vector<std::uint8_t> rgba(std::size_t(image.width) * image.height * 4);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::array<std::uint8_t, 4> t = image.texel(x, y);
      std::copy(t.begin(), t.end(), &rgba[(std::size_t(y) * image.width + x) * 4]);
    }
  }
  int bands[4] = {1, 2, 3, 4};
  const CPLErr written = dataset->RasterIO(GF_Write, 0, 0, image.width, image.height, rgba.data(),
                                           image.width, image.height, GDT_Byte, 4, bands, 4,
                                           std::int64_t(image.width) * 4, 1, nullptr);
  GDALClose(GDALDataset::ToHandle(dataset));
  ASSERT_EQ(written, CE_None);
}

std::array<std::uint8_t, 4> testPattern(int x, int y) {
  return {std::uint8_t(x * 7 % 256), std::uint8_t(y * 5 % 256),
          std::uint8_t(((x / 16) + (y / 16)) % 2 ? 230 : 20), 255};
}

}  // namespace tellus::test
