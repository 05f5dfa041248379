#pragma once
// Why a file is not a raster GDAL can read, in words a user can act on: what was expected and
// what was found (an empty file, an SRTM .hgt tile of the wrong size or name, bytes of no
// known format), instead of GDAL's silence or "unknown GDAL error".
#include <filesystem>
#include <string>

namespace tellus {

// `gdalMessage` is GDAL's last error for the failed open (may be empty). The result completes
// "cannot read 'X' as a raster: ...". `expected` says what the file should have been (default:
// a DEM).
std::string explainUnreadableRaster(const std::filesystem::path& path,
                                    const std::string& gdalMessage,
                                    const std::string& expected = {});

}  // namespace tellus
