#pragma once
// Heights encoded in the colour channels of 8-bit RGB images (web map elevation tiles).
#include <cstdint>
#include <optional>
#include <string_view>

namespace tellus {

enum class HeightEncoding {
  Plain,       // the first band holds heights directly
  TerrainRgb,  // Mapbox Terrain-RGB: h = -10000 + (R*65536 + G*256 + B) * 0.1
  Terrarium,   // Mapzen Terrarium:   h = (R*256 + G + B/256) - 32768
};

// "plain", "terrain-rgb" or "terrarium"; nullopt for anything else.
std::optional<HeightEncoding> parseHeightEncoding(std::string_view name);
std::string_view heightEncodingName(HeightEncoding encoding);

// Height in metres of one encoded pixel.
double decodeTerrainRgb(std::uint8_t r, std::uint8_t g, std::uint8_t b);
double decodeTerrarium(std::uint8_t r, std::uint8_t g, std::uint8_t b);
// Every height an encoding can express is a multiple of this step, metres (0 for Plain).
double heightEncodingStepM(HeightEncoding encoding);

}  // namespace tellus
