#include "tellus/dem/geotiff_writer.hpp"

#include <cpl_string.h>
#include <ogr_spatialref.h>

#include "tellus/core/atomic_output.hpp"
#include "tellus/dem/gdal_support.hpp"

namespace tellus {

Status writeGeoTiff(const HeightGrid& grid, const std::filesystem::path& path) {
  gdal::ensureRegistered();
  return writeFileAtomically(path, [&](const std::filesystem::path& temp) -> Status {
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver) return makeError("cannot write '{}': GDAL has no GTiff driver", path.string());
    CPLStringList options;
    options.SetNameValue("TILED", "YES");
    options.SetNameValue("COMPRESS", "DEFLATE");
    options.SetNameValue("PREDICTOR", "3");
    options.SetNameValue("BIGTIFF", "IF_SAFER");
    gdal::DatasetPtr dataset(
        driver->Create(temp.c_str(), grid.width, grid.height, 1, GDT_Float32, options.List()));
    if (!dataset) return makeError("cannot write '{}': {}", path.string(), gdal::lastError());
    if (grid.georef.hasGeoTransform) {
      std::array<double, 6> gt = grid.georef.geoTransform;
      dataset->SetGeoTransform(gt.data());
    }
    if (!grid.georef.crsWkt.empty()) dataset->SetProjection(grid.georef.crsWkt.c_str());
    GDALRasterBand* band = dataset->GetRasterBand(1);
    band->SetUnitType("m");
    if (band->RasterIO(GF_Write, 0, 0, grid.width, grid.height,
                       const_cast<float*>(grid.heights.data()), grid.width, grid.height,
                       GDT_Float32, 0, 0) != CE_None) {
      return makeError("cannot write '{}': {}", path.string(), gdal::lastError());
    }
    CPLErrorReset();
    dataset.reset();  // flushes and closes
    if (CPLGetLastErrorType() >= CE_Failure) {
      return makeError("cannot write '{}': {}", path.string(), gdal::lastError());
    }
    return {};
  });
}

Result<GeoReference> projectedGeoReference(int epsg, double westEasting, double northNorthing,
                                           double spacingM) {
  gdal::ensureRegistered();
  OGRSpatialReference srs;
  if (srs.importFromEPSG(epsg) != OGRERR_NONE) return makeError("unknown EPSG code {}", epsg);
  GeoReference georef;
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  georef.crsWkt = wkt ? wkt : "";
  CPLFree(wkt);
  georef.crsName = srs.GetName() ? srs.GetName() : "";
  georef.hasGeoTransform = true;
  // Pixel-is-area: the top-left corner lies half a sample up and left of the first centre.
  georef.geoTransform = {westEasting - 0.5 * spacingM,   spacingM, 0.0,
                         northNorthing + 0.5 * spacingM, 0.0,      -spacingM};
  return georef;
}

}  // namespace tellus
