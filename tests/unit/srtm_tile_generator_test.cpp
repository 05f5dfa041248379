// SRTM-like tiles of the procedural planet (dem/srtm_tile_generator.hpp, issue 47's input data):
// SRTM's names, size, byte order and georeferencing as GDAL reads them; shared edges equal
// between neighbours; deterministic per seed; sea at 0 and tiles of open sea left out; voids on
// high ground; and the planet's own grid unchanged by the field it now samples.
#include <algorithm>
#include <fstream>

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include "support/test_support.hpp"
#include "tellus/dem/planet_generator.hpp"
#include "tellus/dem/srtm_tile_generator.hpp"

namespace tellus {
namespace {

TEST(SrtmTiles, NamedAsSrtm) {
  EXPECT_EQ(srtmTileName({37, 127}), "N37E127.hgt");
  EXPECT_EQ(srtmTileName({-5, -71}), "S05W071.hgt");
  EXPECT_EQ(srtmTileName({0, 0}), "N00E000.hgt");
  EXPECT_EQ(srtmTileName({-1, -1}), "S01W001.hgt");
}

TEST(SrtmTiles, ThePlanetGridIsTheFieldAtItsSampleCentres) {
  const PlanetParams params{.columns = 64, .seed = 5, .highestM = 6000.0, .plateau = std::nullopt};
  const HeightGrid grid = generatePlanet(params);
  const PlanetField field(params);
  const double step = 360.0 / 64;
  for (int j = 0; j < grid.height; j += 5) {
    for (int i = 0; i < grid.width; i += 7) {
      EXPECT_EQ(grid.at(i, j), float(field.heightM(90.0 - (j + 0.5) * step, -180.0 + (i + 0.5) * step)));
    }
  }
}

// The first tiles with land of a band across the planet (seed 3, high relief).
struct Found {
  std::vector<SrtmTileId> land;
  int tilesInBox = 0;
};
Found landOf(const PlanetField& field, const LatLonDegreeBox& box) {
  return {srtmLandTiles(field, box), (box.east - box.west) * (box.north - box.south)};
}

TEST(SrtmTiles, NeighboursShareEdgesAndTheSeedDecides) {
  const PlanetField field({.columns = 2160, .seed = 3, .highestM = 9000.0, .plateau = std::nullopt});
  // Land somewhere on the band 30..32 N: find two east-west neighbours with land.
  const Found found = landOf(field, {-180, 30, 180, 32});
  ASSERT_GT(found.land.size(), 2u);
  ASSERT_LT(int(found.land.size()), found.tilesInBox) << "open sea tiles are left out";
  std::optional<std::pair<SrtmTileId, SrtmTileId>> pair;
  for (std::size_t k = 0; k + 1 < found.land.size() && !pair; ++k) {
    if (found.land[k + 1].south == found.land[k].south && found.land[k + 1].west == found.land[k].west + 1) {
      pair = {found.land[k], found.land[k + 1]};
    }
  }
  ASSERT_TRUE(pair);
  constexpr int n = kSrtmTileSamples;
  const std::vector<std::int16_t> a = srtmTileSamples(field, pair->first, 3);
  const std::vector<std::int16_t> b = srtmTileSamples(field, pair->second, 3);
  ASSERT_EQ(a.size(), std::size_t(n) * n);
  for (int row = 0; row < n; ++row) {
    ASSERT_EQ(a[std::size_t(row) * n + (n - 1)], b[std::size_t(row) * n]) << "row " << row;
  }
  // Deterministic; another seed is another planet.
  EXPECT_EQ(srtmTileSamples(field, pair->first, 3), a);
  const PlanetField other({.columns = 2160, .seed = 4, .highestM = 9000.0, .plateau = std::nullopt});
  EXPECT_NE(srtmTileSamples(other, pair->first, 3), a);
  // Heights plausible (voids aside): SRTM has no bathymetry, the sea is 0.
  int lo = 0, hi = 0;
  for (std::int16_t v : a) {
    if (v == kSrtmVoid) continue;
    lo = std::min<int>(lo, v);
    hi = std::max<int>(hi, v);
  }
  EXPECT_GE(lo, -500);
  EXPECT_LE(hi, 8800);
  EXPECT_GT(hi, 0);
}

TEST(SrtmTiles, HighGroundHasVoidsAndGdalReadsTheFileAsSrtm) {
  const PlanetField field({.columns = 2160, .seed = 3, .highestM = 9000.0, .plateau = std::nullopt});
  // A tile reaching above 2,000 m: the field probed on a coarse grid of the band's land tiles.
  const Found found = landOf(field, {-180, 30, 180, 34});
  std::optional<SrtmTileId> high;
  for (const SrtmTileId& t : found.land) {
    for (int j = 0; j <= 10 && !high; ++j) {
      for (int i = 0; i <= 10 && !high; ++i) {
        if (field.heightM(t.south + j / 10.0, t.west + i / 10.0) > 3000.0) high = t;
      }
    }
    if (high) break;
  }
  ASSERT_TRUE(high) << "no mountains on the band";
  const std::vector<std::int16_t> samples = srtmTileSamples(field, *high, 2);
  const auto voids = std::count(samples.begin(), samples.end(), kSrtmVoid);
  EXPECT_GT(voids, 0);
  EXPECT_LT(voids, std::ptrdiff_t(samples.size() / 20));

  const std::filesystem::path dir = test::freshTestDir();
  const std::filesystem::path file = dir / srtmTileName(*high);
  ASSERT_TRUE(writeSrtmTile(file, samples));
  EXPECT_EQ(std::filesystem::file_size(file), std::uintmax_t(kSrtmTileSamples) * kSrtmTileSamples * 2);
  GDALAllRegister();
  GDALDataset* dataset = GDALDataset::FromHandle(GDALOpen(file.c_str(), GA_ReadOnly));
  ASSERT_NE(dataset, nullptr);
  EXPECT_STREQ(dataset->GetDriver()->GetDescription(), "SRTMHGT");
  double gt[6] = {};
  ASSERT_EQ(dataset->GetGeoTransform(gt), CE_None);
  EXPECT_NEAR(gt[0], high->west - 0.5 / 1200.0, 1e-9);
  EXPECT_NEAR(gt[3], high->south + 1 + 0.5 / 1200.0, 1e-9);
  EXPECT_NEAR(gt[1], 1.0 / 1200.0, 1e-12);
  std::vector<std::int16_t> read(samples.size());
  ASSERT_EQ(dataset->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, kSrtmTileSamples, kSrtmTileSamples, read.data(),
                                                kSrtmTileSamples, kSrtmTileSamples, GDT_Int16, 0, 0, nullptr),
            CE_None);
  EXPECT_EQ(read, samples);
  int hasNoData = 0;
  EXPECT_EQ(dataset->GetRasterBand(1)->GetNoDataValue(&hasNoData), double(kSrtmVoid));
  GDALClose(GDALDataset::ToHandle(dataset));
}

}  // namespace
}  // namespace tellus
