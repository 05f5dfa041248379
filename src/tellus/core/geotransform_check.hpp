#pragma once
// Whether a geotransform and a sample spacing mean something (GDAL-free, so the tile store
// reader can use them on untrusted metadata): refused with a reason instead of turned into a
// blank image, a division by zero or a camera path through nowhere.
#include <array>

#include "tellus/core/result.hpp"

namespace tellus {

// Ground distance between samples Tellus accepts, metres: from a micrometre to a quarter of the
// Earth's circumference.
inline constexpr double kMinSampleSpacingM = 1e-6;
inline constexpr double kMaxSampleSpacingM = 1e7;

// A GDAL geotransform of finite numbers whose pixels have an area (not 0 x 0, not collinear);
// when `geographic`, the corners of a `width` x `height` raster at latitudes within [-90, 90]
// (one pixel of tolerance) and longitudes within [-720, 720]. Errors say what is wrong
// ("pixel size 0 x 0", "latitude 1000") without naming the file.
Status checkGeoTransform(const std::array<double, 6>& gt, bool geographic, int width, int height);

// A north-up grid of positive pixel width and negative pixel height, no rotation, every term
// finite (images draped or tiled by latitude and longitude: drapes, imagery, geoid grids,
// global store sources). Errors, without the file's name: "its pixel size is 0 x -0.001: pixels
// need a width above 0 and a negative height (...)", "its geotransform has a non-finite number
// (...)", "it is rotated or sheared (geotransform terms 0.1 and 0)...".
Status checkNorthUpGeoTransform(const std::array<double, 6>& gt);

// True for a north-up grid of cells under a degree whose corners lie within the globe's
// longitudes and latitudes (one degree of tolerance): a raster without a CRS that is so is
// taken as WGS 84 latitude/longitude (SRTM's BIL tiles come without a .prj). False for
// anything else, a grid in metres included (cells of a degree or more, or corners far outside).
bool gridLiesWithinGlobeDegrees(const std::array<double, 6>& gt, int width, int height);

// Both spacings finite and within [kMinSampleSpacingM, kMaxSampleSpacingM].
Status checkSampleSpacing(double spacingXM, double spacingYM);

}  // namespace tellus
