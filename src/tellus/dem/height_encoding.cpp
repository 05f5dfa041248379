#include "tellus/dem/height_encoding.hpp"

namespace tellus {

std::optional<HeightEncoding> parseHeightEncoding(std::string_view name) {
  if (name == "plain") return HeightEncoding::Plain;
  if (name == "terrain-rgb") return HeightEncoding::TerrainRgb;
  if (name == "terrarium") return HeightEncoding::Terrarium;
  return std::nullopt;
}

std::string_view heightEncodingName(HeightEncoding encoding) {
  switch (encoding) {
    case HeightEncoding::Plain:
      return "plain";
    case HeightEncoding::TerrainRgb:
      return "terrain-rgb";
    case HeightEncoding::Terrarium:
      return "terrarium";
  }
  return "?";
}

double decodeTerrainRgb(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return -10000.0 + (double(r) * 65536.0 + double(g) * 256.0 + double(b)) * 0.1;
}

double decodeTerrarium(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return (double(r) * 256.0 + double(g) + double(b) / 256.0) - 32768.0;
}

double heightEncodingStepM(HeightEncoding encoding) {
  switch (encoding) {
    case HeightEncoding::TerrainRgb:
      return 0.1;
    case HeightEncoding::Terrarium:
      return 1.0 / 256.0;
    case HeightEncoding::Plain:
      break;
  }
  return 0.0;
}

}  // namespace tellus
