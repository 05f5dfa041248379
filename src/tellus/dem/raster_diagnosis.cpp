#include "tellus/dem/raster_diagnosis.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <regex>
#include <system_error>

#include <fmt/format.h>

namespace tellus {
namespace fs = std::filesystem;

namespace {

// SRTM tiles: 1201 x 1201 (SRTM3, 3 arc-seconds) or 3601 x 3601 (SRTM1) big-endian int16.
constexpr std::uintmax_t kSrtm3Bytes = 1201ull * 1201ull * 2ull;
constexpr std::uintmax_t kSrtm1Bytes = 3601ull * 3601ull * 2ull;

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

// GDAL's SRTMHGT driver takes the tile's position from its name: N37E127.hgt.
bool hasSrtmName(const std::string& filename) {
  static const std::regex pattern(R"([NSns]\d{2}[EWew]\d{3}(\.SRTMGL[13])?\.hgt)",
                                  std::regex::icase);
  return std::regex_match(filename, pattern);
}

std::string explainHgt(const fs::path& path, std::uintmax_t bytes) {
  const std::string name = path.filename().string();
  const bool sizeOk = bytes == kSrtm3Bytes || bytes == kSrtm1Bytes;
  const std::string expected = fmt::format(
      "an SRTM .hgt tile is named after its south-west corner like N37E127.hgt and holds "
      "1201 x 1201 (SRTM3, {} bytes) or 3601 x 3601 (SRTM1, {} bytes) big-endian 16-bit samples",
      kSrtm3Bytes, kSrtm1Bytes);
  if (!hasSrtmName(name) && sizeOk) {
    return fmt::format("{}; this file has the size of a tile but the name '{}' (rename it)",
                       expected, name);
  }
  if (!sizeOk) {
    // Compared with the nearer of the two tile sizes: "1 byte fewer than an SRTM3 tile".
    const bool nearSrtm3 = bytes < (kSrtm3Bytes + kSrtm1Bytes) / 2;
    const std::uintmax_t tile = nearSrtm3 ? kSrtm3Bytes : kSrtm1Bytes;
    const std::uintmax_t difference = bytes > tile ? bytes - tile : tile - bytes;
    return fmt::format("{}; this file is {} bytes, {} {} than an {} tile", expected, bytes,
                       difference, bytes > tile ? "more" : "fewer",
                       nearSrtm3 ? "SRTM3" : "SRTM1");
  }
  return expected;
}

// The first bytes, in hex, for "bytes of no known format".
std::string leadingBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<char, 8> head{};
  in.read(head.data(), head.size());
  std::string hex;
  for (std::streamsize i = 0; i < in.gcount(); ++i) {
    hex += fmt::format("{}{:02x}", hex.empty() ? "" : " ", std::uint8_t(head[std::size_t(i)]));
  }
  return hex;
}

}  // namespace

std::string explainUnreadableRaster(const fs::path& path, const std::string& gdalMessage,
                                    const std::string& expectedKind) {
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (!ec && bytes == 0) return "the file is empty (0 bytes)";
  if (lowercase(path.extension().string()) == ".hgt" && !ec && expectedKind.empty()) {
    return explainHgt(path, bytes);
  }
  const std::string format =
      ec ? std::string("it is not in a raster format GDAL recognises")
         : fmt::format("it is not in a raster format GDAL recognises ({} bytes starting with {})",
                       bytes, leadingBytes(path));
  const std::string expected =
      !expectedKind.empty()
          ? "expected " + expectedKind
          : "expected a DEM such as a GeoTIFF, an SRTM .hgt tile, a BIL/ENVI raster or a 16-bit PNG";
  if (!gdalMessage.empty()) return fmt::format("{} ({}); {}", gdalMessage, format, expected);
  return fmt::format("{}; {}", format, expected);
}

}  // namespace tellus
