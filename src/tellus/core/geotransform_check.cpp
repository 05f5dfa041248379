#include "tellus/core/geotransform_check.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tellus {

Status checkGeoTransform(const std::array<double, 6>& gt, bool geographic, int width,
                         int height) {
  for (double v : gt) {
    if (!std::isfinite(v)) {
      return makeError("its geotransform has a non-finite number ({}, {}, {}, {}, {}, {})", gt[0],
                       gt[1], gt[2], gt[3], gt[4], gt[5]);
    }
  }
  const double scale =
      std::max({std::abs(gt[1]), std::abs(gt[2]), std::abs(gt[4]), std::abs(gt[5])});
  const double area = gt[1] * gt[5] - gt[2] * gt[4];
  if (!(scale > 0.0) || !(std::abs(area) > 1e-12 * scale * scale)) {
    return makeError("its pixels have no area (pixel size {} x {}, rotation {} and {})", gt[1],
                     gt[5], gt[2], gt[4]);
  }
  if (!geographic) return {};
  const double tolerance = std::abs(gt[4]) + std::abs(gt[5]) + 1e-9;  // a pixel
  for (const auto& [col, row] :
       {std::pair{0.0, 0.0}, std::pair{double(width), 0.0}, std::pair{0.0, double(height)},
        std::pair{double(width), double(height)}}) {
    const double lon = gt[0] + col * gt[1] + row * gt[2];
    const double lat = gt[3] + col * gt[4] + row * gt[5];
    if (!(std::abs(lat) <= 90.0 + tolerance)) {
      return makeError("a corner lies at latitude {}, outside -90..90 degrees", lat);
    }
    if (!(std::abs(lon) <= 720.0)) {
      return makeError("a corner lies at longitude {}, outside -720..720 degrees", lon);
    }
  }
  return {};
}

bool gridLiesWithinGlobeDegrees(const std::array<double, 6>& gt, int width, int height) {
  if (!checkNorthUpGeoTransform(gt)) return false;
  const double east = gt[0] + width * gt[1];
  const double south = gt[3] + height * gt[5];
  return gt[1] < 1.0 && -gt[5] < 1.0 && gt[0] >= -181.0 && east <= 181.0 && south >= -91.0 &&
         gt[3] <= 91.0;
}

Status checkNorthUpGeoTransform(const std::array<double, 6>& gt) {
  for (double v : gt) {
    if (!std::isfinite(v)) {
      return makeError("its geotransform has a non-finite number ({}, {}, {}, {}, {}, {})", gt[0],
                       gt[1], gt[2], gt[3], gt[4], gt[5]);
    }
  }
  if (gt[2] != 0.0 || gt[4] != 0.0) {
    return makeError("it is rotated or sheared (geotransform terms {} and {}); a north-up grid "
                     "has none",
                     gt[2], gt[4]);
  }
  if (!(gt[1] > 0.0) || !(gt[5] < 0.0)) {
    return makeError("its pixel size is {} x {}: pixels need a width above 0 and a negative "
                     "height (rows running north to south)",
                     gt[1], gt[5]);
  }
  return {};
}

Status checkSampleSpacing(double spacingXM, double spacingYM) {
  for (double spacing : {spacingXM, spacingYM}) {
    if (!(std::isfinite(spacing) && spacing >= kMinSampleSpacingM &&
          spacing <= kMaxSampleSpacingM)) {
      return makeError("its sample spacing {} x {} m is outside {} to {} m", spacingXM, spacingYM,
                       kMinSampleSpacingM, kMaxSampleSpacingM);
    }
  }
  return {};
}

}  // namespace tellus
