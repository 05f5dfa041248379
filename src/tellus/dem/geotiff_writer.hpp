#pragma once
// Writes a HeightGrid as a Float32 GeoTIFF (tiled, DEFLATE with the floating-point predictor),
// in metres, with the grid's CRS and geotransform. The file appears atomically.
#include <filesystem>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

Status writeGeoTiff(const HeightGrid& grid, const std::filesystem::path& path);

// Georeferencing for a north-up grid in a projected CRS given by EPSG code, with the north-west
// sample's centre at (westEasting, northNorthing) and square samples of spacingM metres.
Result<GeoReference> projectedGeoReference(int epsg, double westEasting, double northNorthing,
                                           double spacingM);

}  // namespace tellus
