#pragma once
// Textures for a globe (seed 001, "Globe Textures"): NASA's Blue Marble set (colour,
// altitude, clouds, night lights, water mask; 8192 x 4096 plate carree JPEGs) converted once
// into three cube maps, cached beside the store, so later runs only read them:
//   surface  RGB colour, A water (the specular mask)
//   relief   RGB the bump map, A altitude: the seed processes the elevation map into the
//            weights of the normal, the tangent (east: (-y, x, 0) for a normal (x, y, z)) and
//            the binormal (north) in the latitude/longitude image, before the cube conversion,
//            so that the tangent frame is the one the shader derives from the normal; each
//            weight w stored as w / 2 + 1/2
//   sky      R clouds, G night lights
// The conversion resamples bicubically (cube_map.hpp).
#include <filesystem>

#include "tellus/core/result.hpp"
#include "tellus/dem/cube_map.hpp"

namespace tellus {

struct GlobeTextureOptions {
  int faceSize = 2048;  // cube-map texels a face side (8192 / 4: the source's density at the equator)
  // The bump map's height scale: the altitude map's 0..255 runs over 0..8848 m times this (the
  // seed's Figure 13 bump scaling; at 5 km texels true slopes barely show).
  double bumpScale = 10.0;
};

struct GlobeTextureSet {
  CubeMap surface, relief, sky;
};

// The Blue Marble folder found without being given: $TELLUS_BLUE_MARBLE, else
// ../shared/data/bluemarble8k-global or shared/data/bluemarble8k-global (from the working
// directory) when it holds the set; empty when none does.
std::filesystem::path findBlueMarbleSet();

// The Blue Marble file names in the set's folder.
inline constexpr const char* kBlueMarbleColour = "BlueMarbleAlbedo.jpg";
inline constexpr const char* kBlueMarbleAltitude = "BlueMarbleAltitude.jpg";
inline constexpr const char* kBlueMarbleClouds = "BlueMarbleCloud.jpg";
inline constexpr const char* kBlueMarbleNight = "BlueMarbleGlow.jpg";
inline constexpr const char* kBlueMarbleWater = "BlueMarbleWater.jpg";

// The first `channels` 8-bit bands of a raster covering the whole globe in plate carree (its
// georeferencing, or no georeferencing and a 2:1 shape). Errors name the file: not a raster,
// too few or not 8-bit bands, not the whole globe.
Result<LatLonImage> loadWholeGlobeImage(const std::filesystem::path& path, int channels);

// The seed's bump map from an altitude image (0..255): RGB the normal/tangent/binormal weights
// of the perturbed normal, A the altitude.
LatLonImage bumpMapFromAltitude(const LatLonImage& altitude, double bumpScale);

// The set from the Blue Marble folder `sourceDir`: read from `cacheDir` when it holds a
// conversion of the same files (sizes and times) with the same options, else converted and
// written there (the folder is made; a cache that cannot be written only warns). Errors: a
// missing or unreadable source file.
Result<GlobeTextureSet> loadGlobeTextureSet(const std::filesystem::path& sourceDir,
                                            const std::filesystem::path& cacheDir,
                                            const GlobeTextureOptions& options);

}  // namespace tellus
