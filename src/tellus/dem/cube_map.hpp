#pragma once
// Cube maps of the globe (seed 001, "Using Cubemaps as Globe Textures"): latitude/longitude
// images resampled once onto the six faces of a cube, looked up on the GPU by a direction (no
// singularity at the poles, texels spread evenly). Each texel's direction is read as a
// geodetic normal: latitude asin(z), longitude atan2(y, x); the source is sampled there
// bicubically (Catmull-Rom), as the seed does in its preprocessing. Faces follow OpenGL's
// cube-map layout (GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, row 0 first).
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace tellus {

// An 8-bit image of the whole globe in plate carree: column 0 starts at -180 degrees, row 0 at
// 90 degrees north, pixel-is-area.
struct LatLonImage {
  int width = 0, height = 0, channels = 0;
  std::vector<std::uint8_t> pixels;  // width * height * channels, row-major
};

struct CubeMap {
  int size = 0;      // texels a face side
  int channels = 0;  // 1 to 4, 8 bits each
  std::array<std::vector<std::uint8_t>, 6> faces;  // size * size * channels each
};

// The unit direction through texel (column, row) of `face` (0..5: +X, -X, +Y, -Y, +Z, -Z).
glm::dvec3 cubeTexelDirection(int face, int size, double column, double row);

// The source resampled onto faces of `size` texels. Errors: none (an empty source gives zeros).
CubeMap latLonToCubeMap(const LatLonImage& source, int size);

// The cube map's value (0..255, channel `channel`) in direction `direction`, bilinear within the
// face, as a GPU would sample it (without seamless filtering across faces).
double sampleCubeMap(const CubeMap& cube, const glm::dvec3& direction, int channel);

// The source's value at (latDeg, lonDeg), bicubic as the conversion reads it (for tests).
double sampleLatLonBicubic(const LatLonImage& image, double latDeg, double lonDeg, int channel);

}  // namespace tellus
