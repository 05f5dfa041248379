#pragma once
// Whether a georeferencing means something: its geotransform (core/geotransform_check.hpp) and
// its CRS, which GDAL must parse. Checked when a DEM is loaded and by `tellus verify` on a
// store's metadata.
#include "tellus/core/geotransform_check.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

// The geotransform of a `width` x `height` raster (when it has one) and the CRS WKT (when
// given), which must parse and agree with georef.isGeographic. Errors say what is wrong
// without naming the file.
Status checkGeoReference(const GeoReference& georef, int width, int height);

}  // namespace tellus
