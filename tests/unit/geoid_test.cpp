// The EGM96 geoid read through GDAL: known values, bilinear between samples, longitudes wrapped
// at the antimeridian, and agreement with PROJ's vgridshift on the same grid; bad grids refused.
#include <cmath>
#include <fstream>
#include <random>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <proj.h>

#include "support/test_support.hpp"
#include "tellus/dem/geoid.hpp"

namespace tellus {
namespace {

std::filesystem::path egm96(const std::filesystem::path& data) {
  return data / "egm96-geoid/egm96_15.gtx";
}

TEST(Geoid, Egm96KnownValues) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<Geoid> geoid = Geoid::load(egm96(data));
  ASSERT_TRUE(geoid) << geoid.error().message;
  EXPECT_EQ(geoid->columns(), 1440);
  EXPECT_EQ(geoid->rows(), 721);
  EXPECT_DOUBLE_EQ(geoid->stepDeg(), 0.25);
  // Samples (gdallocationinfo): (0, 0) 17.1616 m. The grid's extremes: the Indian Ocean low
  // (about -107 m south of Sri Lanka) and the New Guinea high (about +85 m).
  EXPECT_NEAR(geoid->undulationM(0.0, 0.0), 17.1616, 1e-4);
  double lowest = 1e9, highest = -1e9;
  for (double lat = -90.0; lat <= 90.0; lat += 0.25) {
    for (double lon = -180.0; lon < 180.0; lon += 0.25) {
      const double n = geoid->undulationM(lat, lon);
      lowest = std::min(lowest, n);
      highest = std::max(highest, n);
    }
  }
  EXPECT_NEAR(lowest, -106.991, 1e-3);
  EXPECT_NEAR(highest, 85.391, 1e-3);
  // Halfway between samples: the mean of the two; across the antimeridian, continuous.
  const double a = geoid->undulationM(10.0, 20.0), b = geoid->undulationM(10.0, 20.25);
  EXPECT_NEAR(geoid->undulationM(10.0, 20.125), 0.5 * (a + b), 1e-9);
  EXPECT_NEAR(geoid->undulationM(-30.0, 179.999999), geoid->undulationM(-30.0, -180.000001),
              1e-4);
  EXPECT_DOUBLE_EQ(geoid->undulationM(5.0, 190.0), geoid->undulationM(5.0, -170.0));
  EXPECT_DOUBLE_EQ(geoid->ellipsoidalHeightM(1915.0, 35.337, 127.731),
                   1915.0 + geoid->undulationM(35.337, 127.731));
}

TEST(Geoid, AgreesWithProjVgridshift) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<Geoid> geoid = Geoid::load(egm96(data));
  ASSERT_TRUE(geoid);
  PJ_CONTEXT* context = proj_context_create();
  const std::string pipeline =
      "+proj=vgridshift +grids=" + egm96(data).string() + " +multiplier=1";
  PJ* shift = proj_create(context, pipeline.c_str());
  ASSERT_NE(shift, nullptr) << proj_context_errno_string(context, proj_context_errno(context));
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> lat(-89.9, 89.9), lon(-180.0, 180.0);
  double worst = 0.0;
  for (int i = 0; i < 100000; ++i) {
    const double la = lat(random), lo = lon(random);
    const double degree = 3.14159265358979323846 / 180.0;
    const PJ_COORD out = proj_trans(shift, PJ_FWD, proj_coord(lo * degree, la * degree, 0.0, 0.0));
    worst = std::max(worst, std::abs(out.xyz.z - geoid->undulationM(la, lo)));
  }
  proj_destroy(shift);
  proj_context_destroy(context);
  RecordProperty("worst_m", fmt::format("{:.3g}", worst));
  EXPECT_LT(worst, 1e-4);
}

// A grid's undulations in one call are undulationM's, bit for bit, across the antimeridian and
// up to the poles.
TEST(Geoid, GridLookupsEqualPointLookups) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<Geoid> geoid = Geoid::load(egm96(data));
  ASSERT_TRUE(geoid);
  const std::vector<double> lats = {90.0, 89.9, 45.123, 0.0, -12.7, -90.0};
  const std::vector<double> lons = {-180.0, -179.99, 0.0, 127.731, 179.99, 180.0, 190.0};
  std::vector<double> grid(lats.size() * lons.size());
  geoid->undulationsM(lats, lons, grid);
  for (std::size_t j = 0; j < lats.size(); ++j) {
    for (std::size_t i = 0; i < lons.size(); ++i) {
      EXPECT_EQ(grid[j * lons.size() + i], geoid->undulationM(lats[j], lons[i]))
          << lats[j] << ", " << lons[i];
    }
  }
}

TEST(Geoid, RefusesGridsThatAreNotGlobalGeoids) {
  TELLUS_REQUIRE_SHARED_DATA(data);
  Result<Geoid> dem = Geoid::load(data / "srtm3-hgt-east-asia/N37E127.hgt");
  ASSERT_FALSE(dem);
  EXPECT_NE(dem.error().message.find("do not cover the globe"), std::string::npos)
      << dem.error().message;
  Result<Geoid> missing = Geoid::load(data / "egm96-geoid/absent.gtx");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("absent.gtx"), std::string::npos);
}

}  // namespace
}  // namespace tellus
