#include "tellus/dem/georeference_check.hpp"

#include <ogr_spatialref.h>

#include "tellus/dem/gdal_support.hpp"

namespace tellus {

Status checkGeoReference(const GeoReference& georef, int width, int height) {
  if (georef.hasGeoTransform) {
    if (Status gt = checkGeoTransform(georef.geoTransform, georef.isGeographic, width, height);
        !gt) {
      return gt;
    }
  }
  if (georef.crsWkt.empty()) return {};
  gdal::ensureRegistered();
  OGRSpatialReference srs;
  if (srs.importFromWkt(georef.crsWkt.c_str()) != OGRERR_NONE) {
    return makeError("its coordinate reference system is not valid WKT ('{:.40}...')",
                     georef.crsWkt);
  }
  if (bool(srs.IsGeographic()) != georef.isGeographic) {
    return makeError("its CRS is {} but is recorded as {}",
                     srs.IsGeographic() ? "geographic" : "not geographic",
                     georef.isGeographic ? "geographic" : "projected");
  }
  return {};
}

}  // namespace tellus
