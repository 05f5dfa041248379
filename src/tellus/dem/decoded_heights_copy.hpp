#pragma once
// A Float32 copy of an RGB-encoded height raster (Terrain-RGB, Terrarium), for code that hands
// rasters to GDAL itself (the global store's warper): GDAL cannot decode the colours, so they
// are decoded once into a plain GeoTIFF with the same size and georeferencing.
#include <filesystem>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_encoding.hpp"

namespace tellus {

// Writes `output` (a tiled, uncompressed Float32 GeoTIFF, nodata NaN) holding the heights of
// `input` decoded with `encoding`, in metres; transparent pixels (alpha 0) become NaN. The
// input's geotransform and CRS are copied unchanged. Streams a band of rows at a time. On
// failure `output` is removed.
Status writeDecodedHeightsCopy(const std::filesystem::path& input, HeightEncoding encoding,
                               const std::filesystem::path& output);

}  // namespace tellus
